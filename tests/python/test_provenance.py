"""Outputs that say where they came from (docs/cli.md "Metadata", docs/python.md "Saving and loading"): the
effective scene that hubbeam run --print-scene prints, checked against the scene files read by Python's own TOML
reader and round-tripped; the metadata beside run, modes and linearize outputs; Result.save and hubbeam.load. Needs
HUBBEAM and SOURCE_DIR."""
import glob
import hashlib
import json
import os
import subprocess
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
            with self.assertRaisesRegex(ValueError, "expected the metadata of a run, got that of 'modes'"):
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


if __name__ == "__main__":
    unittest.main()
