"""The Python module's and the sweeps' overheads (docs/python.md): python3 -m hubbeam.benchmark.

1. hubbeam.run against the command line's in-process time (loading the scene, choosing the model, integrating,
   as hubbeam run does), median over repeated runs.
2. A sweep on a local cluster of 2 worker threads against the sum of its runs' own times, for points of about 10 ms
   and about 100 ms: (workers x wall - sum of run times) / sum of run times, the cluster's start-up left out.
3. With --torque-law, only the cost of one call of a torque law hubbeam.run(..., torque=f): cases/controlled_step.toml
   driven by its own PD law written in Python against the same law from its [control], best of five runs each.
"""
from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time

import hubbeam
from hubbeam import sweeps


def run_overhead(scene: str, repeats: int) -> None:
    overheads, inside = [], []
    hubbeam.run(scene, nx=0, t_end=2)  # warm: the variant loaded, the caches filled
    for _ in range(repeats):
        start = time.perf_counter()
        r = hubbeam.run(scene, nx=0, t_end=2)
        total = time.perf_counter() - start
        overheads.append(total - r.in_process_seconds)
        inside.append(r.in_process_seconds)
    print(f"hubbeam.run: in-process time median {1e3 * statistics.median(inside):.3f} ms, Python's overhead over it "
          f"median {1e3 * statistics.median(overheads):.3f} ms (min {1e3 * min(overheads):.3f}, max "
          f"{1e3 * max(overheads):.3f}) over {repeats} runs")


def sweep_overhead(scene: str, points: int, t_end: float, label: str) -> None:
    with tempfile.TemporaryDirectory() as d:
        spec = {"scene": scene, "set": {"output.t_end": t_end},
                "grid": {"motion.omega0": [1.0 + 0.1 * i for i in range(points)]}, "keep": ["wall_seconds"]}
        started = time.perf_counter()
        sweeps.run_sweep(spec, output=os.path.join(d, "sweep.csv"), workers=2, progress=False)
        total = time.perf_counter() - started
        t = sweeps.last_timing
        print(f"sweep ({label}): {points} points, runs' own time {1e3 * t['runs'] / points:.1f} ms each, "
              f"{t['runs']:.2f} s in all; wall {t['wall']:.2f} s on {t['workers']} workers; overhead "
              f"{100 * t['overhead']:.1f} % (the cluster's start-up, {t['start_up']:.2f} s, left out; the whole "
              f"sweep took {total:.2f} s)")


def torque_law_cost(scene: str) -> None:
    calls = [0]

    def law(t, s):  # the scene's [control]: kp 64.45, kd 90.2, step to 0.5 rad, |tau| <= 10 N m
        calls[0] += 1
        tau = -64.45 * (s["theta"] - 0.5) - 90.2 * s["theta_dot"]
        return max(-10.0, min(10.0, tau))

    own, python = [], []
    for _ in range(5):
        c = hubbeam.run(scene, error_check="off")
        calls[0] = 0
        f = hubbeam.run(scene, error_check="off", torque=law)
        own.append(c.wall_seconds)
        python.append(f.wall_seconds)
    per_call = (min(python) - min(own) * f.rhs_evals / c.rhs_evals) / calls[0]
    print(f"torque law: [control] {min(own):.4f} s ({c.rhs_evals} evaluations), torque=f {min(python):.4f} s "
          f"({f.rhs_evals} evaluations, {calls[0]} calls of f): {1e6 * per_call:.2f} us per call, the right-hand "
          f"side with [control] {1e6 * min(own) / c.rhs_evals:.2f} us")


def main() -> int:
    parser = argparse.ArgumentParser(prog="python3 -m hubbeam.benchmark", description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default=os.path.join(os.path.dirname(__file__), "..", "..", "..", "cases",
                                                         "spinup_omega4.toml"))
    parser.add_argument("--repeats", type=int, default=200)
    parser.add_argument("--points", type=int, default=100)
    parser.add_argument("--torque-law", action="store_true", help="only the cost of a call of a torque law")
    args = parser.parse_args()
    if args.torque_law:
        step = os.path.join(os.path.dirname(__file__), "..", "..", "..", "cases", "controlled_step.toml")
        torque_law_cost(os.path.abspath(step))
        return 0
    scene = os.path.abspath(args.scene)
    if not os.path.exists(scene):
        print(f"{hubbeam.printable(scene)}: cannot open (give --scene cases/spinup_omega4.toml)", file=sys.stderr)
        return 2
    run_overhead(scene, args.repeats)
    sweep_overhead(scene, args.points, 4.0, "points of about 10 ms")
    sweep_overhead(scene, args.points, 30.0, "points of about 100 ms")
    return 0


if __name__ == "__main__":
    sys.exit(main())
