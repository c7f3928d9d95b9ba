"""hubbeam run -o FILE.npy read by numpy itself: the array equals the CSV of the same scene number for number (both
runs are deterministic), its names file is the CSV's header, and a run stopped early has the rows it kept.

Usage: python3 npy_read_by_numpy.py HUBBEAM SCENE WORKDIR (run by ctest only where numpy is installed)."""
import os
import subprocess
import sys

import numpy

hubbeam, scene, work = sys.argv[1:4]
os.makedirs(work, exist_ok=True)


def run(output, *options):
    """Runs the scene to output; returns the exit code."""
    return subprocess.run([hubbeam, "run", scene, "--nx", "0", *options, "-o", output],
                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode


def csv_table(path):
    """The header's names and the rows' numbers, read with Python's correctly rounded float()."""
    with open(path) as f:
        lines = f.read().splitlines()
    return lines[0].split(","), numpy.array([[float(x) for x in line.split(",")] for line in lines[1:]])


failures = []
for name, options, code in (("full", ("--t-end", "3"), 0), ("stopped", ("--stepper", "rk8pd", "--max-steps", "300"), 1)):
    npy, csv = os.path.join(work, name + ".npy"), os.path.join(work, name + ".csv")
    if run(npy, *options) != code or run(csv, *options) != code:
        failures.append(f"{name}: expected exit {code}")
        continue
    a = numpy.load(npy)
    names, b = csv_table(csv)
    with open(os.path.join(work, name + ".columns.txt")) as f:
        if f.read().strip().split(",") != names:
            failures.append(f"{name}: the names file is not the CSV's header")
    if a.dtype != numpy.dtype("<f8") or a.ndim != 2 or a.shape != b.shape:
        failures.append(f"{name}: array {a.dtype} {a.shape}, CSV {b.shape}")
    elif not numpy.array_equal(a.view(numpy.uint64), b.view(numpy.uint64)):
        failures.append(f"{name}: the numbers differ from the CSV's")
    elif code == 0 and not a[-1, 0] == 3.0:
        failures.append(f"{name}: the last row is at t = {a[-1, 0]}, not t_end")
    elif code == 1 and not 2 <= len(a) < 3001:
        failures.append(f"{name}: {len(a)} rows for a run stopped early")

print("\n".join(failures) or "ok")
sys.exit(1 if failures else 0)
