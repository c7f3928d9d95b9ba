"""Sweeps on one local Dask cluster of 2 worker threads shared by the tests: the same table as sequential runs,
typed values, a failing point reported while the rest finish, resume without recomputation and past a cut last
line, tip series in files, a full disk, the command line over TLS with certificate files, bad input that leaves
every file as it was, the files a sweep reads (never its table, which is never more readable than they are), stale
rows of a changed scene, paths relative to the sweep file, Python isolated from the current folder, and signals.
Needs HUBBEAM and SOURCE_DIR."""
import csv
import os
import re
import resource
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import unittest

import math

import numpy as np

import hubbeam
from hubbeam import sweeps

HUBBEAM = os.environ["HUBBEAM"]
SOURCE = os.environ["SOURCE_DIR"]
SPINUP = os.path.join(SOURCE, "cases", "spinup_omega4.toml")
KEEP = ["max_abs_tip_uy", "relative_drift", "steps", "variant", "frequencies"]

# 20 points: 4 methods x Ny 4, 6 x two spin rates, and 4 explicit points, one of them bad (FEM needs an even Ny).
SWEEP = f"""
scene = "{SPINUP}"
keep = {KEEP!r}
frequencies = 2

[set]
"output.t_end" = 2.0

[grid]
method = ["amm", "fem", "bim", "bsim"]
ny = [4, 6]
omega0 = [4.0, 2.0]

[[points]]
method = "fem"
ny = 5

[[points]]
method = "amm"
ny = 8
nx = 0

[[points]]
method = "bsim"
ny = 5
rtol = 1e-10

[[points]]
"discretization.method" = "bim"
ny = 9
"""

CLIENT = CLOSE = None
CERTS = {}


def setUpModule():
    # One secured local cluster for every sweep of this file; the command line reaches it over TLS with its files.
    global CLIENT, CLOSE
    CLIENT, CLOSE = sweeps.local_cluster(2)
    folder = tempfile.mkdtemp()
    security = CLIENT.security
    for option, pem in [("--tls-ca-file", security.tls_ca_file), ("--tls-cert", security.tls_client_cert),
                        ("--tls-key", security.tls_client_key)]:
        path = os.path.join(folder, option.strip("-") + ".pem")
        with open(path, "w", opener=lambda p, f: os.open(p, f, 0o600)) as f:
            f.write(pem)
        CERTS[option] = path
    CERTS["folder"] = folder


def tearDownModule():
    CLOSE()
    shutil.rmtree(CERTS["folder"])


def tls_options():
    return ["--scheduler", CLIENT.scheduler.address] + [w for o in ("--tls-ca-file", "--tls-cert", "--tls-key")
                                                         for w in (o, CERTS[o])]


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def lines_of(path):
    with open(path, "rb") as f:
        return f.read()


def cli_all(*commands, limit=None):
    """Every command line at once (each is a Python process of its own: starting them together saves time)."""
    def preexec():
        if limit is not None:
            resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    children = [subprocess.Popen([HUBBEAM, "sweep", *c], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                 preexec_fn=preexec) for c in commands]
    return [(c.wait(timeout=120), c.communicate()[1]) for c in children]


class SweepTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.TemporaryDirectory()
        cls.spec = os.path.join(cls.dir.name, "study.toml")
        with open(cls.spec, "w") as f:
            f.write(SWEEP)
        cls.table_path = os.path.join(cls.dir.name, "study.csv")
        cls.table = hubbeam.sweep(cls.spec, output=cls.table_path, scheduler=CLIENT, progress=False)

    def copy_of_table(self, name, rows):
        """The table with its header and its first `rows` rows, as a new file."""
        with open(self.table_path) as f:
            lines = f.readlines()
        path = os.path.join(self.dir.name, name)
        with open(path, "w") as f:
            f.writelines(lines[:rows + 1])
        return path, lines

    def test_twenty_points_equal_sequential_runs_with_typed_values(self):
        points = sweeps.expand(sweeps.load_sweep(self.spec))
        self.assertEqual(len(points), 20)
        self.assertEqual(len(self.table), 20)
        written = {r["point"]: r for r in read(self.table_path)}
        with open(SPINUP) as f:
            scene_text = f.read()
        for point, row in zip(points, self.table):
            alone = sweeps.run_point(scene_text, SPINUP, point, KEEP, 2)
            for key in ("status", "max_abs_tip_uy", "relative_drift", "steps", "variant", "f1_hz", "f2_hz"):
                # Returned as the run's own value and type (a float is a float, not its text), written as its repr.
                self.assertEqual(row[key], alone.get(key), f"{point}: {key}")
                self.assertIs(type(row[key]), type(alone.get(key)), f"{point}: {key}")
                self.assertEqual(written[row["point"]][key], "" if alone.get(key) is None else
                                 (repr(alone[key]) if isinstance(alone[key], float) else str(alone[key])))
            for key, value in point.items():
                self.assertEqual(row[key], value)
            if row["status"] == "ok":
                self.assertIsInstance(row["steps"], int)
                self.assertIsInstance(row["max_abs_tip_uy"], float)

    def test_frequencies_are_the_cantilevers_in_hz(self):
        # Physics, not the sweep's own run_point: at t_end = 2 s the spin-up has reached a few hundredths of a rad/s,
        # so the first two bending frequencies are the clamped cantilever's, (1.87510407, 4.69409113)^2
        # sqrt(EI / (rho S L^4)) / (2 pi), within each discretization's error at these Ny (below 1 %; FEM at Ny = 4
        # is 0.85 % high in the second). A column filled with rad/s would be 2 pi off.
        import tomllib
        with open(SPINUP, "rb") as f:
            beam = tomllib.load(f)["beam"]
        unit = math.sqrt(beam["youngs_modulus"] * beam["second_moment"] /
                         (beam["density"] * beam["area"] * beam["length"] ** 4))
        exact = [z * z * unit / (2 * math.pi) for z in (1.87510407, 4.69409113)]
        ok = [r for r in self.table if r["status"] == "ok"]
        self.assertGreater(len(ok), 15)
        for r in ok:
            for i, f_exact in enumerate(exact):
                self.assertAlmostEqual(r[f"f{i + 1}_hz"] / f_exact, 1.0, delta=0.01, msg=f"{r['point']}: f{i + 1}_hz")

    def test_a_failing_point_is_a_row_and_the_rest_finish(self):
        bad = [r for r in self.table if r["status"] != "ok"]
        self.assertEqual(len(bad), 1)
        self.assertEqual(bad[0]["discretization.ny"], 5)
        self.assertIn("FEM needs an even ny", bad[0]["status"])
        self.assertIsNone(bad[0]["max_abs_tip_uy"])
        self.assertEqual(sum(r["status"] == "ok" for r in self.table), 19)

    def test_resume_skips_finished_points(self):
        # Keep the header and 15 rows: a rerun computes the 5 missing points only, and keeps the 15 as they were.
        partial, _ = self.copy_of_table("partial.csv", 15)
        kept = {r["point"]: r for r in read(partial)}
        for row in kept.values():
            row["run_seconds"] = "-1"  # a value no run writes: recomputed rows would not have it
        with open(partial, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(read(self.table_path)[0].keys()), lineterminator="\n")
            w.writeheader()
            w.writerows(kept.values())
        table = hubbeam.sweep(self.spec, output=partial, scheduler=CLIENT, progress=False)
        self.assertEqual(len(table), 20)
        self.assertEqual(sum(r["run_seconds"] == -1.0 for r in table), 15)
        self.assertEqual(len(read(partial)), 20)

    def test_a_cut_last_line_is_dropped_and_its_point_recomputed_once(self):
        # The table as a full disk or a kill leaves it: 12 rows and the 13th cut mid-line, without its newline.
        path, lines = self.copy_of_table("cut.csv", 12)
        with open(path, "a") as f:
            f.write(lines[13][:len(lines[13]) // 2])
        fields = len(lines[0].split(","))
        for _ in range(2):  # the second resume finds every point and changes nothing
            table = hubbeam.sweep(self.spec, output=path, scheduler=CLIENT, progress=False)
            self.assertEqual(len(table), 20)
            text = lines_of(path).decode()
            self.assertTrue(text.endswith("\n"))
            rows = list(csv.reader(text.splitlines()))
            self.assertEqual(len(rows), 21)
            self.assertTrue(all(len(r) == fields for r in rows), [len(r) for r in rows])
            self.assertEqual(len({r[0] for r in rows[1:]}), 20)  # every point once
        self.assertEqual(sorted(r["point"] for r in table), sorted(r["point"] for r in self.table))

    def test_the_command_line_over_tls_with_certificate_files(self):
        # A secured remote scheduler: the shared cluster, reached with its CA, certificate and key as files.
        path, _ = self.copy_of_table("remote.csv", 17)
        [(code, err)] = cli_all([self.spec, "-o", path, *tls_options()])
        self.assertEqual(code, 0, err)
        self.assertNotIn("warning", err)
        self.assertEqual(len(read(path)), 20)
        # The same from Python: the address and security=, a distributed.security.Security; without it, refused.
        path, _ = self.copy_of_table("remote_python.csv", 19)
        table = hubbeam.sweep(self.spec, output=path, scheduler=CLIENT.scheduler.address, security=CLIENT.security,
                              progress=False)
        self.assertEqual(len(table), 20)
        with self.assertRaises(sweeps.SweepError) as caught:
            hubbeam.sweep(self.spec, output=path + ".x", scheduler=CLIENT.scheduler.address, progress=False)
        self.assertIn("certificates", str(caught.exception))

    def small_sweep(self, name):
        """A sweep of 4 short points and its complete table."""
        spec = os.path.join(self.dir.name, name + ".toml")
        with open(spec, "w") as f:
            f.write(f'scene = "{SPINUP}"\nkeep = ["max_abs_tip_uy", "steps"]\n[set]\nnx = 0\n"output.t_end" = 2.0\n'
                    f'[grid]\nny = [4, 6]\nomega0 = [4.0, 2.0]\n')
        table = os.path.join(self.dir.name, name + ".csv")
        hubbeam.sweep(spec, output=table, scheduler=CLIENT, progress=False)
        return spec, table

    def test_a_full_disk_leaves_whole_lines_and_the_old_table(self):
        # RLIMIT_FSIZE stands in for a full disk: writes past it fail (EFBIG) as they would with ENOSPC.
        spec, old = self.small_sweep("small")
        with open(old) as f:
            lines = f.readlines()
        limit = len(lines[0]) + len(max(lines[1:], key=len)) * 3 // 2
        fresh = os.path.join(self.dir.name, "full.csv")
        before = lines_of(old)
        [(code, err), (code_replace, err_replace)] = cli_all([spec, "-o", fresh, *tls_options()],
                                                             [spec, "-o", old, "--no-resume", *tls_options()],
                                                             limit=limit)
        self.assertEqual(code, 2, err)
        err = [line for line in err.splitlines() if not line.startswith("sweep: ")]  # the progress lines
        self.assertEqual(len(err), 1, err)
        self.assertIn("cannot write the table", err[0])
        text = lines_of(fresh).decode()
        self.assertTrue(text.endswith("\n"), text)  # no cut line
        self.assertGreaterEqual(len(text.splitlines()), 2)
        # --no-resume wrote its new table beside the old one: the old table is whole, and no temporary file is left.
        self.assertEqual(code_replace, 2, err_replace)
        self.assertEqual(lines_of(old), before)
        self.assertEqual(leftovers(self.dir.name), [])
        # The resume completes the table: every point once, every line whole.
        table = hubbeam.sweep(spec, output=fresh, scheduler=CLIENT, progress=False)
        self.assertEqual(len(table), 4)
        self.assertEqual(len({r["point"] for r in read(fresh)}), 4)
        self.assertEqual(len(read(fresh)), 4)

    def test_no_resume_replaces_the_table_once_complete(self):
        spec, path = self.small_sweep("replace")
        rows = read(path)
        for r in rows:
            r["run_seconds"] = "-1"
        with open(path, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0].keys()), lineterminator="\n")
            w.writeheader()
            w.writerows(rows)
        table = hubbeam.sweep(spec, output=path, scheduler=CLIENT, progress=False, resume=False)
        self.assertEqual(len(table), 4)
        self.assertFalse(any(r["run_seconds"] == -1.0 for r in table))
        self.assertEqual(len(read(path)), 4)


