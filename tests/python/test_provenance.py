"""Outputs that say where they came from (docs/cli.md "Metadata", docs/python.md "Saving and loading"): the
effective scene that hubbeam run --print-scene prints, checked against the scene files read by Python's own TOML
reader and round-tripped; the metadata beside run, modes and linearize outputs; Result.save and hubbeam.load. Needs
HUBBEAM and SOURCE_DIR."""
import glob
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import tomllib
import unittest

import numpy as np

import hubbeam

HUBBEAM = os.environ["HUBBEAM"]
SOURCE = os.environ["SOURCE_DIR"]
CASES = sorted(glob.glob(os.path.join(SOURCE, "cases", "*.toml")))


def cli(*args, cwd=None):
    done = subprocess.run([HUBBEAM, *args], capture_output=True, text=True, cwd=cwd)
    if done.returncode != 0:
        raise AssertionError(f"hubbeam {' '.join(args)}: exit {done.returncode}: {done.stderr}")
    return done.stdout


def printed(scene, *options, cwd=None):
    return cli("run", scene, "--print-scene", *options, cwd=cwd)


class EffectiveScene(unittest.TestCase):
    def test_every_value_the_file_gives_is_printed_as_given(self):
        # An independent reader (tomllib) of the original file against the printed scene: every key the file sets
        # is there with its value (a table's file as the same file, from anywhere).
        for scene in CASES:
            with self.subTest(scene=os.path.basename(scene)):
                with open(scene, "rb") as f:
                    given = tomllib.load(f)
                effective = tomllib.loads(printed(scene))
                for table, keys in given.items():
                    for key, value in keys.items():
                        got = effective[table][key]
                        if key in ("file", "profile", "blade_file") and table in ("motion", "beam"):
                            self.assertTrue(os.path.isabs(got))
                            self.assertTrue(os.path.samefile(got, os.path.join(os.path.dirname(scene), value)))
                        elif isinstance(value, str):
                            self.assertEqual(got, value, f"{table}.{key}")
                        elif isinstance(value, list):
                            self.assertEqual([float(x) for x in got], [float(x) for x in value], f"{table}.{key}")
                        else:
                            self.assertEqual(float(got), float(value), f"{table}.{key}")

    def test_every_key_is_printed_by_some_scene_with_its_defaults(self):
        keys = set()
        for scene in CASES:
            effective = tomllib.loads(printed(scene))
            keys |= {f"{t}.{k}" for t, table in effective.items() for k in table}
        self.assertEqual(keys, set(hubbeam.scene_keys()))
        # A default the file leaves out is the one docs/scene.md gives.
        plain = tomllib.loads(printed(os.path.join(SOURCE, "cases", "spinup_omega4.toml")))
        self.assertEqual(plain["solver"]["max_steps"], 10000000)
        self.assertEqual(plain["beam"]["second_moment_flap"], plain["beam"]["second_moment"])
        self.assertEqual(plain["output"]["file"], "spinup_omega4.csv")

    def test_printed_scene_reads_back_to_the_same_text_from_another_folder(self):
        with tempfile.TemporaryDirectory() as d:
            for scene in CASES:
                with self.subTest(scene=os.path.basename(scene)):
                    text = printed(scene, "--ny", "6", "--t-end", "1.5")
                    copy = os.path.join(d, "copy.toml")
                    with open(copy, "w") as f:
                        f.write(text)
                    self.assertEqual(printed(copy, cwd=d), text)
                    self.assertEqual(hubbeam.effective_scene(copy), text)

    def test_a_run_of_the_printed_scene_writes_the_same_bytes(self):
        # A spin-up, a table drive, a controlled hub with gravity along the axis and damping, a blade with a profile.
        with tempfile.TemporaryDirectory() as d:
            for name in ("spinup_omega4", "table_spinup", "controlled_step", "helicopter_blade", "profile_blade"):
                with self.subTest(scene=name):
                    scene = os.path.join(SOURCE, "cases", f"{name}.toml")
                    copy = os.path.join(d, f"{name}-effective.toml")
                    with open(copy, "w") as f:
                        f.write(printed(scene, "--t-end", "0.5"))
                    cli("run", scene, "--t-end", "0.5", "-o", os.path.join(d, "a.csv"))
                    cli("run", copy, "-o", os.path.join(d, "b.csv"))
                    with open(os.path.join(d, "a.csv"), "rb") as a, open(os.path.join(d, "b.csv"), "rb") as b:
                        self.assertEqual(a.read(), b.read())


