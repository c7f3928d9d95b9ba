"""Parameter sweeps on Dask: `hubbeam sweep SWEEP.toml` and hubbeam.sweep(...) (docs/python.md, "Sweeps").

A sweep is a base scene plus a grid and/or a list of overrides of any scene keys. Every point runs as one Dask
task, on a local cluster (worker threads of this process: the runs release the GIL) or on a running scheduler,
and lands as one row of a CSV table: the point's keys, its status and the quantities kept. A point that fails is a
row with its status; an interrupted sweep resumes without recomputing the points already in the table (keyed by
the effective scene: the base scene's text, the content of the tables it names, the point's overrides and the
model's version). A kept tip series goes to one .npy file per point beside the table, and its cell names that file.
"""
from __future__ import annotations

import argparse
import csv
import errno
import fcntl
import hashlib
import io
import itertools
import json
import logging
import os
import re
import signal
import socket
import stat
import sys
import time
import tomllib
from typing import Any, Mapping, Sequence

# What a sweep may keep per point: the run's summary values, its tip series (t, tip_uy), the elastic modes'
# frequencies about the point's steady spin, and the invariant drift relative to the vibration energy.
SUMMARY_VALUES = ("completed", "t_reached", "max_abs_tip_uy", "jacobi_drift", "vibration_energy", "steps",
                  "rejected_steps", "rhs_evals", "jacobian_evals", "wall_seconds", "variant", "source", "stepper")
DERIVED_VALUES = ("relative_drift", "tip_series", "frequencies")
DEFAULT_KEEP = ("max_abs_tip_uy", "relative_drift", "wall_seconds")
# The mode kinds whose frequencies "frequencies" keeps: the beam's elastic modes as the core labels them (a planar
# beam's bending, a blade's edge, flap and twist), as the Campbell diagram draws them (plots.CAMPBELL_KINDS).
ELASTIC_KINDS = ("bending", "edge", "flap", "twist")
# The type of each kept value as the table's text reads back (the rest are floats): hubbeam.sweep returns these.
_TEXT_COLUMNS = {"point", "status", "variant", "source", "stepper"}
_INT_COLUMNS = {"steps", "rejected_steps", "rhs_evals", "jacobian_evals"}


def _file_keys() -> dict[str, int]:
    """The scene keys that name a file the scene reads, with the most bytes the core reads of it: the core's key
    table says which (hubbeam.file_keys()). In a scene such a path is relative to the scene's folder; in a sweep file
    (as every path there) relative to the sweep file's."""
    import hubbeam

    return hubbeam.file_keys()


class SweepError(ValueError):
    """A sweep that cannot start or go on: a bad sweep file, option, output or scheduler (one line naming it)."""


def _printable(text: Any, cap: int = 400) -> str:
    import hubbeam

    return hubbeam.printable(text, cap)


def _file_kind(mode: int) -> str:
    """What a file that is not a regular file is, as every reader and writer says it (hubbeam._file_kind)."""
    import hubbeam

    return hubbeam._file_kind(mode)


def _fail(where: str, key: str, expected: str, got: Any) -> None:
    raise SweepError(f"{_printable(where)}: {_printable(key, 80)}: expected {expected}, got "
                     f"{_printable(repr(got), 120)}")


def _read_input(path: str, cap: int, what: str) -> bytes:
    """The bytes of an input file (the sweep file, its scene, a table) by the rules of every hubbeam reader
    (hubbeam._read_regular: no FIFO opened, no more than cap bytes read); SweepError naming the file otherwise."""
    import hubbeam

    try:
        return hubbeam._read_regular(path, cap, what)
    except (OSError, ValueError) as e:  # FileNotFoundError among them
        raise _sweep_error(e) from None


def _sweep_error(e: Exception) -> SweepError:
    """A reader's refusal (hubbeam's FileNotFoundError or ValueError, its one line) as the sweep's."""
    return SweepError(e.strerror if isinstance(e, OSError) and e.strerror else str(e))


def load_sweep(spec: str | os.PathLike | Mapping[str, Any]) -> dict[str, Any]:
    """The sweep of a SWEEP.toml file or of a dict with the same keys, checked: scene (the base scene's path),
    set (key -> value for every point), grid (key -> list of values), points (list of key -> value tables), keep
    (names from SUMMARY_VALUES and DERIVED_VALUES), frequencies (how many), output (the CSV; default the sweep
    file's name with .csv). Every path a sweep file gives (scene, output, a file key's value) is relative to the
    sweep file's folder, a dict's to the current folder: base is that folder."""
    if isinstance(spec, Mapping):
        from hubbeam import _plain  # numpy's numbers and arrays go into a dict sweep as into every other call

        where, base_dir = "<dict sweep>", os.getcwd()
        sweep = {k: {kk: _plain(vv) for kk, vv in v.items()} if isinstance(v, Mapping) else _plain(v)
                 for k, v in spec.items()}
        if isinstance(sweep.get("points"), list):
            sweep["points"] = [{kk: _plain(vv) for kk, vv in p.items()} if isinstance(p, Mapping) else p
                               for p in sweep["points"]]
    else:
        where = os.fspath(spec)
        _check_path("sweep file", where)
        from hubbeam import _MAX_SCENE_BYTES  # a sweep file is read as a scene file is

        data = _read_input(where, _MAX_SCENE_BYTES, "a sweep file")
        try:
            sweep = tomllib.loads(data.decode("utf-8-sig"))  # a byte order mark, as the scene reader takes it
        except (tomllib.TOMLDecodeError, UnicodeDecodeError) as e:
            raise SweepError(f"{_printable(where)}: {_printable(e)}") from None
        base_dir = os.path.dirname(os.path.abspath(where))
    known = {"scene", "set", "grid", "points", "keep", "frequencies", "output"}
    for key in sweep:
        if key not in known:
            _fail(where, key, "one of " + ", ".join(sorted(known)), "an unknown key")
    if not isinstance(sweep.get("scene"), str) or not sweep["scene"] or "\0" in sweep["scene"]:
        _fail(where, "scene", "the base scene file's path (a string)", sweep.get("scene", "nothing"))
    scene = os.path.join(base_dir, sweep["scene"])
    grid = sweep.get("grid", {})
    if not isinstance(grid, Mapping):
        _fail(where, "grid", "a table of key = [values]", grid)
    for key, values in grid.items():
        if not isinstance(values, list) or not values:
            _fail(where, f"grid.{key}", "a non-empty list of values", values)
    common = sweep.get("set", {})
    if not isinstance(common, Mapping):
        _fail(where, "set", "a table of key = value for every point", common)
    points = sweep.get("points", [])
    if not isinstance(points, list) or not all(isinstance(p, Mapping) for p in points):
        _fail(where, "points", "a list of tables ([[points]])", points)
    keep = sweep.get("keep", list(DEFAULT_KEEP))
    allowed = SUMMARY_VALUES + DERIVED_VALUES
    if not isinstance(keep, list) or not keep:
        _fail(where, "keep", "a non-empty list of " + ", ".join(allowed), keep)
    for k in keep:
        if k not in allowed:
            _fail(where, "keep", "names from " + ", ".join(allowed), k)
    frequencies = sweep.get("frequencies", 3)
    if not isinstance(frequencies, int) or isinstance(frequencies, bool) or not 1 <= frequencies <= 64:
        _fail(where, "frequencies", "an integer from 1 to 64", frequencies)
    output = sweep.get("output")
    if output is None:
        output = (os.path.splitext(where)[0] if where != "<dict sweep>" else "sweep") + ".csv"
    elif not isinstance(output, str) or not output or "\0" in output:
        _fail(where, "output", "a file name (not empty, no NUL character)", output)
    else:
        output = os.path.join(base_dir, output)
    return {"where": where, "base": base_dir, "scene": scene, "set": dict(common), "grid": dict(grid),
            "points": points, "keep": list(keep), "frequencies": frequencies, "output": output}