class TipSeriesTest(unittest.TestCase):
    def test_a_tip_series_is_an_array_in_a_file_of_its_own_and_resumes(self):
        with tempfile.TemporaryDirectory() as d:
            spec = {"scene": SPINUP, "set": {"output.t_end": 30.0, "output.dt_out": 0.01, "nx": 0},
                    "grid": {"ny": [4, 5]}, "keep": ["tip_series", "max_abs_tip_uy"]}
            out = os.path.join(d, "series.csv")
            table = hubbeam.sweep(spec, output=out, scheduler=CLIENT, progress=False)
            for row in table:
                direct = hubbeam.run(SPINUP, t_end=30.0, nx=0, ny=row["discretization.ny"])
                self.assertIsInstance(row["tip_series"], np.ndarray)
                self.assertEqual(row["tip_series"].shape, (3001, 2))
                self.assertTrue(np.array_equal(row["tip_series"][:, 0], direct.t))
                self.assertTrue(np.array_equal(row["tip_series"][:, 1], direct.tip_uy))
            # The cell names the point's file beside the table; the table stays a table of short lines.
            for row in read(out):
                self.assertEqual(row["tip_series"], os.path.join("series.series", row["point"] + ".npy"))
            self.assertLess(max(len(line) for line in lines_of(out).splitlines()), 300)
            again = hubbeam.sweep(spec, output=out, scheduler=CLIENT, progress=False)
            self.assertEqual([r["run_seconds"] for r in again], [r["run_seconds"] for r in table])  # not recomputed
            self.assertTrue(np.array_equal(again[1]["tip_series"], table[1]["tip_series"]))
            # A series file gone: that point alone runs again.
            os.remove(os.path.join(d, "series.series", table[0]["point"] + ".npy"))
            third = hubbeam.sweep(spec, output=out, scheduler=CLIENT, progress=False)
            self.assertTrue(np.array_equal(third[0]["tip_series"], table[0]["tip_series"]))
            self.assertEqual(third[1]["run_seconds"], table[1]["run_seconds"])
            self.assertEqual(len(read(out)), 2)  # the resumed point's new row replaces its old one


class LockTest(unittest.TestCase):
    def test_a_table_another_hubbeam_writes_is_refused(self):
        # Every hubbeam writer holds DIR/.NAME.lock (flock) while it writes NAME: a sweep onto a table that another
        # sweep or command is writing exits 2 with one line, and leaves the table as it was.
        import fcntl
        with tempfile.TemporaryDirectory() as d:
            spec = os.path.join(d, "s.toml")
            with open(spec, "w") as f:
                f.write(f'scene = "{SPINUP}"\n[set]\n"output.t_end" = 0.1\n')
            table = os.path.join(d, "table.csv")
            with open(table, "w") as f:
                f.write("a table being written\n")
            with open(os.path.join(d, ".table.csv.lock"), "w") as held:
                fcntl.flock(held, fcntl.LOCK_EX)
                (code, err), = cli_all([spec, "-o", table, "--no-resume"])
            self.assertEqual(code, 2, err)
            self.assertIn("another hubbeam is writing", err)
            self.assertEqual(lines_of(table), b"a table being written\n")


class BadInputTest(unittest.TestCase):
    def test_bad_input_is_one_line_and_leaves_every_file_as_it_was(self):
        with tempfile.TemporaryDirectory() as d:
            scene = os.path.join(d, "scene.toml")
            shutil.copy(SPINUP, scene)
            alias = os.path.join(d, "alias.toml")
            os.link(scene, alias)  # another name of the scene's file: compared as a file, not a name
            spec = os.path.join(d, "s.toml")
            with open(spec, "w") as f:
                f.write(f'scene = "{scene}"\n[grid]\nny = [4, 6]\n')
            broken = os.path.join(d, "broken.toml")
            with open(broken, "w") as f:
                f.write("[beam]\nlength = -8.0\n")
            bad_scene = os.path.join(d, "bad_base.toml")
            with open(bad_scene, "w") as f:
                f.write(f'scene = "{broken}"\n')
            nul = os.path.join(d, "nul.toml")
            with open(nul, "w") as f:
                f.write(f'scene = "{scene}"\noutput = "a\\u0000b.csv"\n')
            shady = os.path.join(d, "shady.toml")
            with open(shady, "w") as f:
                f.write(f'scene = "{scene}"\n[set]\n"ny\\u001b[31m\\u202e" = 4\n')
            table = os.path.join(d, "table.csv")
            with open(table, "w") as f:
                f.write("a table that must survive\n")
            binary = os.path.join(d, "binary.csv")
            with open(binary, "wb") as f:
                f.write(bytes(range(256)))
            with socket.socket() as s:  # a port nothing listens on
                s.bind(("127.0.0.1", 0))
                port = s.getsockname()[1]
            unreachable = os.path.join(d, "unreachable.csv")
            files = {p: lines_of(p) for p in (scene, spec, table, binary)}
            cases = [
                ([bad_scene, "-o", table, "--no-resume"], "broken.toml"),  # the base scene is checked first
                ([spec, "-o", alias, "--no-resume"], "same file"),
                ([spec, "-o", spec, "--no-resume"], "same file"),
                ([spec, "-o", d], "got a directory"),
                ([spec, "-o", ""], "--output: expected a file name"),
                ([nul], "output: expected a file name"),
                ([shady], "\\x1b[31m\\u202e"),
                ([spec, "-o", binary], "binary.csv: expected this sweep's CSV table"),
                ([spec, "-o", unreachable, "--scheduler", f"tcp://127.0.0.1:{port}"], "cannot reach"),
                ([spec, "-o", unreachable + "-tls", "--scheduler", f"tls://127.0.0.1:{port}"], "certificates"),
            ]
            start = time.perf_counter()
            results = cli_all(*(c for c, _ in cases))
            self.assertLess(time.perf_counter() - start, 60)
            for (command, expected), (code, err) in zip(cases, results):
                self.assertEqual(code, 2, f"{command}: {err}")
                lines = [line for line in err.strip().splitlines() if not line.startswith("hubbeam: warning:")]
                self.assertEqual(len(lines), 1, f"{command}: {err}")
                self.assertIn(expected, lines[0], command)
                self.assertNotIn("\x1b", err)
                self.assertNotIn("\u202e", err)
            for path, content in files.items():
                self.assertEqual(lines_of(path), content, path)
            self.assertFalse(os.path.exists(unreachable))  # no header-only table
            self.assertIn("runs whatever any client", results[-2][1])  # a plain tcp:// scheduler is named unsafe
            self.assertEqual(leftovers(d), [])


def write(path, text, mode=None):
    with open(path, "w") as f:
        f.write(text)
    if mode is not None:
        os.chmod(path, mode)
    return path


def leftovers(folder):
    """The lock and temporary files a writer leaves beside its table while it writes (none once it has ended)."""
    return sorted(n for n in os.listdir(folder) if n.endswith(".lock") or ".tmp-" in n or n.endswith(".partial"))