class Metadata(unittest.TestCase):
    def test_run_metadata_describes_its_output(self):
        scene = os.path.join(SOURCE, "cases", "table_spinup.toml")
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "run.csv")
            stdout = cli("run", scene, "--t-end", "1", "--rtol", "1e-9", "--fields-at", "0.5", "-o", out)
            with open(out + ".hubbeam.json") as f:
                meta = json.load(f)
            with open(out) as f:
                lines = f.read().splitlines()
            self.assertEqual(meta["format"], "hubbeam-metadata 1")
            self.assertEqual(meta["hubbeam_version"], hubbeam.__version__)
            self.assertEqual(meta["generator_version"], hubbeam.generator_version())
            self.assertEqual((meta["output"], meta["fields"]), ("run.csv", "run-fields.csv"))
            self.assertEqual(meta["columns"], lines[0].split(","))
            self.assertEqual(meta["rows"], len(lines) - 1)
            self.assertEqual(meta["solver"]["rtol"], 1e-9)
            self.assertEqual(meta["scene"]["solver"]["rtol"], 1e-9)
            self.assertEqual(meta["scene"]["output"]["t_end"], 1)
            self.assertIn(f"stepper     {meta['summary']['stepper']} ", stdout)
            self.assertEqual(meta["summary"]["summary_text"], stdout[:len(meta["summary"]["summary_text"])])
            # The table by its content: hashed here by hashlib, not by hubbeam's own SHA-256.
            table = os.path.join(SOURCE, "cases", "table_spinup.csv")
            with open(table, "rb") as f:
                digest = hashlib.sha256(f.read()).hexdigest()
            self.assertEqual(meta["tables"]["motion.file"]["sha256"], digest)
            self.assertTrue(os.path.samefile(meta["tables"]["motion.file"]["path"], table))

    def test_modes_and_linearize_metadata(self):
        scene = os.path.join(SOURCE, "cases", "controlled_step.toml")
        with tempfile.TemporaryDirectory() as d:
            cli("modes", scene, "--omega", "0,1", "-q", "-o", os.path.join(d, "m.csv"))
            with open(os.path.join(d, "m.csv.hubbeam.json")) as f:
                meta = json.load(f)
            with open(os.path.join(d, "m.csv")) as f:
                rows = len(f.read().splitlines()) - 1
            self.assertEqual((meta["command"], meta["omega"], meta["rows"]), ("modes", [0, 1], rows))
            self.assertEqual(meta["variants"], [hubbeam.modes(scene, 0.0)["variant"]])
            cli("linearize", scene, "--omega", "0", "-o", os.path.join(d, "lin"))
            with open(os.path.join(d, "lin.hubbeam.json")) as f:
                meta = json.load(f)
            npz = np.load(os.path.join(d, "lin.npz"))
            self.assertEqual(meta["states"], list(npz["states"]))
            self.assertIn("lin-open.npz", meta["files"])
            self.assertEqual(meta["scene"]["control"]["kp"], tomllib.load(open(scene, "rb"))["control"]["kp"])

    def test_metadata_is_never_written_over_an_input(self):
        with tempfile.TemporaryDirectory() as d:
            # A scene whose name is what the output's metadata would be called.
            scene = os.path.join(d, "y.csv.hubbeam.json")
            with open(scene, "w") as f:
                f.write(printed(os.path.join(SOURCE, "cases", "spinup_omega4.toml")))
            with open(scene) as f:
                before = f.read()
            done = subprocess.run([HUBBEAM, "run", scene, "-o", os.path.join(d, "y.csv")], capture_output=True,
                                  text=True)
            self.assertEqual(done.returncode, 2)
            self.assertIn("-o's metadata: expected a file other than the scene itself", done.stderr)
            with open(scene) as f:
                self.assertEqual(f.read(), before)
            self.assertFalse(os.path.exists(os.path.join(d, "y.csv")))


