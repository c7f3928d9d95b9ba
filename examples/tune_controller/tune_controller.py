"""Tunes the PD gains of cases/controlled_step.toml so that the beam rings least once the hub has turned.

The hub turns 0.5 rad under tau = -kp (theta - 0.5) - kd theta_dot, at most 10 N m. The measure to minimise is the
amplitude of the tip's residual vibration from t = 8 s on (hubbeam.residual_vibration) plus a penalty on the hub
not being at 0.5 rad at t = 15 s (hubbeam.final_error). Each evaluation is one run with the sensitivities to kp
and kd on, so scipy gets the exact gradient with the value; the same minimisation with scipy's finite differences
needs about three runs per gradient. Run it from the repository (docs/sensitivities.md, "Gradients"):

    PYTHONPATH=build/python /usr/bin/python3 examples/tune_controller/tune_controller.py
"""
import os
import sys

import numpy as np
import scipy.optimize

import hubbeam

SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "cases", "controlled_step.toml")
NAMES = ["kp", "kd"]
START = np.array([64.45, 90.2])  # the scene's gains: a rigid-body design, 1 rad/s and damping ratio 0.7
SCALE = START                    # the optimizer works in gains relative to these
AFTER, T_END, WEIGHT = 8.0, 15.0, 10.0


def measure(result, names):
    """Residual vibration amplitude (m) after AFTER, plus WEIGHT (theta(T_END) - 0.5)^2, with its gradient."""
    vibration, d_vibration = hubbeam.residual_vibration(result, names, after=AFTER)
    error, d_error = hubbeam.final_error(result, names, "theta", 0.5)
    return vibration + WEIGHT * error, d_vibration + WEIGHT * d_error


def minimise(jac: bool):
    """Minimises the measure over (kp, kd) from START; returns scipy's result and the number of runs it took."""
    objective = hubbeam.Objective(SCENE, NAMES, measure, t_end=T_END)
    if jac:
        def f(x):
            value, gradient = objective(x * SCALE)
            return value, gradient * SCALE
    else:
        def f(x):
            return objective.value(x * SCALE)
    best = scipy.optimize.minimize(f, np.ones(2), jac=jac, method="L-BFGS-B", bounds=[(0.2, 5.0), (0.2, 5.0)],
                                   options={"ftol": 1e-12, "gtol": 1e-8})
    return best, objective.runs


def main() -> int:
    start = hubbeam.Objective(SCENE, NAMES, measure, t_end=T_END).value(START)
    exact, exact_runs = minimise(jac=True)
    differenced, differenced_runs = minimise(jac=False)
    print(f"start          kp {START[0]:8.3f}  kd {START[1]:8.3f}  measure {start:.4e}")
    for label, best, runs in (("exact gradient", exact, exact_runs), ("differences", differenced, differenced_runs)):
        kp, kd = best.x * SCALE
        print(f"{label:14} kp {kp:8.3f}  kd {kd:8.3f}  measure {best.fun:.4e}  runs {runs}")
    return 0 if exact.fun < start else 1


if __name__ == "__main__":
    sys.exit(main())