class InputsTest(unittest.TestCase):
    """Every file a sweep reads is an input: its table is never one of them, and never more readable than they are."""

    def test_the_table_is_none_of_the_files_the_sweep_reads(self):
        # The sweep file, its scene, the scene's profile and the points' motion tables; by name, as a hard link, and
        # as the file a point reads through a symbolic link: refused in one line, exit 2, every file as it was.
        with tempfile.TemporaryDirectory() as d:
            for name in ("profile_blade.toml", "profile_blade.csv", "table_spinup.csv"):
                shutil.copy(os.path.join(SOURCE, "cases", name), d)
            shutil.copy(os.path.join(SOURCE, "cases", "table_spinup.csv"), os.path.join(d, "drive.csv"))
            os.symlink("drive.csv", os.path.join(d, "drive_link.csv"))
            os.link(os.path.join(d, "table_spinup.csv"), os.path.join(d, "table_hard.csv"))
            spec = write(os.path.join(d, "s.toml"), 'scene = "profile_blade.toml"\n[set]\n"output.t_end" = 0.1\n'
                         '"motion.kind" = "table"\n[[points]]\n"motion.file" = "table_spinup.csv"\n'
                         '[[points]]\n"motion.file" = "drive_link.csv"\n')
            files = {n: lines_of(os.path.join(d, n)) for n in os.listdir(d) if not os.path.islink(os.path.join(d, n))}
            targets = ["s.toml", "profile_blade.toml", "profile_blade.csv", "table_spinup.csv", "table_hard.csv",
                       "drive.csv"]
            results = cli_all(*([spec, "-o", os.path.join(d, t), "--no-resume"] for t in targets))
            for target, (code, err) in zip(targets, results):
                self.assertEqual(code, 2, f"{target}: {err}")
                self.assertEqual(len(err.strip().splitlines()), 1, err)
                self.assertIn("same file", err, target)
            for name, content in files.items():
                self.assertEqual(lines_of(os.path.join(d, name)), content, name)
            self.assertEqual(leftovers(d), [])

    def test_a_symbolic_link_as_the_series_folder_is_refused_before_the_table_is_written(self):
        with tempfile.TemporaryDirectory() as d:
            spec = write(os.path.join(d, "s.toml"), f'scene = "{SPINUP}"\nkeep = ["tip_series"]\n[set]\n'
                                                    f'"output.t_end" = 0.1\n')
            elsewhere = os.path.join(d, "elsewhere")
            os.mkdir(elsewhere)
            # A killed writer's leftover in the folder the link names: not the sweep's to remove through a link.
            planted = write(os.path.join(elsewhere, ".x.npy.tmp-999999999"), "another user's file\n")
            os.symlink(elsewhere, os.path.join(d, "t.series"))
            code, err = cli_all([spec, "-o", os.path.join(d, "t.csv")])[0]
            self.assertEqual(code, 2, err)
            self.assertEqual(len(err.strip().splitlines()), 1, err)
            self.assertIn("t.series: expected the table's folder of tip series, got a symbolic link", err)
            self.assertFalse(os.path.exists(os.path.join(d, "t.csv")))  # no table, not even its header
            self.assertEqual(os.listdir(elsewhere), [os.path.basename(planted)])
            self.assertEqual(leftovers(d), [])

    def test_a_table_name_with_a_control_or_format_character_is_refused(self):
        # The one check of an output's name that every hubbeam writer makes: a newline, ESC, U+202E or a byte that is
        # not UTF-8 in the name is refused before anything is computed, and nothing is created.
        with tempfile.TemporaryDirectory() as d:
            spec = write(os.path.join(d, "s.toml"), f'scene = "{SPINUP}"\n[set]\n"output.t_end" = 0.1\n')
            names = ["t\n!touch pwned\n.csv", "t\x1b[31m.csv", "t\u202e.csv", os.fsdecode(b"t\xff.csv")]
            results = cli_all(*([spec, "-o", os.path.join(d, n)] for n in names))
            for name, (code, err) in zip(names, results):
                self.assertEqual(code, 2, err)
                self.assertEqual(len(err.strip().splitlines()), 1, err)
                self.assertIn("-o: expected a file name without control or format characters, got ", err)
            with self.assertRaisesRegex(sweeps.SweepError, "without control or format characters"):
                hubbeam.sweep(spec, output=os.path.join(d, names[0]), scheduler=CLIENT, progress=False)
            self.assertEqual(sorted(os.listdir(d)), ["s.toml"])

    def test_a_symbolic_link_as_the_table_is_never_written_through(self):
        with tempfile.TemporaryDirectory() as d:
            spec = write(os.path.join(d, "s.toml"), f'scene = "{SPINUP}"\n[set]\n"output.t_end" = 0.1\n')
            victim = write(os.path.join(d, "victim.csv"), "another user's file\n")
            os.symlink(victim, os.path.join(d, "planted.csv"))
            os.symlink(os.path.join(d, "nowhere.csv"), os.path.join(d, "dangling.csv"))
            results = cli_all([spec, "-o", os.path.join(d, "planted.csv")],
                              [spec, "-o", os.path.join(d, "planted.csv"), "--no-resume"],
                              [spec, "-o", os.path.join(d, "dangling.csv"), "--no-resume"])
            for code, err in results:
                self.assertEqual(code, 2, err)
                self.assertEqual(len(err.strip().splitlines()), 1, err)
                self.assertIn("symbolic link", err)
            self.assertEqual(lines_of(victim), b"another user's file\n")
            self.assertTrue(os.path.islink(os.path.join(d, "planted.csv")))
            self.assertFalse(os.path.exists(os.path.join(d, "nowhere.csv")))
            self.assertEqual(leftovers(d), [])

    def test_a_read_only_table_is_refused_as_every_writer_refuses_it(self):
        with tempfile.TemporaryDirectory() as d:
            spec = write(os.path.join(d, "s.toml"), f'scene = "{SPINUP}"\n[set]\n"output.t_end" = 0.1\n')
            table = write(os.path.join(d, "kept.csv"), "a table you protected\n", 0o444)
            results = cli_all([spec, "-o", table], [spec, "-o", table, "--no-resume"])
            for code, err in results:
                self.assertEqual(code, 2, err)
                self.assertEqual(err, f"{table} is read-only (mode 0444): hubbeam does not replace a file you "
                                      f"protected; chmod u+w it or choose another output\n")
            self.assertEqual(lines_of(table), b"a table you protected\n")

    def private_sweep(self, d):
        """A sweep whose second point's motion table is a credentials file (0600), run under umask 022."""
        secret = write(os.path.join(d, "credentials"), "token=hunter2-do-not-print\n", 0o600)
        spec = {"scene": os.path.join(SOURCE, "cases", "table_spinup.toml"), "keep": ["max_abs_tip_uy", "tip_series"],
                "set": {"output.t_end": 0.2, "nx": 0}, "points": [{"ny": 4}, {"ny": 4, "motion.file": secret}]}
        old = os.umask(0o022)
        try:
            return spec, hubbeam.sweep(spec, output=os.path.join(d, "t.csv"), scheduler=CLIENT, progress=False)
        finally:
            os.umask(old)

    def test_a_private_input_makes_a_private_table(self):
        # The table (and a kept tip series) is no more readable than the most private file the sweep reads; a public
        # sweep keeps the umask's permissions. A sweep's own messages never quote a file either.
        with tempfile.TemporaryDirectory() as d:
            spec, table = self.private_sweep(d)
            self.assertEqual(table[0]["status"], "ok")
            self.assertEqual(os.stat(os.path.join(d, "t.csv")).st_mode & 0o777, 0o600)
            series = os.path.join(d, "t.series", table[0]["point"] + ".npy")
            self.assertEqual(os.stat(series).st_mode & 0o777, 0o600)
            umask = os.umask(0)
            os.umask(umask)
            hubbeam.sweep(dict(spec, points=[{"ny": 4}]), output=os.path.join(d, "public.csv"), scheduler=CLIENT,
                          progress=False)
            self.assertEqual(os.stat(os.path.join(d, "public.csv")).st_mode & 0o777, 0o666 & ~umask)
            # Resuming onto a file that is not this sweep's table: refused without quoting its first line.
            private = write(os.path.join(d, "private.txt"), "token=hunter2-do-not-print\n", 0o600)
            with self.assertRaises(sweeps.SweepError) as caught:
                hubbeam.sweep(spec, output=private, scheduler=CLIENT, progress=False)
            self.assertNotIn("hunter2", str(caught.exception))
            self.assertIn("private.txt: expected the table of this sweep", str(caught.exception))

    def test_a_row_never_holds_the_content_of_a_file(self):
        # The point whose motion table is the credentials file is an error row that says what was expected, not
        # what the file holds (the sweep adds no file's content; the core's table readers quote none).
        with tempfile.TemporaryDirectory() as d:
            _, table = self.private_sweep(d)
            self.assertTrue(table[1]["status"].startswith("error: "), table[1]["status"])
            text = lines_of(os.path.join(d, "t.csv")).decode()
            self.assertNotIn("hunter2", text)
            self.assertNotIn("token", text)

    def test_a_fifo_or_a_huge_file_is_refused_without_reading_it(self):
        with tempfile.TemporaryDirectory() as d:
            fifo = os.path.join(d, "fifo.toml")
            os.mkfifo(fifo)
            huge = os.path.join(d, "huge.toml")
            with open(huge, "w") as f:
                f.write(f'scene = "{SPINUP}"\n#')
                f.truncate(1 << 30)  # 1 GB, sparse
            big_scene = os.path.join(d, "big_scene.toml")
            shutil.copy(SPINUP, big_scene)
            with open(big_scene, "a") as f:
                f.write("#" * (1 << 20) + "\n")
            cases = [([fifo], "fifo.toml: expected a sweep file (a regular file), got a FIFO"),
                     ([write(os.path.join(d, "s.toml"), f'scene = "{fifo}"\n')],
                      "fifo.toml: expected a scene file (a regular file), got a FIFO"),
                     ([huge], "huge.toml: expected a sweep file of at most 1024 KB, got a larger file"),
                     ([write(os.path.join(d, "b.toml"), f'scene = "{big_scene}"\n')],
                      "big_scene.toml: expected a scene file of at most 1024 KB, got a larger file")]
            start = time.perf_counter()
            results = cli_all(*(c for c, _ in cases))
            self.assertLess(time.perf_counter() - start, 60)
            for (command, expected), (code, err) in zip(cases, results):
                self.assertEqual(code, 2, f"{command}: {err}")
                self.assertEqual(len(err.strip().splitlines()), 1, err)
                self.assertIn(expected, err)
            self.assertEqual(sorted(n for n in os.listdir(d) if n.endswith(".csv")), [])


