"""Sweeps on a local Dask cluster of 2 workers: the same table as sequential runs, a failing point reported while
the rest finish, resume without recomputation, and hubbeam sweep's exit codes. Needs HUBBEAM and SOURCE_DIR."""
import csv
import os
import subprocess
import tempfile
import unittest

import hubbeam
from hubbeam import sweeps

HUBBEAM = os.environ["HUBBEAM"]
SOURCE = os.environ["SOURCE_DIR"]
SPINUP = os.path.join(SOURCE, "cases", "spinup_omega4.toml")

# 20 points: 4 methods x Ny 4, 6 x two spin rates, and 4 explicit points, one of them bad (FEM needs an even Ny).
SWEEP = f"""
scene = "{SPINUP}"
keep = ["max_abs_tip_uy", "relative_drift", "steps", "variant", "frequencies"]
frequencies = 2

[set]
"output.t_end" = 20.0

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


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


class SweepTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.TemporaryDirectory()
        cls.spec = os.path.join(cls.dir.name, "study.toml")
        with open(cls.spec, "w") as f:
            f.write(SWEEP)
        cls.table_path = os.path.join(cls.dir.name, "study.csv")
        cls.table = hubbeam.sweep(cls.spec, output=cls.table_path, workers=2, progress=False)

    def test_twenty_points_equal_sequential_runs(self):
        points = sweeps.expand(sweeps.load_sweep(self.spec))
        self.assertEqual(len(points), 20)
        self.assertEqual(len(self.table), 20)
        # What was written (in the order the points finished) is what was returned (in the sweep's order).
        by_point = lambda rows: sorted(rows, key=lambda r: r["point"])  # noqa: E731
        self.assertEqual(by_point(read(self.table_path)), by_point(self.table))
        scene_text = open(SPINUP).read()
        for point, row in zip(points, self.table):
            alone = sweeps.run_point(scene_text, SPINUP, point, ["max_abs_tip_uy", "relative_drift", "steps", "variant",
                                                               "frequencies"], 2)
            for key in ("status", "max_abs_tip_uy", "relative_drift", "steps", "variant", "f1_hz", "f2_hz"):
                expected = alone.get(key, "")
                written = row[key]
                self.assertEqual(written, repr(expected) if isinstance(expected, float) else str(expected),
                                 f"{point}: {key}")
            direct = hubbeam._run_text(scene_text, SPINUP, point) if row["status"] == "ok" else None
            if direct is not None:
                self.assertEqual(float(row["max_abs_tip_uy"]), direct.max_abs_tip_uy)

    def test_a_failing_point_is_a_row_and_the_rest_finish(self):
        bad = [r for r in self.table if r["status"] != "ok"]
        self.assertEqual(len(bad), 1)
        self.assertEqual(bad[0]["discretization.ny"], "5")
        self.assertIn("FEM needs an even ny", bad[0]["status"])
        self.assertEqual(sum(r["status"] == "ok" for r in self.table), 19)

    def test_resume_skips_finished_points(self):
        # Keep the header and 15 rows: a rerun computes the 5 missing points only, and keeps the 15 as they were.
        with open(self.table_path) as f:
            lines = f.readlines()
        partial = os.path.join(self.dir.name, "partial.csv")
        with open(partial, "w") as f:
            f.writelines(lines[:16])
        kept = {r["point"]: r for r in read(partial)}
        for row in kept.values():
            row["run_seconds"] = "-1"  # a value no run writes: recomputed rows would not have it
        with open(partial, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(self.table[0].keys()), lineterminator="\n")
            w.writeheader()
            w.writerows(kept.values())
        table = hubbeam.sweep(self.spec, output=partial, workers=2, progress=False)
        self.assertEqual(len(table), 20)
        self.assertEqual(sum(r["run_seconds"] == "-1" for r in table), 15)
        self.assertEqual(len(read(partial)), 20)

    def test_command_line(self):
        out = os.path.join(self.dir.name, "cli.csv")
        done = subprocess.run([HUBBEAM, "sweep", self.spec, "-o", self.table_path], capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("already", done.stderr)  # all 20 points are in the table
        bad = subprocess.run([HUBBEAM, "sweep", os.path.join(self.dir.name, "none.toml"), "-o", out], capture_output=True,
                             text=True)
        self.assertEqual(bad.returncode, 2)
        self.assertIn("none.toml: cannot open", bad.stderr)
        other = os.path.join(self.dir.name, "other.csv")
        with open(other, "w") as f:
            f.write("a,b\n1,2\n")
        clash = subprocess.run([HUBBEAM, "sweep", self.spec, "-o", other], capture_output=True, text=True)
        self.assertEqual(clash.returncode, 2)
        self.assertIn("expected the table of this sweep", clash.stderr)
        with open(other) as f:
            self.assertEqual(f.read(), "a,b\n1,2\n")  # never touched


if __name__ == "__main__":
    unittest.main()