class SaveAndLoad(unittest.TestCase):
    SCENE = os.path.join(SOURCE, "cases", "controlled_step.toml")

    def test_saved_rows_load_back_as_the_run(self):
        r = hubbeam.run(self.SCENE, t_end=3)
        with tempfile.TemporaryDirectory() as d:
            for name in ("r.csv", "r.npy"):
                with self.subTest(file=name):
                    path = r.save(os.path.join(d, name))
                    back = hubbeam.load(path)
                    self.assertTrue(np.array_equal(back.data, r.data))
                    self.assertEqual(back.columns, r.columns)
                    for k in ("variant", "stepper", "completed", "steps", "estimated_error", "jacobi_drift",
                              "max_abs_tip_uy", "wall_seconds"):
                        self.assertEqual(getattr(back, k), getattr(r, k), k)
                    self.assertEqual(back.summary_text, r.summary_text)
                    self.assertTrue(np.array_equal(back.tau, r.tau))
                    self.assertEqual(list(back.to_pandas().columns), list(r.columns))

    def test_saved_csv_is_the_command_lines(self):
        r = hubbeam.run(self.SCENE, t_end=3)
        with tempfile.TemporaryDirectory() as d:
            cli("run", self.SCENE, "--t-end", "3", "-o", os.path.join(d, "cli.csv"))
            r.save(os.path.join(d, "py.csv"))
            with open(os.path.join(d, "cli.csv"), "rb") as a, open(os.path.join(d, "py.csv"), "rb") as b:
                self.assertEqual(a.read(), b.read())
            back = hubbeam.load(os.path.join(d, "cli.csv"))  # the command line's output, read by Python
            self.assertTrue(np.array_equal(back.data, r.data))
            with open(os.path.join(d, "cli.csv.hubbeam.json")) as f:
                self.assertEqual(back.estimated_error, float(json.load(f)["summary"]["estimated_error"]))

    def test_a_changed_or_unexplained_file_is_refused(self):
        r = hubbeam.run(self.SCENE, t_end=1)
        with tempfile.TemporaryDirectory() as d:
            path = r.save(os.path.join(d, "r.csv"))
            with open(path, "a") as f:
                f.write(",".join(["0"] * len(r.columns)) + "\n")
            with self.assertRaisesRegex(ValueError, "changed or replaced after its metadata"):
                hubbeam.load(path)
            os.remove(path + ".hubbeam.json")
            with self.assertRaisesRegex(FileNotFoundError, "r.csv.hubbeam.json: not found"):
                hubbeam.load(path)
            cli("modes", self.SCENE, "--omega", "0", "-q", "-o", os.path.join(d, "m.csv"))
            with self.assertRaisesRegex(ValueError, r"m.csv.hubbeam.json: command: expected \"run\" \(hubbeam.load reads "
                                                    r"the metadata of a run\)$"):
                hubbeam.load(os.path.join(d, "m.csv"))

    def test_save_refuses_what_hubbeam_run_refuses(self):
        r = hubbeam.run(self.SCENE, t_end=1)
        with tempfile.TemporaryDirectory() as d:
            target = os.path.join(d, "kept.csv")
            with open(target, "w") as f:
                f.write("mine\n")
            os.chmod(target, 0o444)
            with self.assertRaisesRegex(ValueError, "read-only"):
                r.save(target)
            with open(target) as f:
                self.assertEqual(f.read(), "mine\n")
            with self.assertRaisesRegex(ValueError, "ending in .csv or .npy"):
                r.save(os.path.join(d, "r.txt"))

    def test_save_never_replaces_a_file_the_run_read(self):
        # The scene itself (through a hard link named .csv), its profile, its blade file (through a hard link) and its
        # motion table, for every file key of the core's key table: refused as hubbeam run refuses them, naming the
        # key, every file as it was; also from a Result loaded back, whose metadata names the same files.
        self.assertEqual(set(hubbeam.file_keys()), set(SCENE_SETTING), "a file key with no scene in SCENE_SETTING")
        with tempfile.TemporaryDirectory() as d:
            for key, (scene_name, file_name) in SCENE_SETTING.items():
                with self.subTest(key=key):
                    for name in (scene_name, file_name):
                        shutil.copy(os.path.join(SOURCE, "cases", name), d)
                    scene, file = os.path.join(d, scene_name), os.path.join(d, file_name)
                    r = hubbeam.run(scene, t_end=0.05, source="assembled")
                    target = file if file.endswith(".csv") else os.path.join(d, key + ".csv")
                    if target != file:
                        os.link(file, target)
                    scene_link = os.path.join(d, "scene-" + key + ".csv")
                    os.link(scene, scene_link)
                    before = {f: lines_of(f) for f in (scene, file)}
                    back = hubbeam.load(r.save(os.path.join(d, key + "-saved.csv")))
                    for result in (r, back):
                        with self.assertRaisesRegex(ValueError, f": expected a file other than the scene's {key}, "):
                            result.save(target)
                        with self.assertRaisesRegex(ValueError, "expected a file other than the scene itself, "):
                            result.save(scene_link)
                        for f, content in before.items():
                            self.assertEqual(lines_of(f), content, f)
                        self.assertFalse(os.path.exists(target + ".hubbeam.json"))


