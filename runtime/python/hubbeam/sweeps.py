"""Parameter sweeps on Dask: `hubbeam sweep SWEEP.toml` and hubbeam.sweep(...) (README "Parameter sweeps").

A sweep is a base scene plus a grid and/or a list of overrides of any scene keys. Every point runs as one Dask
task, on a local cluster (one worker process per core) or on a running scheduler, and lands as one row of a CSV
table: the point's keys, its status and the quantities kept. A point that fails is a row with its status; an
interrupted sweep resumes without recomputing the points already in the table (keyed by the point's overrides
and the generator's version).
"""
from __future__ import annotations

import argparse
import csv
import hashlib
import io
import itertools
import json
import math
import os
import sys
import time
import tomllib
from typing import Any, Mapping, Sequence

# What a sweep may keep per point: the run's summary values, its tip_uy series, the bending frequencies about the
# point's steady spin, and the invariant drift relative to the vibration energy.
SUMMARY_VALUES = ("completed", "t_reached", "max_abs_tip_uy", "jacobi_drift", "vibration_energy", "steps",
                  "rhs_evals", "jacobian_evals", "wall_seconds", "variant", "source", "stepper")
DERIVED_VALUES = ("relative_drift", "tip_series", "frequencies")
DEFAULT_KEEP = ("max_abs_tip_uy", "relative_drift", "wall_seconds")


class SweepError(ValueError):
    """A sweep that cannot start: a bad sweep file, option or existing output (one line naming it)."""


def _fail(where: str, key: str, expected: str, got: Any) -> None:
    raise SweepError(f"{where}: {key}: expected {expected}, got {got!r}")


def load_sweep(spec: str | os.PathLike | Mapping[str, Any]) -> dict[str, Any]:
    """The sweep of a SWEEP.toml file or of a dict with the same keys, checked: scene (the base scene's path,
    relative to the sweep file), set (key -> value for every point), grid (key -> list of values), points (list of
    key -> value tables), keep (names from SUMMARY_VALUES and DERIVED_VALUES), frequencies (how many), output (the
    CSV)."""
    if isinstance(spec, Mapping):
        where, base_dir, sweep = "<dict sweep>", os.getcwd(), dict(spec)
    else:
        where = os.fspath(spec)
        try:
            with open(where, "rb") as f:
                sweep = tomllib.load(f)
        except OSError as e:
            raise SweepError(f"{where}: cannot open: {e.strerror}") from None
        except tomllib.TOMLDecodeError as e:
            raise SweepError(f"{where}: {e}") from None
        base_dir = os.path.dirname(os.path.abspath(where))
    known = {"scene", "set", "grid", "points", "keep", "frequencies", "output"}
    for key in sweep:
        if key not in known:
            _fail(where, key, "one of " + ", ".join(sorted(known)), "an unknown key")
    if not isinstance(sweep.get("scene"), str):
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
        output = (os.path.splitext(os.path.basename(where))[0] if where != "<dict sweep>" else "sweep") + ".csv"
    if not isinstance(output, str):
        _fail(where, "output", "a file name", output)
    return {"where": where, "scene": scene, "set": dict(common), "grid": dict(grid), "points": points, "keep": list(keep),
            "frequencies": frequencies, "output": output}


def _full_key(name: str, where: str) -> str:
    import hubbeam

    keys = hubbeam.scene_keys()
    if name in keys:
        return name
    matches = [k for k in keys if k.split(".", 1)[1] == name]
    if len(matches) != 1:
        _fail(where, name, "a scene key (README: Scene files)", "an unknown key")
    return matches[0]


def expand(sweep: Mapping[str, Any]) -> list[dict[str, Any]]:
    """Every point of the sweep, as dotted scene keys: each combination of the grid, then each [[points]] table,
    all on top of the keys of [set]. Without grid and points, the one point [set] makes."""
    where = sweep["where"]
    common = {_full_key(k, where): v for k, v in sweep["set"].items()}
    grid_keys = [_full_key(k, where) for k in sweep["grid"]]
    out = []
    if sweep["grid"]:
        for combo in itertools.product(*sweep["grid"].values()):
            out.append({**common, **dict(zip(grid_keys, combo))})
    for point in sweep["points"]:
        out.append({**common, **{_full_key(k, where): v for k, v in point.items()}})
    return out or [common]


