"""Sweeps on one local Dask cluster of 2 worker threads shared by the tests: the same table as sequential runs,
typed values, a failing point reported while the rest finish, resume without recomputation and past a cut last
line, tip series in files, a full disk, the command line over TLS with certificate files, and bad input that
leaves every file as it was. Needs HUBBEAM and SOURCE_DIR."""
import csv
import os
import resource
import shutil
import socket
import subprocess
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
        self.assertEqual([n for n in os.listdir(self.dir.name) if n.endswith(".partial")], [])
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
            self.assertEqual(len(read(out)), 3)  # the resumed point's new row; the old row is ignored


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
            self.assertEqual([n for n in os.listdir(d) if n.endswith((".partial", ".lock"))], [])