def lines_of(path):
    with open(path, "rb") as f:
        return f.read()


# For each file key of the scene's schema, a scene of cases/ that sets it and the file it names there.
SCENE_SETTING = {"beam.profile": ("profile_blade.toml", "profile_blade.csv"),
                 "beam.blade_file": ("blade_from_file.toml", "blade_sections.dat"),
                 "motion.file": ("table_spinup.toml", "table_spinup.csv")}


class LoadTrust(unittest.TestCase):
    """hubbeam.load on files someone else may have written: every problem is a ValueError naming the file and the
    line, column or key, never quoting the file; a FIFO is refused without being opened; no name in the file replaces
    one of Result's own attributes."""

    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.TemporaryDirectory()
        cls.r = hubbeam.run(os.path.join(SOURCE, "cases", "spinup_omega4.toml"), t_end=0.1, nx=0)
        cls.path = cls.r.save(os.path.join(cls.dir.name, "r.csv"))
        with open(cls.path + ".hubbeam.json") as f:
            cls.meta = json.load(f)

    @classmethod
    def tearDownClass(cls):
        cls.dir.cleanup()

    def planted(self, name, meta=None, csv=None, raw=None):
        """A copy of the run as NAME.csv with its metadata changed (meta, a dict, or raw, bytes) or its CSV (csv)."""
        path = os.path.join(self.dir.name, name + ".csv")
        with open(path, "wb") as f:
            f.write(lines_of(self.path) if csv is None else csv)
        with open(path + ".hubbeam.json", "wb") as f:
            f.write(raw if raw is not None else json.dumps(self.meta if meta is None else meta).encode())
        return path

    def refused(self, path, pattern):
        with self.assertRaises(ValueError) as caught:
            hubbeam.load(path)
        self.assertIs(type(caught.exception), ValueError)
        message = str(caught.exception)
        self.assertRegex(message, pattern)
        self.assertNotIn("hunter2", message)
        self.assertEqual(len(message.splitlines()), 1, message)
        return message

    def test_a_csv_cell_is_never_quoted(self):
        good = lines_of(self.path).decode().split("\n")
        cells = good[3].split(",")
        cells[2] = "hunter2"
        path = self.planted("cell", csv="\n".join(good[:3] + [",".join(cells)] + good[4:]).encode())
        self.refused(path, r"cell.csv: line 4, column 3: expected a number$")
        path = self.planted("short", csv="\n".join(good[:2] + ["1,hunter2"] + good[3:]).encode())
        self.refused(path, rf"short.csv: line 3: expected {len(self.r.columns)} fields, got 2$")
        path = self.planted("bytes", csv=lines_of(self.path) + b"\xffhunter2\n")
        self.refused(path, r"bytes.csv: expected a run's CSV \(UTF-8 text\), got bytes that are not text at byte \d+$")
        # A header of the secret: said to be another header, not quoted.
        path = self.planted("header", csv=b"hunter2" + lines_of(self.path)[lines_of(self.path).index(b"\n"):])
        self.refused(path, r"header.csv: expected the rows and columns that .*header.csv.hubbeam.json describes, got "
                           r"another header")

    def test_a_fifo_is_refused_without_being_opened(self):
        # Opening a FIFO blocks until a writer comes: the load runs in a child with a deadline.
        for which in ("sidecar", "csv"):
            with self.subTest(which=which), tempfile.TemporaryDirectory() as d:
                path = os.path.join(d, "f.csv")
                shutil.copy(self.path, path)
                shutil.copy(self.path + ".hubbeam.json", path + ".hubbeam.json")
                fifo = path + ".hubbeam.json" if which == "sidecar" else path
                os.remove(fifo)
                os.mkfifo(fifo)
                code = ("import hubbeam\ntry:\n    hubbeam.load(%r)\nexcept ValueError as e:\n    print(e)\n" % path)
                done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
                self.assertEqual(done.returncode, 0, done.stderr)
                self.assertRegex(done.stdout, rf"^{re.escape(fifo)}: expected .* \(a regular file\), got a FIFO\n$")

    def test_tampered_metadata_raises_valueerror_naming_the_key(self):
        meta, summary = self.meta, self.meta["summary"]
        deep = b"[" * 100000 + b"]" * 100000
        cases = {
            "not_json": (None, b"{\"format\": hunter2", r"line 1, column 12: expected hubbeam's metadata \(JSON\)$"),
            "not_text": (None, b"\xff\xfehunter2", r"expected hubbeam's metadata \(UTF-8 text\), got bytes that are "
                                                 r"not text at byte 0$"),
            "deep": (None, deep, r"nested too deeply$"),
            "deep_object": (None, b'{"a":' * 50000 + b"1" + b"}" * 50000, r"nested too deeply|: format: expected"),
            "huge": (None, b" " * (2 << 20), r"expected hubbeam's metadata of at most 1024 KB, got a larger file$"),
            "list": ([meta], None, r": format: expected"),
            "string": ("hunter2", None, r": format: expected"),
            "format": (dict(meta, format="hunter2"), None, r": format: expected \"hubbeam-metadata 1\""),
            "format_list": (dict(meta, format=["hubbeam-metadata 1"]), None, r": format: expected"),
            "command": (dict(meta, command="hunter2"), None, r": command: expected \"run\""),
            "command_dict": (dict(meta, command={"run": 1}), None, r": command: expected \"run\""),
            "no_columns": ({k: v for k, v in meta.items() if k != "columns"}, None, r": columns: expected a list"),
            "columns_text": (dict(meta, columns="t,theta"), None, r": columns: expected a list"),
            "columns_numbers": (dict(meta, columns=[1, 2]), None, r": columns: expected a list"),
            "columns_twice": (dict(meta, columns=["t", "t"]), None, r": columns: expected a list of column names, each"),
            "columns_empty": (dict(meta, columns=[]), None, r": columns: expected a list"),
            "columns_no_t": (dict(meta, columns=meta["columns"][1:] + ["x"]), None,
                             r": columns: expected a list of column names, the first t$"),
            "no_rows": ({k: v for k, v in meta.items() if k != "rows"}, None, r": rows: expected a number of rows"),
            "rows_text": (dict(meta, rows="3"), None, r": rows: expected a number of rows"),
            "rows_bool": (dict(meta, rows=True), None, r": rows: expected a number of rows"),
            "rows_negative": (dict(meta, rows=-1), None, r": rows: expected a number of rows"),
            "rows_float": (dict(meta, rows=3.5), None, r": rows: expected a number of rows"),
            "rows_wrong": (dict(meta, rows=meta["rows"] + 1), None, r"changed or replaced after its metadata"),
            "scene_file": (dict(meta, scene_file=7), None, r": scene_file: expected"),
            "no_scene_file": ({k: v for k, v in meta.items() if k != "scene_file"}, None, r": scene_file: expected"),
            "tables": (dict(meta, tables=[1]), None, r": tables: expected"),
            "tables_path": (dict(meta, tables={"motion.file": {"path": 3}}), None, r": tables: expected"),
            "no_summary": ({k: v for k, v in meta.items() if k != "summary"}, None, r": summary: expected a table"),
            "summary_list": (dict(meta, summary=[summary]), None, r": summary: expected a table"),
            "summary_missing": (dict(meta, summary={k: v for k, v in summary.items() if k != "t_reached"}), None,
                                r": summary.t_reached: expected a value \(the key is missing\)$"),
            "no_summary_text": (dict(meta, summary={k: v for k, v in summary.items() if k != "summary_text"}), None,
                                r": summary.summary_text: expected a value"),
            "number_text": (dict(meta, summary=dict(summary, t_reached="hunter2")), None,
                            r": summary.t_reached: expected a number"),
            "number_list": (dict(meta, summary=dict(summary, max_abs_tip_uy=[1])), None,
                            r": summary.max_abs_tip_uy: expected a number"),
            "number_bool": (dict(meta, summary=dict(summary, wall_seconds=True)), None,
                            r": summary.wall_seconds: expected a number"),
            "text_number": (dict(meta, summary=dict(summary, variant=3)), None, r": summary.variant: expected a text"),
            "failure_none": (dict(meta, summary=dict(summary, failure=None)), None, r": summary.failure: expected a text"),
            "completed_text": (dict(meta, summary=dict(summary, completed="yes")), None,
                               r": summary.completed: expected true or false"),
            "steps_float": (dict(meta, summary=dict(summary, steps=1.5)), None, r": summary.steps: expected an integer"),
            "other_dict": (dict(meta, summary=dict(summary, extra={"a": 1})), None,
                           r": summary.extra: expected a number, a text or a boolean"),
        }
        for name, (changed, raw, pattern) in cases.items():
            with self.subTest(case=name):
                self.refused(self.planted(name, meta=changed, raw=raw), rf"^.*{name}.csv.hubbeam.json{pattern}"
                             if pattern.startswith(":") else pattern)

    def test_no_name_in_the_file_replaces_an_attribute_of_result(self):
        # A summary key or a column named as one of Result's attributes or methods: refused, naming the key; the
        # Result of a good file keeps save and plot as methods.
        summary = self.meta["summary"]
        for name in ("save", "plot", "data", "columns", "to_pandas", "summary", "metadata", "inputs", "__class__"):
            with self.subTest(summary_key=name):
                path = self.planted("shadow_" + name.strip("_"), meta=dict(self.meta, summary=dict(summary, **{name: "x"})))
                self.refused(path, rf"json: {re.escape(name)}: expected a summary value or column name that is none of "
                                   rf"Result's own attributes")
        columns = list(self.meta["columns"])
        columns[2] = "save"
        good = lines_of(self.path).decode().split("\n", 1)
        path = self.planted("shadow_column", meta=dict(self.meta, columns=columns),
                            csv=(",".join(columns) + "\n" + good[1]).encode())
        self.refused(path, r"json: save: expected a summary value or column name that is none of")
        columns[2] = "variant"
        path = self.planted("column_and_summary", meta=dict(self.meta, columns=columns),
                            csv=(",".join(columns) + "\n" + good[1]).encode())
        self.refused(path, r"json: variant: expected a name that is a column or a summary value, not both")
        back = hubbeam.load(self.path)
        self.assertTrue(callable(back.save) and callable(back.plot))
        self.assertTrue(np.array_equal(back.data, self.r.data))


if __name__ == "__main__":
    unittest.main()