# For each file key of the scene's schema, a scene of cases/ that sets it and the file it names there.
SCENE_SETTING = {"beam.profile": ("profile_blade.toml", "profile_blade.csv"),
                 "beam.blade_file": ("blade_from_file.toml", "blade_sections.dat"),
                 "motion.file": ("table_spinup.toml", "table_spinup.csv")}


def blade_study(d, mode=0o644, **extra):
    """cases/blade_from_file.toml and a copy of its blade file (mode) in d, and a sweep of two coning angles that
    keeps the three lowest frequencies (hand-assembled model, a short run, without gravity: a steady spin to take
    the modes about)."""
    scene = os.path.join(d, "blade_from_file.toml")
    shutil.copy(os.path.join(SOURCE, "cases", "blade_from_file.toml"), scene)
    blade = os.path.join(d, "blade_sections.dat")
    shutil.copy(os.path.join(SOURCE, "cases", "blade_sections.dat"), blade)
    os.chmod(blade, mode)
    keep = extra.pop("keep", ["frequencies", "max_abs_tip_uy"])
    spec = write(os.path.join(d, "sw.toml"), f'scene = "blade_from_file.toml"\nkeep = {keep!r}\nfrequencies = '
                 f'{extra.pop("frequencies", 3)}\n[set]\n"output.t_end" = 0.05\n"model.source" = "assembled"\n'
                 '"gravity.g" = 0.0\n'
                 '[grid]\nprecone = [0.05, 0.1]\n')
    return scene, blade, spec