def point_key(point: Mapping[str, Any], version: str) -> str:
    """The point's identity for resuming: its overrides and the generator version that computes it."""
    text = json.dumps(sorted(point.items()), default=str) + "\n" + version
    return hashlib.sha256(text.encode()).hexdigest()[:16]


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
    """One point, on a worker: its row. Never raises: bad input, an unstable run or any error is the status."""
    import numpy as np

    import hubbeam

    row: dict[str, Any] = {}
    start = time.perf_counter()
    try:
        # The base scene travels as text, so a remote worker needs no copy of the file.
        r = hubbeam._run_text(scene_text, scene_name, point)
        row["status"] = "ok" if r.completed else "stopped: " + r.failure
        for k in keep:
            if k in SUMMARY_VALUES:
                row[k] = getattr(r, k)
            elif k == "relative_drift":
                row[k] = r.jacobi_drift / r.vibration_energy if r.vibration_energy > 0 else ""
            elif k == "tip_series":
                row[k] = " ".join(repr(float(v)) for v in r.tip_uy)
            elif k == "frequencies":
                # About the point's steady spin: the rate the hub ends at when prescribed, at rest for a free hub.
                omega = 0.0 if "_torque_" in r.variant else abs(float(r.theta_dot[-1]))
                m = hubbeam._modes_text(scene_text, scene_name, point, [omega])
                hz = m["hz"][m["kind"] == "bending"][:frequencies]
                for i in range(frequencies):
                    row[f"f{i + 1}_hz"] = float(hz[i]) if i < len(hz) else ""
        row["run_seconds"] = r.in_process_seconds  # as hubbeam run spends in process: load, model, integrate
    except ValueError as e:
        row["status"] = "error: " + str(e)
    except Exception as e:  # noqa: BLE001 - a point's failure must never end the sweep
        row["status"] = f"error: {type(e).__name__}: {e}"
    row.setdefault("run_seconds", time.perf_counter() - start)
    return row


def _csv_line(values: Sequence[Any]) -> str:
    buffer = io.StringIO()
    csv.writer(buffer, lineterminator="\n").writerow(
        ["" if v is None else (repr(v) if isinstance(v, float) else v) for v in values])
    return buffer.getvalue()


def _done_points(path: str, header: list[str]) -> dict[str, dict[str, str]]:
    """The rows already in an earlier run's table, by point key; SweepError if it is another table."""
    if not os.path.exists(path):
        return {}
    with open(path, newline="") as f:
        reader = csv.reader(f)
        found = next(reader, None)
        if found is None:
            return {}
        if found != header:
            raise SweepError(f"{path}: expected the table of this sweep to resume (header {','.join(header)}), got "
                             f"the header {','.join(found)}; remove it or choose another output")
        return {row[0]: dict(zip(header, row)) for row in reader if len(row) == len(header)}


class _Progress:
    """One line on standard error per finished point, rewritten in place on a terminal."""

    def __init__(self, total: int, before: int, enabled: bool):
        self.total, self.before, self.enabled = total, before, enabled
        self.done = self.failed = 0
        self.start = time.perf_counter()
        self.tty = enabled and sys.stderr.isatty()

    def point(self, ok: bool) -> None:
        self.done += 1
        self.failed += 0 if ok else 1
        if not self.enabled:
            return
        elapsed = time.perf_counter() - self.start
        left = elapsed / self.done * (self.total - self.before - self.done)
        line = (f"sweep: {self.before + self.done} of {self.total} points ({self.before} from before), "
                f"{self.failed} not ok, {elapsed:.1f} s, about {left:.0f} s left")
        print(("\r" + line + "\033[K") if self.tty else line, end="" if self.tty else "\n", file=sys.stderr, flush=True)

    def close(self) -> None:
        if self.tty and self.done:
            print(file=sys.stderr)


def _import_hubbeam() -> str:
    import hubbeam

    return hubbeam.__version__


def _client(scheduler: str | None, workers: int | None):
    """A Dask client: of the scheduler at its address, or of a local cluster of single-threaded worker processes
    (one per core by default) that can import hubbeam from where this process did."""
    from distributed import Client, LocalCluster

    if scheduler:
        return Client(scheduler), None
    import hubbeam

    package_parent = os.path.dirname(os.path.dirname(os.path.abspath(hubbeam.__file__)))
    paths = [package_parent] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]
    os.environ["PYTHONPATH"] = os.pathsep.join(dict.fromkeys(paths))  # the worker processes inherit it
    cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                           dashboard_address=None)
    return Client(cluster), cluster


# The last sweep's timing: the wall time from the first task submitted to the last row, the workers, the sum of the
# points' own in-process times, and the overhead (workers x wall - runs) / runs (python3 -m hubbeam.benchmark reads
# it).
last_timing: dict[str, float] = {}