def _full_key(name: str, where: str) -> str:
    import hubbeam

    keys = hubbeam.scene_keys()
    if name in keys:
        return name
    matches = [k for k in keys if k.split(".", 1)[1] == name]
    if len(matches) != 1:
        _fail(where, name, "a scene key (docs/scene.md)", "an unknown key")
    return matches[0]


def expand(sweep: Mapping[str, Any]) -> list[dict[str, Any]]:
    """Every point of the sweep, as dotted scene keys: each combination of the grid, then each [[points]] table,
    all on top of the keys of [set]. Without grid and points, the one point [set] makes. Each value must be a
    number, a string or a boolean (SweepError otherwise)."""
    where = sweep["where"]
    common = {_full_key(k, where): v for k, v in sweep["set"].items()}
    grid_keys = [_full_key(k, where) for k in sweep["grid"]]
    out = []
    if sweep["grid"]:
        for combo in itertools.product(*sweep["grid"].values()):
            out.append({**common, **dict(zip(grid_keys, combo))})
    for point in sweep["points"]:
        out.append({**common, **{_full_key(k, where): v for k, v in point.items()}})
    out = out or [common]
    for point in out:
        for k, v in point.items():
            if not isinstance(v, (int, float, str)) or (isinstance(v, str) and "\0" in v):
                _fail(where, k, "a number or a string (no NUL character)", v)
    return out


def _resolved(point: Mapping[str, Any], base: str) -> dict[str, Any]:
    """The point's overrides as the core takes them: a file key's relative path joined to the sweep's folder."""
    files = _file_keys()
    return {k: os.path.join(base, v) if k in files and isinstance(v, str) and v else v for k, v in point.items()}


class _SceneFiles:
    """The files each point's run reads (file key -> path), as the core lists them for the base scene with the
    point's overrides (hubbeam.scene_files: the key table's file keys, resolved as the core opens them). Only a
    point's file keys change the list, so it is asked once per distinct set of them."""

    def __init__(self, scene_text: str, scene_path: str):
        import hubbeam

        self.text, self.path = scene_text, scene_path
        self.files = hubbeam._FILE_KEYS
        self.known: dict[tuple, dict[str, str]] = {}
        self.base = self.of_point({})

    def of_point(self, point: Mapping[str, Any]) -> dict[str, str]:
        import hubbeam

        own = tuple(sorted((k, v) for k, v in point.items() if k in self.files))
        if own not in self.known:
            try:
                self.known[own] = dict(hubbeam._core_call(hubbeam._core.scene_files, self.text, self.path,
                                                          hubbeam._overrides(dict(own))))
            except ValueError:
                # A file key of the wrong kind: the point's run is refused for it whatever the files hold.
                self.known[own] = dict(self.base) if own else {}
        return self.known[own]