class FileKeysTest(unittest.TestCase):
    """Every file key of the core's key table is an input of the sweep: never its table, part of each point's key
    for resuming, and as private as the table; a blade file (beam.blade_file) as every other."""

    def test_every_file_key_is_an_input_the_table_may_not_be(self):
        self.assertEqual(set(hubbeam.file_keys()), set(SCENE_SETTING), "a file key with no scene in SCENE_SETTING")
        with tempfile.TemporaryDirectory() as d:
            for key, (scene_name, file_name) in SCENE_SETTING.items():
                with self.subTest(key=key):
                    for name in (scene_name, file_name):
                        shutil.copy(os.path.join(SOURCE, "cases", name), d)
                    file = os.path.join(d, file_name)
                    before = lines_of(file)
                    spec = {"scene": os.path.join(d, scene_name), "set": {"output.t_end": 0.05}}
                    with self.assertRaisesRegex(sweeps.SweepError, rf": expected an output other than the scene's "
                                                                   rf"{re.escape(key)} \(.*\), got the same file$"):
                        hubbeam.sweep(spec, output=file, resume=False, scheduler=CLIENT, progress=False)
                    self.assertEqual(lines_of(file), before)
                    # Named by a point rather than the scene: the same.
                    point = {"scene": os.path.join(SOURCE, "cases", scene_name), "points": [{key: file}],
                             "set": {"output.t_end": 0.05}}
                    with self.assertRaisesRegex(sweeps.SweepError, "got the same file$"):
                        hubbeam.sweep(point, output=file, resume=False, scheduler=CLIENT, progress=False)
                    self.assertEqual(lines_of(file), before)

    def test_the_command_line_never_writes_over_the_blade_file(self):
        with tempfile.TemporaryDirectory() as d:
            _, blade, spec = blade_study(d)
            before = lines_of(blade)
            (code, err), = cli_all([spec, "-o", blade, "--no-resume"])
            self.assertEqual(code, 2, err)
            self.assertEqual(err, f"{blade}: expected an output other than the scene's beam.blade_file ({blade}), got "
                                  f"the same file\n")
            self.assertEqual(lines_of(blade), before)
            self.assertEqual(leftovers(d), [])

    def test_a_changed_blade_file_recomputes_its_rows(self):
        # The flapwise stiffness x4 doubles the flap frequencies (the lowest is then edge 1, 2.77 Hz, where flap 1
        # was 1.62 Hz): the resumed table holds the rows of the file as it is now (those of a new sweep, and of a
        # direct run), not the rows of the file as it was.
        with tempfile.TemporaryDirectory() as d:
            scene, blade, spec = blade_study(d)
            out = os.path.join(d, "sb.csv")
            before = hubbeam.sweep(spec, output=out, scheduler=CLIENT, progress=False)
            self.assertEqual([r["status"] for r in before], ["ok", "ok"])
            with open(blade) as f:
                lines = f.read().split("\n")
            for i in range(5, 16):  # the 11 sections: flp_stff, the 7th column, x4
                cells = lines[i].split()
                cells[6] = repr(4 * float(cells[6]))
                lines[i] = "  ".join(cells)
            write(blade, "\n".join(lines))
            (code, err), = cli_all([spec, "-o", out, *tls_options()])
            self.assertEqual(code, 0, err)
            self.assertNotIn("already", err)
            rows = read(out)
            self.assertEqual(len(rows), 2)
            fresh = hubbeam.sweep(spec, output=os.path.join(d, "fresh.csv"), resume=False, scheduler=CLIENT,
                                  progress=False)
            # The table holds its rows in the order they finished (two workers): matched to the points by their ids.
            by_point = {r["point"]: r for r in rows}
            after = [by_point[r["point"]] for r in fresh]
            for a, b, c in zip(before, after, fresh):
                self.assertEqual([float(b[f"f{i}_hz"]) for i in (1, 2, 3)], [c[f"f{i}_hz"] for i in (1, 2, 3)])
                self.assertAlmostEqual(float(b["f1_hz"]) / a["f1_hz"], 2.77 / 1.62, delta=0.02)
                direct = hubbeam.run(scene, t_end=0.05, source="assembled", g=0.0, precone=a["beam.precone"])
                self.assertEqual(float(b["max_abs_tip_uy"]), direct.max_abs_tip_uy)
            again = hubbeam.sweep(spec, output=out, scheduler=CLIENT, progress=False)  # nothing changed: kept
            self.assertEqual([r["f1_hz"] for r in again], [float(r["f1_hz"]) for r in after])

    def test_a_private_blade_file_makes_a_private_table(self):
        with tempfile.TemporaryDirectory() as d:
            _, _, spec = blade_study(d, mode=0o600)
            old = os.umask(0o022)
            try:
                hubbeam.sweep(spec, output=os.path.join(d, "sb.csv"), scheduler=CLIENT, progress=False)
            finally:
                os.umask(old)
            self.assertEqual(os.stat(os.path.join(d, "sb.csv")).st_mode & 0o777, 0o600)


class BladeFrequenciesTest(unittest.TestCase):
    def test_a_blades_frequencies_are_its_lowest_elastic_modes(self):
        # cases/blade_from_file.toml's own comment: at rest flap 1.62 Hz, edge 2.77 Hz, flap 5.39 Hz (the short
        # run leaves the hub at a few thousandths of a rad/s).
        with tempfile.TemporaryDirectory() as d:
            _, _, spec = blade_study(d)
            table = hubbeam.sweep(spec, output=os.path.join(d, "sb.csv"), scheduler=CLIENT, progress=False)
        for row in table:
            self.assertEqual(row["status"], "ok")
            self.assertEqual([round(row[f"f{i}_hz"], 2) for i in (1, 2, 3)], [1.62, 2.77, 5.39])

    def test_frequencies_the_variant_has_not_are_no_ok_row(self):
        # 64 asked for, fewer modes that oscillate: the row says so rather than "ok" with empty cells.
        with tempfile.TemporaryDirectory() as d:
            _, _, spec = blade_study(d, frequencies=64)
            table = hubbeam.sweep(spec, output=os.path.join(d, "sb.csv"), scheduler=CLIENT, progress=False)
        for row in table:
            self.assertRegex(row["status"], r"^error: frequencies: expected 64, got \d+: ")
            self.assertIsNotNone(row["f1_hz"])
            self.assertIsNone(row["f64_hz"])


class DaskConfigurationTest(unittest.TestCase):
    def test_the_command_line_reads_no_dask_configuration(self):
        # A preload in ~/.config/dask, in $DASK_CONFIG and in a DASK_ variable would each run a Python file in the
        # sweep's process (scheduler, worker and client alike): none runs, and the sweep computes its point.
        with tempfile.TemporaryDirectory() as d:
            marker = os.path.join(d, "ran")
            plant = write(os.path.join(d, "plant.py"), f"open({marker!r}, 'a').write('preloaded\\n')\n")
            config = "distributed:\n" + "".join(f"  {part}:\n    preload: [{plant!r}]\n"
                                                for part in ("scheduler", "worker", "client"))
            for folder in (os.path.join(d, "home", ".config", "dask"), os.path.join(d, "config")):
                os.makedirs(folder)
                write(os.path.join(folder, "dask.yaml"), config)
            spec = write(os.path.join(d, "s.toml"), f'scene = "{SPINUP}"\n[set]\n"output.t_end" = 0.1\n')
            env = dict(os.environ, HOME=os.path.join(d, "home"), DASK_CONFIG=os.path.join(d, "config"),
                       DASK_DISTRIBUTED__WORKER__PRELOAD=f"[{plant!r}]")
            child = subprocess.run([HUBBEAM, "sweep", spec, "-o", os.path.join(d, "t.csv"), "--workers", "1"],
                                   env=env, capture_output=True, text=True, timeout=120)
            self.assertEqual(child.returncode, 0, child.stderr)
            self.assertFalse(os.path.exists(marker), lines_of(marker) if os.path.exists(marker) else "")
            self.assertEqual([r["status"] for r in read(os.path.join(d, "t.csv"))], ["ok"])


    def test_its_empty_configuration_folder_prints_no_warning(self):
        # dask.config reads DASK_ROOT_CONFIG, the empty folder's path, through ast.literal_eval: a random name like
        # "...-config-8in5x" (a number before a keyword) made Python print a SyntaxWarning on the sweep's stderr.
        code = ("import os, sys, tempfile\n"
                "base = tempfile.mkdtemp()\n"
                "def named(prefix='', **kw):\n"
                "    p = os.path.join(base, prefix + '8in5x')\n"
                "    os.mkdir(p)\n"
                "    return p\n"
                "tempfile.mkdtemp = named\n"
                "from hubbeam import sweep_cluster\n"
                "assert 'dask.config' not in sys.modules\n"
                "sweep_cluster._ignore_dask_configuration()\n")
        child = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
        self.assertEqual((child.returncode, child.stderr), (0, ""))