def run_sweep(spec: str | os.PathLike | Mapping[str, Any], *, output: str | None = None,
              scheduler: str | None = None, workers: int | None = None, resume: bool = True,
              progress: bool = True, batch: int | None = None) -> list[dict[str, str]]:
    """Runs every point not yet in the output table on Dask and appends its row as it finishes. Returns the table
    (the rows of all points, in the sweep's order, values as written). scheduler: a Dask scheduler's address
    (tcp://host:8786); else a local cluster of `workers` processes (default one per core). batch: points per task
    (default: about four tasks per worker, at most 16 points each, so that short points share Dask's per-task cost
    and the workers stay balanced); a batch's rows are written when it finishes."""
    import hubbeam

    if workers is not None and not (isinstance(workers, int) and workers >= 1):
        raise SweepError(f"--workers: expected a number of worker processes >= 1, got {workers!r}")
    sweep = load_sweep(spec)
    path = output or sweep["output"]
    points = expand(sweep)
    keys = list(dict.fromkeys(k for p in points for k in p))
    header = _columns(keys, sweep["keep"], sweep["frequencies"])
    version = hubbeam.generator_version()
    ids = [point_key(p, version) for p in points]
    done = _done_points(path, header) if resume else {}
    if not resume and os.path.exists(path):
        os.remove(path)
    try:
        with open(sweep["scene"], encoding="utf-8") as f:
            scene_text = f.read()
    except OSError as e:
        raise SweepError(f"{sweep['scene']}: cannot open: {e.strerror}") from None
    hubbeam._check_scene(scene_text, sweep["scene"])  # a bad base scene stops the sweep before any task
    todo = [(i, p) for i, p in enumerate(points) if ids[i] not in done]
    table = dict(done)
    meter = _Progress(len(points), len(points) - len(todo), progress)
    if not todo and progress:
        print(f"sweep: all {len(points)} points are in {path} already (this generator version); --no-resume "
              f"recomputes them", file=sys.stderr)
    if todo:
        new_file = not os.path.exists(path) or os.path.getsize(path) == 0
        with open(path, "a", encoding="utf-8") as out:
            if new_file:
                out.write(_csv_line(header))
                out.flush()
            client, cluster = _client(scheduler, workers)
            client.run(_import_hubbeam)  # each worker's one-off imports, part of its start-up, not of a point
            n_workers = len(client.scheduler_info().get("workers", {})) or 1
            started = time.perf_counter()
            run_total = 0.0
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
                        rows = [{"status": f"error: the task failed: {type(e).__name__}: {e}"} for _ in b]
                    for (i, _), row in zip(b, rows):
                        values = [ids[i], *(points[i].get(k, "") for k in keys)] + \
                            [row.get(c, "") for c in header[len(keys) + 1:]]
                        line = _csv_line(values)
                        out.write(line)  # one whole line per write: a reader never sees half of it
                        table[ids[i]] = dict(zip(header, next(csv.reader([line]))))
                        run_total += row["run_seconds"] if isinstance(row.get("run_seconds"), float) else 0.0
                        meter.point(row.get("status") == "ok")
                    out.flush()
            finally:
                meter.close()
                wall = time.perf_counter() - started
                overhead = (wall * n_workers - run_total) / run_total if run_total > 0 else float("nan")
                last_timing.update(wall=wall, workers=n_workers, runs=run_total, overhead=overhead)
                client.close()
                if cluster is not None:
                    cluster.close()
            if progress:
                print(f"sweep: {len(todo)} points in {wall:.2f} s on {n_workers} workers; the runs' own time {run_total:.2f} s; "
                      f"overhead {100 * overhead:.0f} % (workers x wall against the runs' time)", file=sys.stderr)
    return [table[k] for k in ids]


def main(argv: Sequence[str] | None = None) -> int:
    """hubbeam sweep: returns the exit code (0 done, 2 bad input, 130 interrupted)."""
    parser = argparse.ArgumentParser(prog="hubbeam sweep", description="Runs a parameter sweep on Dask (README: "
                                     "Parameter sweeps). Exit codes: 0 every point has a row (whatever its status), "
                                     "2 bad input, 130 interrupted (finished points kept; run again to resume).")
    parser.add_argument("sweep", help="SWEEP.toml: scene, grid and/or [[points]], keep, frequencies, output")
    parser.add_argument("-o", "--output", help="CSV table (default: the sweep's output, else SWEEP.csv)")
    parser.add_argument("--scheduler", help="a running Dask scheduler's address (tcp://host:8786); default: a local "
                        "cluster")
    parser.add_argument("--workers", type=int, help="local cluster's worker processes (default: one per core)")
    parser.add_argument("--no-resume", action="store_true", help="recompute every point (replaces the table)")
    args = parser.parse_args(argv)
    try:
        run_sweep(args.sweep, output=args.output, scheduler=args.scheduler, workers=args.workers,
                  resume=not args.no_resume)
    except SweepError as e:
        print(e, file=sys.stderr)
        return 2
    except ValueError as e:
        print(e, file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("hubbeam: sweep interrupted; the finished points are in the table, run again to resume", file=sys.stderr)
        return 130
    return 0


if __name__ == "__main__":
    sys.exit(main())