def point_key(point: Mapping[str, Any], scene_text: str, files: Mapping[str, str], version: str) -> str:
    """The point's identity for resuming: the effective scene it runs (the base scene's text, the digest of each
    file it reads by file key, its overrides) and the version of the generator and module that compute it. A row
    whose key differs from its point's is stale and is computed again."""
    text = json.dumps({"scene": hashlib.sha256(scene_text.encode()).hexdigest(), "files": sorted(files.items()),
                       "set": sorted(point.items()), "version": version}, default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


class _Inputs:
    """The files a sweep reads besides its sweep file and scene (the tables and profiles of every point), each read
    once: its digest for the points' keys and its permissions for the table's."""

    def __init__(self):
        self.digests: dict[str, str] = {}
        self.stats: dict[str, os.stat_result] = {}

    def digest(self, path: str, cap: int) -> str:
        if path not in self.digests:
            try:
                data = _read_input(path, cap, "a table")
                self.stats[path] = os.stat(path)
                self.digests[path] = hashlib.sha256(data).hexdigest()
            except SweepError:
                self.digests[path] = "unreadable"  # the point's run says why, in its row
        return self.digests[path]

    def of_point(self, files: Mapping[str, str]) -> dict[str, str]:
        """file key -> digest of the files the point's run reads (_SceneFiles.of_point)."""
        caps = _file_keys()
        return {k: self.digest(path, caps[k]) for k, path in files.items()}


def _columns(keys: Sequence[str], keep: Sequence[str], frequencies: int) -> list[str]:
    values = []
    for k in keep:
        values += [f"f{i}_hz" for i in range(1, frequencies + 1)] if k == "frequencies" else [k]
    return ["point", *keys, "status", *values, "run_seconds"]


def run_points(scene_text: str, scene_name: str, points: Sequence[Mapping[str, Any]], keep: Sequence[str],
               frequencies: int) -> list[dict[str, Any]]:
    """A batch of points in one task (Dask's own cost per task is about a millisecond: short points share it)."""
    return [run_point(scene_text, scene_name, p, keep, frequencies) for p in points]


def run_point(scene_text: str, scene_name: str, point: Mapping[str, Any], keep: Sequence[str],
              frequencies: int) -> dict[str, Any]:
    """One point, on a worker: its row, values typed (tip_series an n x 2 array of t and tip_uy). Never raises:
    bad input, an unstable run or any error is the status."""
    import numpy as np

    import hubbeam

    row: dict[str, Any] = {}
    start = time.perf_counter()
    try:
        # The base scene travels as text, so a remote worker needs no copy of the file.
        r = hubbeam._run_text(scene_text, scene_name, point)
        row["status"] = "ok" if r.completed else "stopped: " + hubbeam.printable(r.failure)
        for k in keep:
            if k in SUMMARY_VALUES:
                row[k] = getattr(r, k)
            elif k == "relative_drift":
                row[k] = r.jacobi_drift / r.vibration_energy if r.vibration_energy > 0 else None
            elif k == "tip_series":
                row[k] = np.column_stack([r.t, r.tip_uy])
            elif k == "frequencies":
                # About the point's steady spin: the rate the hub ends at when prescribed, at rest for a free hub.
                omega = 0.0 if "_torque_" in r.variant else abs(float(r.theta_dot[-1]))
                m = hubbeam._modes_text(scene_text, scene_name, point, [omega])
                # The beam's elastic modes as the core labels them (a planar beam's "bending", a blade's "edge",
                # "flap" and "twist"; not the axial ones, hundreds of times higher, nor the hub's), those that
                # oscillate (an overdamped mode's frequency is 0), lowest first.
                hz = np.sort(m["hz"][np.isin(m["kind"], ELASTIC_KINDS) & (m["hz"] > 0)])[:frequencies]
                for i in range(frequencies):
                    row[f"f{i + 1}_hz"] = float(hz[i]) if i < len(hz) else None
                if len(hz) < frequencies:
                    row["status"] = (f"error: frequencies: expected {frequencies}, got {len(hz)}: the point's "
                                     f"variant has {len(hz)} oscillating {', '.join(ELASTIC_KINDS)} modes")
        row["run_seconds"] = r.in_process_seconds  # as hubbeam run spends in process: load, model, integrate
    except ValueError as e:
        row["status"] = "error: " + hubbeam.printable(e)
    except Exception as e:  # noqa: BLE001 - a point's failure must never end the sweep
        row["status"] = "error: " + hubbeam.printable(f"{type(e).__name__}: {e}")
    row.setdefault("run_seconds", time.perf_counter() - start)
    return row


def _cell(value: Any) -> str:
    if value is None:
        return ""
    return repr(value) if isinstance(value, float) else str(value)


def _csv_line(values: Sequence[Any]) -> str:
    buffer = io.StringIO()
    csv.writer(buffer, lineterminator="\n").writerow([_cell(v) for v in values])
    return buffer.getvalue()


# --- files: the output checked before anything is written, rows appended whole, resume past a cut line ----------

def _check_path(what: str, path: Any) -> None:
    if not isinstance(path, (str, os.PathLike)) or not os.fspath(path) or "\0" in os.fspath(path):
        raise SweepError(f"{what}: expected a file name (not empty, no NUL character), got "
                         f"{_printable(repr(path), 120)}")


def _same_file(a: str, b: str) -> bool:
    """Whether a and b are one file: the same device and inode (through links); False when either does not exist."""
    try:
        sa, sb = os.stat(a), os.stat(b)
    except OSError:
        return False
    return (sa.st_dev, sa.st_ino) == (sb.st_dev, sb.st_ino)


def _check_output(path: str, inputs: Sequence[tuple[str, str]]) -> None:
    """SweepError unless path can be the table: a regular file its owner may write, or a new name in an existing
    folder; never a symbolic link (an attacker's link in a shared folder would point the table at their victim),
    and none of the sweep's inputs (what, path), compared as files, not as names."""
    _check_path("--output", path)
    from hubbeam import _core  # the one check of an output's name, every writer's (printable.hpp)

    if why := _core.unsafe_character(os.fsencode(path)):
        raise SweepError(f"-o: expected a file name without control or format characters, got {why}")
    shown = _printable(path)
    try:
        st = os.lstat(path)
    except FileNotFoundError:
        st = None
    except OSError as e:
        raise SweepError(f"{shown}: cannot open for writing: {e.strerror}") from None
    if st is not None and stat.S_ISLNK(st.st_mode):
        raise SweepError(f"{shown}: expected a regular file or the name of a new one, got a symbolic link (hubbeam "
                         f"does not write through a link: give the file it points to)")
    if st is not None and stat.S_ISDIR(st.st_mode):
        raise SweepError(f"{shown}: expected a file for the sweep's table, got a directory (give -o DIR/NAME.csv)")
    if st is not None and not stat.S_ISREG(st.st_mode):
        raise SweepError(f"{shown}: expected a regular file for the sweep's table, got {_file_kind(st.st_mode)}")
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise SweepError(f"{shown}: expected a file in an existing folder, got a folder that does not exist")
    if st is not None and not st.st_mode & stat.S_IWUSR:
        # The rule of every hubbeam writer (output_file.cpp), root included.
        raise SweepError(f"{shown} is read-only (mode {stat.S_IMODE(st.st_mode):04o}): hubbeam does not replace a "
                         f"file you protected; chmod u+w it or choose another output")
    if not os.access(folder, os.W_OK) or (st is not None and not os.access(path, os.W_OK)):
        raise SweepError(f"{shown}: cannot write there (permission denied)")
    for what, other in inputs:
        if _same_file(path, other):
            raise SweepError(f"{shown}: expected an output other than the {what} ({_printable(other)}), got the "
                             f"same file")


def _table_mode(inputs: Sequence[os.stat_result]) -> int:
    """The permissions the table and its series files are created with (before the umask): read and write for
    everyone, less group's if one input is not readable by its group and less others' if one is not readable by
    others, so the table (whose rows come from those files) is never readable by someone who cannot read them."""
    mode = 0o666
    for st in inputs:
        if not st.st_mode & stat.S_IRGRP:
            mode &= ~0o070
        if not st.st_mode & stat.S_IROTH:
            mode &= ~0o007
    return mode


# DIR/.NAME.tmp-PID or .NAME.tmp-PID-N: a temporary file of a hubbeam writer (output_file.cpp names them so too).
_TEMPORARY = re.compile(r"\.(.+)\.tmp-(\d+)(?:-\d+)?")


def _clean_leftovers(folder: str, name: str | None) -> None:
    """Removes the temporary files of name (every name when None) in folder that a killed writer left: its pid no
    longer runs and the file is this user's. Called holding the table's lock, so no live hubbeam writes them."""
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return
    for entry in entries:
        m = _TEMPORARY.fullmatch(entry.name)
        if not m or (name is not None and m.group(1) != name) or int(m.group(2)) == os.getpid():
            continue
        try:
            os.kill(int(m.group(2)), 0)
            continue  # alive (or another user's): not ours to remove
        except ProcessLookupError:
            pass
        except (PermissionError, OverflowError):
            continue
        try:
            st = entry.stat(follow_symlinks=False)
            if stat.S_ISREG(st.st_mode) and st.st_uid == os.geteuid():
                os.remove(entry.path)
        except OSError:
            pass


def _series_dir(path: str) -> str:
    return os.path.splitext(path)[0] + ".series"


def _read_table(path: str, header: list[str]) -> tuple[list[tuple[list[str], str]], int, bool]:
    """An earlier run's table: its complete rows (fields and line), the byte length of its complete lines, and
    whether a last line was cut (no newline at its end or a wrong number of fields: a write that did not finish).
    SweepError if it is not this sweep's table (the message never quotes the file: it may be anybody's)."""
    shown = _printable(path)
    try:
        with open(path, "rb") as f:
            data = f.read()
    except FileNotFoundError:
        return [], 0, False
    except OSError as e:
        raise SweepError(f"{shown}: cannot read the table to resume: {e.strerror}") from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise SweepError(f"{shown}: expected this sweep's CSV table (UTF-8 text) to resume, got bytes that are not "
                         f"text at byte {e.start}; remove it, choose another output or give --no-resume") from None
    if not text:
        return [], 0, False
    lines = text.split("\n")
    complete, tail = lines[:-1], lines[-1]
    if not complete and _csv_line(header).startswith(tail):  # a header cut before its newline: nothing finished
        return [], 0, True
    found = next(csv.reader([complete[0] if complete else tail]), [])
    if found != header:
        raise SweepError(f"{shown}: expected the table of this sweep to resume (header {','.join(header)}), got a "
                         f"file with another first line; remove it, choose another output or give --no-resume")
    rows: list[tuple[list[str], str]] = []
    end = len(complete[0].encode()) + 1 if complete else 0
    cut = bool(tail)
    for n, line in enumerate(complete[1:], start=2):
        row = next(csv.reader([line]), [])
        if len(row) != len(header):
            if n == len(complete):  # the last line, cut by a full disk or a kill before its newline was written
                cut = True
                break
            raise SweepError(f"{shown}: line {n}: expected {len(header)} fields, got {len(row)}; remove the line or "
                             f"give --no-resume")
        end += len(line.encode()) + 1
        rows.append((row, line + "\n"))
    return rows, end, cut


class _OutputLock:
    """The lock every hubbeam writer takes beside its output, DIR/.NAME.lock (flock, as runtime/src/io/output_file.cpp):
    while one sweep or command writes a table, another that would write it is refused at once. The lock file is
    removed when released, so once locked it must still be the file at that path, else it is taken again."""

    def __init__(self, path: str, shown: str):
        target = os.path.abspath(path)
        self.path = os.path.join(os.path.dirname(target), "." + os.path.basename(target) + ".lock")
        for _ in range(100):
            try:
                fd = os.open(self.path, os.O_RDONLY | os.O_CREAT | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC,
                             0o666)
            except OSError as e:
                raise SweepError(f"{shown}: cannot create its lock file {_printable(self.path)}: {e.strerror}") \
                    from None
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError:
                os.close(fd)
                raise SweepError(f"another hubbeam is writing {shown} (it holds {_printable(self.path)}): wait for "
                                 f"it to finish, or write to another file") from None
            held = os.fstat(fd)
            try:
                now = os.stat(self.path)
                if (now.st_dev, now.st_ino) == (held.st_dev, held.st_ino):
                    self.fd = fd
                    return
            except OSError:
                pass
            os.close(fd)
        raise SweepError(f"{shown}: its lock file {_printable(self.path)} keeps changing")

    def release(self) -> None:
        try:
            os.remove(self.path)  # while still holding it: a writer waiting on this file re-checks and retries
        except OSError:
            pass
        os.close(self.fd)


class _Table:
    """The table file, appended one whole row at a time: each row is one write of one line, flushed, and a write
    that fails (a full disk) is cut back to the previous line before the error is raised, so the file never holds
    half a row. Opened without following a symbolic link; a new file (new=True: created exclusively, as a
    temporary file is) gets mode, and an existing one loses the permissions mode does not grant."""

    def __init__(self, path: str, shown: str, truncate_to: int | None, header: str | None, mode: int,
                 new: bool = False):
        self.shown = shown
        flags = os.O_WRONLY | os.O_CREAT | os.O_APPEND | os.O_CLOEXEC | os.O_NONBLOCK | os.O_NOFOLLOW
        try:
            self.fd = os.open(path, flags | (os.O_EXCL if new else 0), mode)
        except OSError as e:
            if e.errno == errno.ELOOP:
                raise SweepError(f"{shown}: expected a regular file or the name of a new one, got a symbolic link "
                                 f"(hubbeam does not write through a link: give the file it points to)") from None
            raise SweepError(f"{shown}: cannot open for writing: {e.strerror}") from None
        try:
            held = os.fstat(self.fd)
            if not stat.S_ISREG(held.st_mode):
                raise SweepError(f"{shown}: expected a regular file for the sweep's table, got "
                                 f"{_file_kind(held.st_mode)}")
            narrower = stat.S_IMODE(held.st_mode) & ~(0o777 & ~mode & 0o077)
            if narrower != stat.S_IMODE(held.st_mode):
                try:
                    os.fchmod(self.fd, narrower)  # rows of a private input go into a table no wider than it
                except OSError as e:
                    raise SweepError(f"{shown}: cannot narrow its permissions to mode {narrower:04o}, as the sweep's "
                                     f"inputs are private: {e.strerror}; choose another output") from None
            if truncate_to is not None:
                os.ftruncate(self.fd, truncate_to)
        except OSError as e:
            os.close(self.fd)
            raise SweepError(f"{shown}: cannot open for writing: {e.strerror}") from None
        except BaseException:
            os.close(self.fd)
            raise
        if header is not None:
            self.append(header)

    def append(self, line: str) -> None:
        data = line.encode()
        start = os.fstat(self.fd).st_size
        try:
            written = 0
            while written < len(data):
                written += os.write(self.fd, data[written:])
        except OSError as e:
            try:
                os.ftruncate(self.fd, start)
            except OSError:
                pass
            raise SweepError(f"{self.shown}: cannot write the table: {e.strerror}; it holds every point finished "
                             f"before, run the sweep again to resume") from None

    def close(self, sync: bool) -> None:
        try:
            if sync:
                os.fsync(self.fd)
        except OSError as e:
            raise SweepError(f"{self.shown}: cannot write the table: {e.strerror}") from None
        finally:
            os.close(self.fd)


def _save_series(folder: str, name: str, series: Any, mode: int) -> str:
    """The series as folder/name.npy (created with mode), written to a temporary file and renamed; returns its path
    relative to the table's folder."""
    import numpy as np

    final = os.path.join(folder, name + ".npy")
    temporary = os.path.join(folder, f".{name}.npy.tmp-{os.getpid()}")
    try:
        os.makedirs(folder, mode=0o700 | (mode & 0o044) | (mode & 0o044) >> 2, exist_ok=True)
        if os.path.islink(folder) or not os.path.isdir(folder):
            raise SweepError(f"{_printable(folder)}: expected the table's folder of tip series, got a symbolic link "
                             f"or a file (hubbeam does not write through a link)")
        fd = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC, mode)
        with open(fd, "wb") as f:
            np.save(f, np.asarray(series, dtype=float))
        os.replace(temporary, final)
    except BaseException as e:
        try:
            os.remove(temporary)
        except OSError:
            pass
        if isinstance(e, OSError):
            raise SweepError(f"{_printable(final)}: cannot write the tip series: {e.strerror}; the table holds every "
                             f"point finished before, run the sweep again to resume") from None
        raise
    return os.path.join(os.path.basename(folder), name + ".npy")