class StaleRowsTest(unittest.TestCase):
    def test_a_changed_scene_or_table_recomputes_its_rows(self):
        # The stiffness x100 leaves the tip's deflection 100 times smaller; a changed motion table changes the run:
        # each resumed table equals a direct run of the scene as it is now, not the rows of the scene as it was.
        with tempfile.TemporaryDirectory() as d:
            scene = os.path.join(d, "scene.toml")
            shutil.copy(os.path.join(SOURCE, "cases", "table_spinup.csv"), d)
            with open(os.path.join(SOURCE, "cases", "table_spinup.toml")) as f:
                original = f.read()
            write(scene, original)
            spec = write(os.path.join(d, "s.toml"), 'scene = "scene.toml"\nkeep = ["max_abs_tip_uy"]\n'
                         '[set]\n"output.t_end" = 3.0\nnx = 0\n[grid]\nny = [4, 5]\n')
            out = os.path.join(d, "s.csv")

            def check():
                table = hubbeam.sweep(spec, output=out, scheduler=CLIENT, progress=False)
                for row in table:
                    direct = hubbeam.run(scene, t_end=3.0, nx=0, ny=row["discretization.ny"])
                    self.assertEqual(row["max_abs_tip_uy"], direct.max_abs_tip_uy)
                return table

            before = check()
            write(scene, original.replace("youngs_modulus = 6.8952e10", "youngs_modulus = 6.8952e12"))
            stiff = check()
            for a, b in zip(before, stiff):
                self.assertLess(b["max_abs_tip_uy"] / a["max_abs_tip_uy"], 0.1)
            # The motion table: theta doubled.
            with open(os.path.join(d, "table_spinup.csv")) as f:
                rows = f.read().splitlines()
            write(os.path.join(d, "table_spinup.csv"), "\n".join(
                [rows[0]] + [f"{t},{2 * float(v)!r}" for t, v in (r.split(",") for r in rows[1:])]) + "\n")
            doubled = check()
            for a, b in zip(stiff, doubled):
                self.assertGreater(b["max_abs_tip_uy"] / a["max_abs_tip_uy"], 1.5)
            self.assertEqual(len(read(out)), 2)  # the stale rows are gone from the table, not left beside the new
            # The command line, with the stiffness back as it was.
            write(scene, original)
            (code, err), = cli_all([spec, "-o", out, "--workers", "1"])
            self.assertEqual(code, 0, err)
            for row in read(out):
                direct = hubbeam.run(scene, t_end=3.0, nx=0, ny=int(row["discretization.ny"]))
                self.assertEqual(float(row["max_abs_tip_uy"]), direct.max_abs_tip_uy)


class PathsTest(unittest.TestCase):
    def test_every_path_in_a_sweep_file_is_relative_to_it(self):
        # The sweep file in study/, its scene in scenes/, started from elsewhere/: the scene, the output and a
        # point's motion table are all found beside the sweep file (elsewhere/ and scenes/ have a drive.csv too, each
        # with a motion the run would not complete, so a table read from either is seen).
        with tempfile.TemporaryDirectory() as d:
            for sub in ("study", "scenes", "elsewhere"):
                os.mkdir(os.path.join(d, sub))
            for name in ("table_spinup.toml", "table_spinup.csv"):
                shutil.copy(os.path.join(SOURCE, "cases", name), os.path.join(d, "scenes"))
            shutil.copy(os.path.join(SOURCE, "cases", "table_spinup.csv"), os.path.join(d, "study", "drive.csv"))
            for sub in ("scenes", "elsewhere"):
                write(os.path.join(d, sub, "drive.csv"), "t, theta\n0, 0\n0.1, 1e9\n0.2, 0\n0.3, 1e9\n")
            write(os.path.join(d, "study", "s.toml"),
                  'scene = "../scenes/table_spinup.toml"\noutput = "out.csv"\nkeep = ["max_abs_tip_uy"]\n'
                  '[set]\n"output.t_end" = 0.2\nnx = 0\n"motion.file" = "drive.csv"\n')
            child = subprocess.run([HUBBEAM, "sweep", os.path.join("..", "study", "s.toml"), "--workers", "1"],
                                   cwd=os.path.join(d, "elsewhere"), capture_output=True, text=True, timeout=120)
            self.assertEqual(child.returncode, 0, child.stderr)
            rows = read(os.path.join(d, "study", "out.csv"))
            direct = hubbeam.run(os.path.join(d, "scenes", "table_spinup.toml"), t_end=0.2, nx=0,
                                 **{"motion.file": os.path.join(d, "study", "drive.csv")})
            self.assertEqual([r["status"] for r in rows], ["ok"])
            self.assertEqual(float(rows[0]["max_abs_tip_uy"]), direct.max_abs_tip_uy)
            self.assertEqual(rows[0]["motion.file"], "drive.csv")  # the point's value, as the sweep file gives it
            self.assertFalse(os.path.exists(os.path.join(d, "elsewhere", "out.csv")))


class IsolationTest(unittest.TestCase):
    def test_python_in_the_current_folder_never_runs(self):
        # A csv.py and a hubbeam/ package where the sweep starts, and a PYTHONPATH naming a folder of the same: none
        # is imported; the sweep computes its point with this build's hubbeam.
        with tempfile.TemporaryDirectory() as d:
            marker = os.path.join(d, "ran")
            planted = f"open({marker!r}, 'a').write(__name__ + '\\n')\n"
            write(os.path.join(d, "csv.py"), planted)
            os.mkdir(os.path.join(d, "hubbeam"))
            write(os.path.join(d, "hubbeam", "__init__.py"), planted)
            write(os.path.join(d, "hubbeam", "sweeps.py"), planted + "def main(argv=None):\n    return 0\n")
            spec = write(os.path.join(d, "s.toml"), f'scene = "{SPINUP}"\n[set]\n"output.t_end" = 0.1\n')
            env = dict(os.environ, PYTHONPATH=d + os.pathsep + os.environ.get("PYTHONPATH", ""), PYTHONSTARTUP=marker)
            child = subprocess.run([HUBBEAM, "sweep", "s.toml", "-o", "t.csv", "--workers", "1"], cwd=d, env=env,
                                   capture_output=True, text=True, timeout=120)
            self.assertEqual(child.returncode, 0, child.stderr)
            self.assertFalse(os.path.exists(marker), lines_of(marker) if os.path.exists(marker) else "")
            self.assertEqual([r["status"] for r in read(os.path.join(d, "t.csv"))], ["ok"])


