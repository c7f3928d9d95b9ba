"""hubbeam run -o FILE.npy read by numpy itself: the array equals the CSV of the same scene number for number (both
runs are deterministic), its names file is the CSV's header, and a run stopped early has the rows it kept; that file's
header and every entry's of hubbeam linearize's .npz are a multiple of 64 bytes long (NEP 1: numpy reads a header of
any length, so only this check sees the alignment).

Usage: python3 npy_read_by_numpy.py HUBBEAM SCENE WORKDIR (run by ctest only where numpy is installed)."""
import os
import struct
import subprocess
import sys
import zipfile

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


def header_length(data):
    """The .npy header's length in bytes, as its version 1.0 prefix states it."""
    assert data[:8] == b"\x93NUMPY\x01\x00", data[:8]
    return 10 + struct.unpack("<H", data[8:10])[0]


failures = []
for name, options, code in (("full", ("--t-end", "3"), 0), ("stopped", ("--stepper", "rk8pd", "--max-steps", "300"), 1)):
    npy, csv = os.path.join(work, name + ".npy"), os.path.join(work, name + ".csv")
    if run(npy, *options) != code or run(csv, *options) != code:
        failures.append(f"{name}: expected exit {code}")
        continue
    a = numpy.load(npy)
    with open(npy, "rb") as f:
        if header_length(f.read(12)) % 64:
            failures.append(f"{name}: the .npy header is not a multiple of 64 bytes")
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

prefix = os.path.join(work, "linear")
if subprocess.run([hubbeam, "linearize", scene, "--omega", "0", "--nx", "2", "-o", prefix],
                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode != 0:
    failures.append("linearize: expected exit 0")
else:
    arrays = numpy.load(prefix + ".npz")
    with zipfile.ZipFile(prefix + ".npz") as z:
        for entry in z.namelist():
            length = header_length(z.read(entry))
            if length % 64:
                failures.append(f"linearize: {entry}'s header is {length} bytes, not a multiple of 64")
    with open(prefix + "-A.csv") as f:
        rows = [line.split(",") for line in f.read().splitlines()[1:]]
    if not numpy.array_equal(arrays["A"], numpy.array([[float(x) for x in r[1:]] for r in rows])):
        failures.append("linearize: the .npz's A is not the CSV's")

print("\n".join(failures) or "ok")
sys.exit(1 if failures else 0)