def _typed(column: str, text: str, folder: str) -> Any:
    """A cell's text as the value it was: None for an empty cell, str, int, bool, float, or the tip series' array."""
    if text == "":
        return None
    if column in _TEXT_COLUMNS:
        return text
    if column == "completed":
        return text == "True"
    if column in _INT_COLUMNS:
        return int(text)
    if column == "tip_series":
        import numpy as np

        return np.load(os.path.join(folder, text))
    try:
        return float(text)
    except ValueError:
        return text


# --- the cluster --------------------------------------------------------------------------------------------------

def _notebook_bar(total: int, before: int):
    """A tqdm progress bar where the sweep runs in a notebook (an IPython kernel, whose standard error is no terminal
    to rewrite a line on) and tqdm is installed (python3-tqdm); else None. tqdm's widget where ipywidgets is there
    too, its text bar otherwise."""
    if "ipykernel" not in sys.modules:
        return None
    try:
        try:
            import ipywidgets  # noqa: F401  (tqdm.notebook draws with it)
            from tqdm.notebook import tqdm
        except ImportError:
            from tqdm import tqdm
    except ImportError:
        return None
    return tqdm(total=total, initial=before, desc="sweep", unit="point", file=sys.stderr)


class _Progress:
    """One line on standard error per finished point, rewritten in place on a terminal; a tqdm bar in a notebook."""

    def __init__(self, total: int, before: int, enabled: bool):
        self.total, self.before, self.enabled = total, before, enabled
        self.done = self.failed = 0
        self.start = time.perf_counter()
        self.tty = enabled and sys.stderr.isatty()
        self.bar = _notebook_bar(total, before) if enabled else None

    def point(self, ok: bool) -> None:
        self.done += 1
        self.failed += 0 if ok else 1
        if self.bar is not None:
            self.bar.update(1)
            if self.failed:
                self.bar.set_postfix(not_ok=self.failed)
            return
        if not self.enabled:
            return
        elapsed = time.perf_counter() - self.start
        left = elapsed / self.done * (self.total - self.before - self.done)
        line = (f"sweep: {self.before + self.done} of {self.total} points ({self.before} from before), "
                f"{self.failed} not ok, {elapsed:.1f} s, about {left:.0f} s left")
        print(("\r" + line + "\033[K") if self.tty else line, end="" if self.tty else "\n", file=sys.stderr, flush=True)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
        elif self.tty and self.done:
            print(file=sys.stderr)


