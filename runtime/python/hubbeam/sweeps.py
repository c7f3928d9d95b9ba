"""Parameter sweeps on Dask: `hubbeam sweep SWEEP.toml` and hubbeam.sweep(...) (docs/python.md, "Sweeps").

A sweep is a base scene plus a grid and/or a list of overrides of any scene keys. Every point runs as one Dask
task, on a local cluster (worker threads of this process: the runs release the GIL) or on a running scheduler,
and lands as one row of a CSV table: the point's keys, its status and the quantities kept. A point that fails is a
row with its status; an interrupted sweep resumes without recomputing the points already in the table (keyed by
the effective scene: the base scene's text, the content of the tables it names, the point's overrides and the
model's version). A kept tip series goes to one .npy file per point beside the table, and its cell names that file.

The sweep's parts: its specification and points (sweep_spec), where it may write (sweep_output), its table and
resuming (sweep_table), its cluster (sweep_cluster); here the points' runs, run_sweep's steps and the command.
"""
from __future__ import annotations

import argparse
import csv
import dataclasses
import logging
import os
import signal
import sys
import time
from typing import Any, Mapping, Sequence

from .sweep_cluster import (_connect, _ignore_dask_configuration, _import_hubbeam, _Progress, _security_of_files,
                            local_cluster)
from .sweep_output import _check_output, _OutputLock, _prepare_folders, _replace_mode, _series_dir, _table_mode
from .sweep_spec import (DEFAULT_KEEP, DERIVED_VALUES, ELASTIC_KINDS, SUMMARY_VALUES, SweepError, _base_scene_text,
                         _check_path, _Inputs, _printable, _resolved, _SceneFiles, expand, load_sweep, point_key)
from .sweep_table import (_columns, _csv_line, _Earlier, _earlier_rows, _save_series, _Table, _TableOutput,
                          _typed_rows)

# The public names of the sweeps module, those of its parts among them (hubbeam.sweeps.load_sweep, expand, ...).
__all__ = ["DEFAULT_KEEP", "DERIVED_VALUES", "ELASTIC_KINDS", "SUMMARY_VALUES", "SweepError", "expand", "last_timing",
           "load_sweep", "local_cluster", "main", "point_key", "run_point", "run_points", "run_sweep"]


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


# The last sweep's timing: the wall time from the first task submitted to the last row, the worker threads, the sum
# of the points' own in-process times, the cluster's start-up, and the overhead (workers x wall - runs) / runs
# (python3 -m hubbeam.benchmark reads it: meaningful over many points, not over three).
last_timing: dict[str, float] = {}


@dataclasses.dataclass
class _Plan:
    """A sweep checked and ready to run: its points (as given and as the core takes them), the base scene's text,
    each point's key, the table's path, header and permissions (new, and replacing an old table)."""
    sweep: dict[str, Any]
    path: str
    points: list[dict[str, Any]]
    runs: list[dict[str, Any]]
    scene_text: str
    ids: list[str]
    keys: list[str]
    header: list[str]
    mode: int
    replace_mode: int


@dataclasses.dataclass
class _Options:
    """How run_sweep runs its points (its keyword arguments)."""
    scheduler: Any
    workers: int | None
    resume: bool
    progress: bool
    batch: int | None
    security: Any
    dashboard: bool


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
    _check_counts(workers, batch)
    options = _Options(scheduler, workers, resume, progress, batch, security, dashboard)
    plan = _plan(spec, output)
    # Taken before the table is read: a second sweep (or a hubbeam command) writing the same table is refused.
    lock = _OutputLock(plan.path, _printable(plan.path))
    try:
        _prepare_folders(plan.path, plan.sweep["keep"])
        earlier = _earlier_rows(plan.path, plan.header, plan.keys, plan.points, plan.ids, resume)
        todo = [(i, p) for i, p in enumerate(plan.runs) if plan.ids[i] not in earlier.done]
        lines: dict[str, list[str]] = dict(earlier.done)
        if not todo and progress:
            print(f"sweep: all {len(plan.points)} points are in {_printable(plan.path)} already (the same scene, "
                  f"tables and version); --no-resume recomputes them", file=sys.stderr)
        if todo:
            _compute(plan, earlier, todo, lines, options)
        return _typed_rows(plan.path, plan.header, lines, plan.ids, plan.points, plan.keys)
    finally:
        lock.release()


def _check_counts(workers: Any, batch: Any) -> None:
    """SweepError unless workers and batch are None or whole numbers >= 1."""
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise SweepError(f"--workers: expected a number of worker threads >= 1, got {_printable(repr(workers))}")
    if batch is not None and (isinstance(batch, bool) or not isinstance(batch, int) or batch < 1):
        raise SweepError(f"batch: expected a number of points per task >= 1, got {_printable(repr(batch))}")


def _plan(spec: str | os.PathLike | Mapping[str, Any], output: Any) -> _Plan:
    """The sweep read and checked, and everything it reads, before the table is touched: the sweep, its points, the
    base scene, the files they read, the output."""
    import hubbeam

    sweep = load_sweep(spec)
    if output is not None:
        _check_path("--output", output)
    path = os.fspath(output) if output is not None else sweep["output"]
    points = expand(sweep)
    runs = [_resolved(p, sweep["base"]) for p in points]  # as the core takes them: file keys' paths resolved
    scene_text = _base_scene_text(sweep)
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
    keys = list(dict.fromkeys(k for p in points for k in p))
    return _Plan(sweep, path, points, runs, scene_text, ids, keys, _columns(keys, sweep["keep"], sweep["frequencies"]),
                 mode, _replace_mode(path, mode))