class SignalTest(unittest.TestCase):
    def test_signals_keep_the_rows_so_far_and_leave_no_lock_or_temporary_file(self):
        # Two short points finish, a third runs for minutes: each signal ends the sweep with the two rows kept, the
        # exit code 128 + the signal, and no lock or temporary file left (with --no-resume the old table stays).
        long_point = '[[points]]\nny = 4\n"output.t_end" = 1e6\n"output.dt_out" = 1.0\n"solver.max_steps" = 1e12\n'
        with tempfile.TemporaryDirectory() as d:
            spec = write(os.path.join(d, "s.toml"), f'scene = "{SPINUP}"\nkeep = ["steps"]\n[set]\nnx = 0\n'
                         f'"output.t_end" = 0.1\n[grid]\nny = [4, 5]\n' + long_point)
            signals = [signal.SIGHUP, signal.SIGQUIT, signal.SIGTERM, signal.SIGINT]
            tables = {s: os.path.join(d, f"{s.name}.csv") for s in signals}
            old = write(os.path.join(d, "old.csv"), "the old table\n")
            children = {s: subprocess.Popen([HUBBEAM, "sweep", spec, "-o", tables[s], "--workers", "2"],
                                            stderr=subprocess.PIPE, text=True) for s in signals}
            children["no-resume"] = subprocess.Popen([HUBBEAM, "sweep", spec, "-o", old, "--workers", "2",
                                                      "--no-resume"], stderr=subprocess.PIPE, text=True)
            temporaries = lambda: [n for n in os.listdir(d) if n.startswith(".old.csv.tmp-")]
            try:
                end = time.monotonic() + 120
                while time.monotonic() < end and not (
                        all(os.path.exists(t) and len(read(t)) == 2 for t in tables.values()) and temporaries() and
                        len(lines_of(os.path.join(d, temporaries()[0])).splitlines()) == 3):
                    time.sleep(0.2)
                for s, child in children.items():
                    child.send_signal(signal.SIGTERM if s == "no-resume" else s)
                results = {s: (c.wait(timeout=60), c.stderr.read()) for s, c in children.items()}
            finally:
                for c in children.values():
                    if c.poll() is None:
                        c.kill()
                        c.wait()
            for s in signals:
                code, err = results[s]
                self.assertEqual(code, 128 + s, f"{s.name}: {err}")
                self.assertIn("the finished points are in the table", err)
                self.assertNotIn("Traceback", err)
                self.assertEqual(sorted(r["discretization.ny"] for r in read(tables[s])), ["4", "5"], s.name)
            self.assertEqual(results["no-resume"][0], 143, results["no-resume"][1])
            self.assertEqual(lines_of(old), b"the old table\n")
            self.assertEqual(leftovers(d), [])

    def test_what_a_killed_sweep_left_is_cleaned_by_the_next_writer(self):
        with tempfile.TemporaryDirectory() as d:
            spec = write(os.path.join(d, "s.toml"), f'scene = "{SPINUP}"\nkeep = ["steps"]\n[set]\nnx = 0\n'
                         f'"output.t_end" = 1e6\n"output.dt_out" = 1.0\n"solver.max_steps" = 1e12\n')
            table = write(os.path.join(d, "t.csv"), "the old table\n")
            child = subprocess.Popen([HUBBEAM, "sweep", spec, "-o", table, "--workers", "1", "--no-resume"],
                                     stderr=subprocess.DEVNULL)
            end = time.monotonic() + 120
            while time.monotonic() < end and len(leftovers(d)) < 2:
                time.sleep(0.2)
            child.kill()
            child.wait()
            left = leftovers(d)
            self.assertEqual(left, [".t.csv.lock", f".t.csv.tmp-{child.pid}"])
            # A live process's temporary file (this test's own pid) is not the next writer's to remove.
            alive = write(os.path.join(d, f".t.csv.tmp-{os.getpid()}"), "")
            quick = write(os.path.join(d, "q.toml"), f'scene = "{SPINUP}"\nkeep = ["steps"]\n[set]\nnx = 0\n'
                          f'"output.t_end" = 0.1\n')
            (code, err), = cli_all([quick, "-o", table, "--no-resume", "--workers", "1"])
            self.assertEqual(code, 0, err)
            self.assertEqual(leftovers(d), [os.path.basename(alive)])
            self.assertEqual(len(read(table)), 1)


class InputFormsTest(unittest.TestCase):
    def test_numpy_grids_and_a_sweep_file_with_a_byte_order_mark(self):
        # A dict sweep's grid may be a numpy array and its values numpy numbers, as everywhere else in the package; a
        # sweep file saved with a UTF-8 byte order mark reads like the same file without it, as a scene file does.
        with tempfile.TemporaryDirectory() as d:
            spec = {"scene": SPINUP, "set": {"output.t_end": np.float64(0.2), "nx": np.int64(0)},
                    "grid": {"ny": np.array([4, 6])}, "keep": ["max_abs_tip_uy"]}
            table = hubbeam.sweep(spec, output=os.path.join(d, "np.csv"), scheduler=CLIENT, progress=False)
            rows = read(os.path.join(d, "np.csv"))
            # The file holds the rows as the points finish (two workers: either first); the table returned is in the
            # sweep's order.
            self.assertEqual(sorted((int(r["discretization.ny"]), r["status"]) for r in rows), [(4, "ok"), (6, "ok")])
            self.assertEqual([int(r["discretization.ny"]) for r in table], [4, 6])
            plain = os.path.join(d, "plain.toml")
            text = f'scene = "{SPINUP}"\nkeep = ["max_abs_tip_uy"]\n[set]\n"output.t_end" = 0.2\nnx = 0\n'
            write(plain, text)
            with open(os.path.join(d, "bom.toml"), "wb") as f:
                f.write(b"\xef\xbb\xbf" + text.encode())
            self.assertEqual(sweeps.load_sweep(os.path.join(d, "bom.toml"))["set"], sweeps.load_sweep(plain)["set"])
            del table