def _import_hubbeam() -> str:
    import hubbeam

    return hubbeam.__version__


def local_cluster(workers: int | None = None, dashboard: bool = False):
    """A local Dask cluster for sweeps and a client of it: (client, close). One worker with `workers` threads (one
    per core by default) in this process: the runs release the GIL, so threads run in parallel, and no process is
    spawned (a script without an `if __name__ == "__main__":` guard, a notebook and stdin work alike). Its scheduler
    and worker listen on 127.0.0.1 only, speak TLS with credentials made for this cluster alone (a client without
    them is refused), and the dashboard is off unless asked for (then on 127.0.0.1:8787, or a free port)."""
    from distributed import Client, Scheduler, SpecCluster, Worker
    from distributed.security import Security

    security = Security.temporary()  # a fresh CA and certificates, in memory, for this cluster only
    common = {"host": "127.0.0.1", "protocol": "tls://", "security": security}
    # Every HTTP server on loopback: Dask's default address for them is every interface.
    scheduler = {"cls": Scheduler, "options": {**common, "dashboard": dashboard,
                                               "dashboard_address": "127.0.0.1:8787" if dashboard else "127.0.0.1:0"}}
    worker = {"cls": Worker, "options": {**common, "nthreads": workers or os.cpu_count() or 1, "dashboard": False,
                                         "dashboard_address": "127.0.0.1:0"}}
    cluster = SpecCluster(scheduler=scheduler, workers={0: worker}, security=security, silence_logs=logging.CRITICAL)
    try:
        client = Client(cluster, security=security)
    except BaseException:
        cluster.close()
        raise

    def close() -> None:
        # Shutting the cluster down on a loaded machine can time out inside Dask's event loop; the table is complete
        # (or as complete as it will be) by then, so that is no failure of the sweep, and asyncio's report of it
        # ("Future exception was never retrieved") is not printed.
        quiet = logging.getLogger("asyncio")
        level = quiet.level
        quiet.setLevel(logging.CRITICAL)
        try:
            for step in (client.close, cluster.close):
                try:
                    step()
                except Exception:  # noqa: BLE001 - see above
                    pass
        finally:
            quiet.setLevel(level)

    return client, close