def _compute(plan: _Plan, earlier: _Earlier, todo: list[tuple[int, dict[str, Any]]], lines: dict[str, list[str]],
             options: _Options) -> None:
    """Runs todo's points on the cluster and appends each row to the table (and to lines) as it finishes; prints
    the timing once all are in. Interrupted, a local cluster's runs stop; the table keeps every row written."""
    import hubbeam

    started_cluster = time.perf_counter()
    client, close = _connect(options.scheduler, options.workers, options.dashboard, options.security,
                             options.progress)
    output = _TableOutput(plan.path, _printable(plan.path))
    interrupted = True
    try:
        client.run(_import_hubbeam)  # each worker's one-off imports, part of its start-up, not of a point
        n_workers = sum(w.get("nthreads", 1) for w in client.scheduler_info().get("workers", {}).values()) or 1
        start_up = time.perf_counter() - started_cluster
        # Only now that the cluster answers is a file written: the table, or with resume=False a new table beside it
        # that replaces the old one once complete.
        table = output.open(earlier, plan.header, options.resume, plan.mode, plan.replace_mode, options.progress)
        wall, run_total = _run_batches(client, plan, todo, lines, table, n_workers, options)
        output.finish()
        interrupted = False
    except SweepError:
        interrupted = False
        raise
    finally:
        if interrupted and options.scheduler is None:
            hubbeam._cancel_runs()  # the local workers are this process's threads: their runs stop now
        output.abandon()
        if close is not None:
            close()
    _report_timing(len(todo), wall, n_workers, run_total, start_up, options.progress)


def _run_batches(client: Any, plan: _Plan, todo: list[tuple[int, dict[str, Any]]], lines: dict[str, list[str]],
                 table: _Table, n_workers: int, options: _Options) -> tuple[float, float]:
    """Submits todo's points in batches and writes their rows as the batches finish: (the wall time from the first
    task submitted to the last row, the sum of the points' own in-process times)."""
    series_folder = _series_dir(os.path.abspath(plan.path))
    started = time.perf_counter()
    run_total = 0.0
    meter = _Progress(len(plan.points), len(plan.points) - len(todo), options.progress)
    try:
        from distributed import as_completed

        size = options.batch or max(1, min(16, len(todo) // (4 * n_workers)))
        batches = [todo[k:k + size] for k in range(0, len(todo), size)]
        futures = {client.submit(run_points, plan.scene_text, plan.sweep["scene"], [p for _, p in b],
                                 plan.sweep["keep"], plan.sweep["frequencies"],
                                 key=f"hubbeam-points-{plan.ids[b[0][0]]}-{len(b)}", pure=False): b for b in batches}
        for future in as_completed(futures):
            b = futures[future]
            try:
                rows = future.result()
            except Exception as e:  # noqa: BLE001 - a lost worker: its points are rows with the status
                rows = [{"status": "error: the task failed: " + _printable(f"{type(e).__name__}: {e}")} for _ in b]
            for (i, _), row in zip(b, rows):
                run_total += _write_row(plan, i, row, table, lines, series_folder)
                meter.point(row.get("status") == "ok")
    finally:
        meter.close()
    return time.perf_counter() - started, run_total


def _write_row(plan: _Plan, i: int, row: dict[str, Any], table: _Table, lines: dict[str, list[str]],
               series_folder: str) -> float:
    """Point i's row appended to the table (its tip series saved first, its cell naming the file) and to lines;
    returns its run's in-process time."""
    if row.get("tip_series") is not None:
        row["tip_series"] = _save_series(series_folder, plan.ids[i], row["tip_series"], plan.mode)
    values = [plan.ids[i], *(plan.points[i].get(k) for k in plan.keys)] + \
        [row.get(c) for c in plan.header[len(plan.keys) + 1:]]
    line = _csv_line(values)
    table.append(line)  # one whole line per write: a reader never sees half of it
    lines[plan.ids[i]] = next(csv.reader([line]))
    return row["run_seconds"] if isinstance(row.get("run_seconds"), float) else 0.0


def _report_timing(points: int, wall: float, n_workers: int, run_total: float, start_up: float,
                   progress: bool) -> None:
    """Records the finished sweep's timing in last_timing and prints its closing line."""
    overhead = (wall * n_workers - run_total) / run_total if run_total > 0 else float("nan")
    last_timing.update(wall=wall, workers=n_workers, runs=run_total, overhead=overhead, start_up=start_up)
    if progress:
        print(f"sweep: {points} points in {wall:.2f} s on {n_workers} worker{'s' if n_workers != 1 else ''}, after "
              f"{start_up:.2f} s to start or reach the cluster; the runs themselves took {run_total:.2f} s of the "
              f"workers' {wall * n_workers:.2f} s (the rest is Dask's scheduling and transfers, and workers left "
              f"without a point)", file=sys.stderr)


class _Terminated(KeyboardInterrupt):
    """A signal that ends the sweep (SIGTERM, SIGHUP, SIGQUIT), raised where the sweep is so that the cluster closes,
    the table is left whole and the lock and temporary files are removed."""

    def __init__(self, signum: int):
        super().__init__(signum)
        self.signum = signum


# The signals that end a sweep as Ctrl-C does, keeping its rows. SIGXFSZ stays ignored (Python's own setting): a
# write past a file-size limit then fails with EFBIG, and the sweep ends as on a full disk, rows kept, exit 2.
_ENDING_SIGNALS = (signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT)


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