def _tcp_reachable(address: str) -> str | None:
    """None if a TCP connection to the scheduler's host and port opens within 3 s, else why not."""
    host_port = address.split("://", 1)[-1]
    host, _, port = host_port.rpartition(":")
    try:
        with socket.create_connection((host.strip("[]"), int(port)), timeout=3):
            return None
    except ValueError:
        return "expected host:port after the protocol"
    except OSError as e:
        return e.strerror or str(e) or type(e).__name__


def _remote_client(scheduler: str, security: Any):
    """A client of the scheduler at its address, or SweepError within a few seconds naming what is wrong."""
    from distributed import Client

    shown = _printable(scheduler)
    protocol = scheduler.split("://", 1)[0] if "://" in scheduler else "tcp"
    if protocol not in ("tcp", "tls"):
        raise SweepError(f"--scheduler: expected a tls://host:port or tcp://host:port address, got {shown}")
    if protocol == "tls" and security is None:
        raise SweepError(f"--scheduler: expected the cluster's certificates for {shown} (--tls-ca-file, --tls-cert, "
                         f"--tls-key; security= in Python)")
    if protocol == "tcp":
        print(f"hubbeam: warning: {shown} is a plain tcp:// scheduler: it runs whatever any client that reaches it "
              f"sends, as the workers' user; use tls:// with certificates (docs/python.md, Security)", file=sys.stderr)
    why = _tcp_reachable(scheduler)
    if why is not None:
        raise SweepError(f"--scheduler: cannot reach {shown}: {why}")
    try:
        return Client(scheduler, security=security, timeout=10)
    except (OSError, TimeoutError) as e:
        raise SweepError(f"--scheduler: cannot connect to {shown}: {_printable(e, 200)}") from None


def _security_of_files(ca: str | None, cert: str | None, key: str | None):
    """A Security for a tls:// scheduler from the CA's certificate and this client's certificate and key."""
    given = {"--tls-ca-file": ca, "--tls-cert": cert, "--tls-key": key}
    if not any(given.values()):
        return None
    for option, path in given.items():
        if not path:
            raise SweepError(f"{option}: expected a PEM file (a tls:// scheduler needs all three of --tls-ca-file, "
                             f"--tls-cert, --tls-key), got nothing")
        if not os.path.isfile(path):
            raise SweepError(f"{option}: cannot open {_printable(path)}: expected a PEM file")
    from distributed.security import Security

    return Security(tls_ca_file=ca, tls_client_cert=cert, tls_client_key=key, require_encryption=True)


# The last sweep's timing: the wall time from the first task submitted to the last row, the worker threads, the sum
# of the points' own in-process times, the cluster's start-up, and the overhead (workers x wall - runs) / runs
# (python3 -m hubbeam.benchmark reads it: meaningful over many points, not over three).
last_timing: dict[str, float] = {}


def run_sweep(spec: str | os.PathLike | Mapping[str, Any], *, output: str | None = None,
              scheduler: Any = None, workers: int | None = None, resume: bool = True,
              progress: bool = True, batch: int | None = None, security: Any = None,
              dashboard: bool = False) -> list[dict[str, Any]]:
    """Runs every point not yet in the output table on Dask and appends its row as it finishes. Returns the table:
    one dict per point in the sweep's order, values typed (floats, ints, None for an empty cell, tip_series an
    n x 2 array of t and tip_uy). scheduler: a Dask scheduler's address (tls://host:8786 with security=, a
    distributed.security.Security with this client's certificates; tcp:// is unauthenticated) or a
    distributed.Client; else a local cluster of `workers` threads (default one per core; dashboard=True serves
    Dask's dashboard on 127.0.0.1). batch: points per task (default: about four tasks per worker, at most 16 points
    each); a batch's rows are written when it finishes. resume=False recomputes every point into a new table that
    replaces the old one only once it is complete."""
    import hubbeam

    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise SweepError(f"--workers: expected a number of worker threads >= 1, got {_printable(repr(workers))}")
    if batch is not None and (isinstance(batch, bool) or not isinstance(batch, int) or batch < 1):
        raise SweepError(f"batch: expected a number of points per task >= 1, got {_printable(repr(batch))}")
    # Everything is checked before the table is touched: the sweep, its points, the base scene, the files they
    # read, the output.
    sweep = load_sweep(spec)
    if output is not None:
        _check_path("--output", output)
    path = os.fspath(output) if output is not None else sweep["output"]
    points = expand(sweep)
    runs = [_resolved(p, sweep["base"]) for p in points]  # as the core takes them: file keys' paths resolved
    _check_path("scene", sweep["scene"])
    try:
        scene_text = hubbeam._scene_file_text(sweep["scene"])  # as hubbeam.run reads a scene
    except (OSError, ValueError) as e:
        raise _sweep_error(e) from None
    hubbeam._check_scene(scene_text, sweep["scene"])  # a bad base scene stops the sweep before any task
    # What every point reads (the core's list: every file key of the scene's schema), by content for its key, by
    # identity for the output checks, by permissions for the table's.
    scene_files = _SceneFiles(scene_text, sweep["scene"])
    point_files = [scene_files.of_point(r) for r in runs]
    tables = _Inputs()
    version = hubbeam.generator_version() + " " + hubbeam.__version__
    ids = [point_key(p, scene_text, tables.of_point(f), version) for p, f in zip(points, point_files)]
    inputs = [("base scene", sweep["scene"])] + [("sweep file", sweep["where"])] * (sweep["where"] != "<dict sweep>")
    inputs += list(dict.fromkeys((f"scene's {k}", v) for f in point_files for k, v in f.items()))
    _check_output(path, inputs)
    readable = [os.stat(f) for _, f in inputs[:2] if os.path.exists(f)] + list(tables.stats.values())
    mode = _table_mode(readable)
    try:  # a table that replaces the old one is no wider than it either (the rule of every hubbeam writer)
        replace_mode = mode & (stat.S_IMODE(os.stat(path).st_mode) | 0o600)
    except OSError:
        replace_mode = mode
    # Taken before the table is read: a second sweep (or a hubbeam command) writing the same table is refused.
    lock = _OutputLock(path, _printable(path))
    try:
        shown = _printable(path)
        folder = os.path.dirname(os.path.abspath(path))
        series_folder = _series_dir(os.path.abspath(path))
        # A series folder that is a link or no folder is refused before anything is written or removed (the table's
        # header included), not at the first point's series; one the sweep keeps no series in is left alone.
        if os.path.islink(series_folder) or (os.path.lexists(series_folder) and not os.path.isdir(series_folder)):
            if "tip_series" in sweep["keep"]:
                raise SweepError(f"{_printable(series_folder)}: expected the table's folder of tip series, got a "
                                 f"symbolic link or a file (hubbeam does not write through a link)")
        else:
            _clean_leftovers(series_folder, None)
        _clean_leftovers(folder, os.path.basename(path))  # what a killed writer of this table left
        keys = list(dict.fromkeys(k for p in points for k in p))
        header = _columns(keys, sweep["keep"], sweep["frequencies"])
        rows, good_end, cut = _read_table(path, header) if resume else ([], 0, False)
        # A row is done when its key is a point's and its series file (if kept) is there. A row of a point of this
        # sweep that is not done (its scene, tables or version changed, or its series is gone) is stale: dropped
        # from the table when its point is written again. Rows of points not in this sweep stay as they are.
        current = set(ids)
        values_of = {tuple(_cell(p.get(k)) for k in keys) for p in points}
        done: dict[str, list[str]] = {}
        kept_lines: list[str] = []
        for row, line in rows:
            series = dict(zip(header, row)).get("tip_series")
            if row[0] in current and not (series and not os.path.exists(os.path.join(folder, series))):
                done[row[0]] = row
            elif tuple(row[1:1 + len(keys)]) in values_of:
                continue
            kept_lines.append(line)
        stale = len(kept_lines) < len(rows)
        todo = [(i, p) for i, p in enumerate(runs) if ids[i] not in done]
        lines: dict[str, list[str]] = dict(done)
        if not todo and progress:
            print(f"sweep: all {len(points)} points are in {shown} already (the same scene, tables and version); "
                  f"--no-resume recomputes them", file=sys.stderr)
        if todo:
            started_cluster = time.perf_counter()
            close = None
            if scheduler is None:
                client, close = local_cluster(workers, dashboard)
                if progress:
                    print(f"sweep: local cluster at {client.scheduler.address} (TLS, this sweep's certificates only)"
                          + (f", dashboard {client.dashboard_link}" if dashboard else ""), file=sys.stderr, flush=True)
            elif isinstance(scheduler, (str, os.PathLike)):
                client = _remote_client(os.fspath(scheduler), security)
                close = client.close
            elif hasattr(scheduler, "submit") and hasattr(scheduler, "scheduler_info"):
                client = scheduler  # the caller's distributed.Client: theirs to close
            else:
                raise SweepError(f"scheduler: expected an address or a distributed.Client, got "
                                 f"{_printable(type(scheduler).__name__)}")
            table = None
            temporary = None
            finished = False
            interrupted = True
            try:
                client.run(_import_hubbeam)  # each worker's one-off imports, part of its start-up, not of a point
                n_workers = sum(w.get("nthreads", 1) for w in client.scheduler_info().get("workers", {}).values()) or 1
                start_up = time.perf_counter() - started_cluster
                # Only now that the cluster answers is a file written: the table, or with resume=False a new table
                # beside it that replaces the old one once complete.
                if resume and not stale:
                    if cut and progress:
                        print(f"sweep: {shown}: its last line was cut (a write that did not finish): dropped, that point "
                              f"runs again", file=sys.stderr)
                    table = _Table(path, shown, good_end, _csv_line(header) if good_end == 0 else None, mode)
                else:
                    # A new table beside the old one, which it replaces whole: with stale rows dropped it starts with
                    # the rows kept; with resume=False it replaces the old table only once complete.
                    temporary = os.path.join(folder, f".{os.path.basename(path)}.tmp-{os.getpid()}")
                    table = _Table(temporary, shown, None, _csv_line(header) + "".join(kept_lines), replace_mode,
                                   new=True)
                    if resume:
                        try:
                            os.replace(temporary, path)
                        except OSError as e:
                            raise SweepError(f"{shown}: cannot replace the table without its stale rows: "
                                             f"{e.strerror}") from None
                        temporary = None
                started = time.perf_counter()
                run_total = 0.0
                meter = _Progress(len(points), len(points) - len(todo), progress)
                try:
                    from distributed import as_completed

                    size = batch or max(1, min(16, len(todo) // (4 * n_workers)))
                    batches = [todo[k:k + size] for k in range(0, len(todo), size)]
                    futures = {client.submit(run_points, scene_text, sweep["scene"], [p for _, p in b], sweep["keep"],
                                             sweep["frequencies"], key=f"hubbeam-points-{ids[b[0][0]]}-{len(b)}",
                                             pure=False): b for b in batches}
                    for future in as_completed(futures):
                        b = futures[future]
                        try:
                            rows = future.result()
                        except Exception as e:  # noqa: BLE001 - a lost worker: its points are rows with the status
                            rows = [{"status": "error: the task failed: " + _printable(f"{type(e).__name__}: {e}")}
                                    for _ in b]
                        for (i, _), row in zip(b, rows):
                            if row.get("tip_series") is not None:
                                row["tip_series"] = _save_series(series_folder, ids[i], row["tip_series"], mode)
                            values = [ids[i], *(points[i].get(k) for k in keys)] + \
                                [row.get(c) for c in header[len(keys) + 1:]]
                            line = _csv_line(values)
                            table.append(line)  # one whole line per write: a reader never sees half of it
                            lines[ids[i]] = next(csv.reader([line]))
                            run_total += row["run_seconds"] if isinstance(row.get("run_seconds"), float) else 0.0
                            meter.point(row.get("status") == "ok")
                finally:
                    meter.close()
                wall = time.perf_counter() - started
                table.close(sync=True)
                table = None
                if temporary is not None:
                    try:
                        os.replace(temporary, path)
                    except OSError as e:
                        raise SweepError(f"{shown}: cannot replace the old table with the new one: {e.strerror}") from None
                    temporary = None
                finished = True
                interrupted = False
            except SweepError:
                interrupted = False
                raise
            finally:
                if interrupted and scheduler is None:
                    hubbeam._cancel_runs()  # the local workers are this process's threads: their runs stop now
                if table is not None:
                    table.close(sync=False)
                if temporary is not None:  # an unfinished replacement: the old table stays as it was
                    try:
                        os.remove(temporary)
                    except OSError:
                        pass
                if close is not None:
                    close()
            if finished:
                overhead = (wall * n_workers - run_total) / run_total if run_total > 0 else float("nan")
                last_timing.update(wall=wall, workers=n_workers, runs=run_total, overhead=overhead, start_up=start_up)
                if progress:
                    print(f"sweep: {len(todo)} points in {wall:.2f} s on {n_workers} worker{'s' if n_workers != 1 else ''}, after {start_up:.2f} s to "
                          f"start or reach the cluster; the runs themselves took {run_total:.2f} s of the workers' "
                          f"{wall * n_workers:.2f} s (the rest is Dask's scheduling and transfers, and workers left "
                          f"without a point)", file=sys.stderr)
        by_point = {k: dict(zip(header, row)) for k, row in lines.items()}
        out = []
        for i, k in enumerate(ids):
            row = {c: _typed(c, v, folder) for c, v in by_point[k].items()}
            row.update({key: points[i].get(key) for key in keys})  # the point's own values, as the sweep gave them
            out.append(row)
        return out
    finally:
        lock.release()


class _Terminated(KeyboardInterrupt):
    """A signal that ends the sweep (SIGTERM, SIGHUP, SIGQUIT), raised where the sweep is so that the cluster closes,
    the table is left whole and the lock and temporary files are removed."""

    def __init__(self, signum: int):
        super().__init__(signum)
        self.signum = signum


# The signals that end a sweep as Ctrl-C does, keeping its rows. SIGXFSZ stays ignored (Python's own setting): a
# write past a file-size limit then fails with EFBIG, and the sweep ends as on a full disk, rows kept, exit 2.
_ENDING_SIGNALS = (signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT)


def _ignore_dask_configuration() -> None:
    """Dask with its own defaults only, for `hubbeam sweep`: no configuration file (~/.config/dask, $DASK_CONFIG,
    /etc/dask) and no DASK_* variable is read. Dask's configuration can name Python to run in this process (a
    scheduler's, worker's or client's "preload": a module, a file, a URL), and `hubbeam sweep` runs only hubbeam's
    Python (its interpreter is isolated, python3 -I). Importing dask.config reads the files: where this runs first
    (as in `hubbeam sweep`) it is imported with HOME and DASK_ROOT_CONFIG pointing at an empty private folder, so
    that none is even parsed; in any case the configuration is then reset to the defaults and the search path
    emptied for any later refresh, before a scheduler, worker or client reads it."""
    import shutil
    import tempfile

    for name in [n for n in os.environ if n.startswith("DASK_")]:
        del os.environ[name]
    if "dask.config" not in sys.modules:
        empty = tempfile.mkdtemp(prefix="hubbeam-no-dask-config-")
        home = os.environ.get("HOME")
        os.environ.update(HOME=empty, DASK_ROOT_CONFIG=empty)
        try:
            import dask.config  # noqa: F401
        finally:
            del os.environ["DASK_ROOT_CONFIG"]
            if home is None:
                del os.environ["HOME"]
            else:
                os.environ["HOME"] = home  # the variant cache's default folder is under it
            shutil.rmtree(empty, ignore_errors=True)
    import dask.config

    dask.config.paths[:] = []  # collect()'s default: a later refresh() reads no file either
    dask.config.refresh(paths=[], env={})


def main(argv: Sequence[str] | None = None) -> int:
    """hubbeam sweep: returns the exit code (0 done, 2 bad input, 130 interrupted, 128 + the signal when ended by
    SIGTERM, SIGHUP or SIGQUIT)."""
    _ignore_dask_configuration()
    # The command's own lines say what went wrong; Dask's event loop may still report a shutdown timed out on a
    # loaded machine when its futures are collected at exit, which would add lines to a one-line message.
    logging.getLogger("asyncio").setLevel(logging.CRITICAL)
    parser = argparse.ArgumentParser(prog="hubbeam sweep", description="Runs a parameter sweep on Dask "
                                     "(docs/python.md). Exit codes: 0 every point has a row (whatever its status), "
                                     "2 bad input or an output that cannot be written, 130 interrupted, 143 "
                                     "terminated (129 SIGHUP, 131 SIGQUIT; finished points kept; run again to "
                                     "resume).")
    parser.add_argument("sweep", help="SWEEP.toml: scene, grid and/or [[points]], keep, frequencies, output")
    parser.add_argument("-o", "--output", help="CSV table (default: the sweep's output, else SWEEP.csv beside the "
                        "sweep file)")
    parser.add_argument("--scheduler", help="a running Dask scheduler's address: tls://host:8786 with --tls-ca-file, "
                        "--tls-cert and --tls-key (tcp:// runs whatever any client sends); default: a local cluster "
                        "on 127.0.0.1 with TLS")
    parser.add_argument("--tls-ca-file", help="PEM: the certificate authority of the tls:// scheduler's cluster")
    parser.add_argument("--tls-cert", help="PEM: this client's certificate, signed by that authority")
    parser.add_argument("--tls-key", help="PEM: this client's private key")
    parser.add_argument("--workers", type=int, help="local cluster's worker threads (default: one per core)")
    parser.add_argument("--dashboard", action="store_true", help="serve the local cluster's Dask dashboard on "
                        "127.0.0.1:8787 (off by default)")
    parser.add_argument("--no-resume", action="store_true", help="recompute every point (the new table replaces "
                        "the old one once complete)")
    args = parser.parse_args(argv)

    def terminate(signum, frame):
        raise _Terminated(signum)

    for signum in _ENDING_SIGNALS:
        signal.signal(signum, terminate)
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    try:
        security = _security_of_files(args.tls_ca_file, args.tls_cert, args.tls_key)
        run_sweep(args.sweep, output=args.output, scheduler=args.scheduler, workers=args.workers,
                  resume=not args.no_resume, security=security, dashboard=args.dashboard)
    except ValueError as e:  # SweepError and the core's bad-input errors: one line each
        print(e if isinstance(e, SweepError) else _printable(e), file=sys.stderr)
        return 2
    except _Terminated as e:
        print(f"hubbeam: sweep terminated by {signal.Signals(e.signum).name}; the finished points are in the table, "
              f"run again to resume", file=sys.stderr)
        return 128 + e.signum
    except KeyboardInterrupt:
        print("hubbeam: sweep interrupted; the finished points are in the table, run again to resume", file=sys.stderr)
        return 130
    return 0


if __name__ == "__main__":
    sys.exit(main())
