"""Summary quantities of a run with their exact gradients, for optimization (docs/sensitivities.md, "Gradients").

Each measure takes a Result of hubbeam.run(..., sensitivities=names) and returns (value, gradient) with the
gradient over names in their order; Objective turns a measure into f(x) -> (value, gradient) for
scipy.optimize.minimize(f, x0, jac=True):

    import hubbeam, scipy.optimize
    f = hubbeam.Objective("cases/controlled_step.toml", ["kp", "kd"],
                          lambda r, names: hubbeam.residual_vibration(r, names, after=10.0))
    best = scipy.optimize.minimize(f, [64.45, 90.2], jac=True, method="L-BFGS-B")
"""
from __future__ import annotations

from typing import Any, Callable, Sequence

import numpy as np

# The scene key that sets each parameter a sensitivity can be taken with respect to (docs/sensitivities.md).
PARAMETER_KEYS = {
    "L": "beam.length", "rho": "beam.density", "S": "beam.area", "I": "beam.second_moment",
    "E": "beam.youngs_modulus", "a": "hub.radius", "J_oh": "hub.inertia", "m_tip": "tip.mass",
    "J_tip": "tip.inertia", "g": "gravity.g", "alpha": "damping.mass_proportional",
    "beta": "damping.stiffness_proportional", "tip_ratio": "beam.tip_ratio",
    "m_hub": "hub.mass", "k_x": "support.stiffness_x", "k_y": "support.stiffness_y", "c_x": "support.damping_x",
    "c_y": "support.damping_y",
    "kp": "control.kp", "kd": "control.kd", "ki": "control.ki", "k_tip": "control.k_tip",
}

Measure = Callable[[Any, Sequence[str]], "tuple[float, np.ndarray]"]


def _derivatives(result: Any, column: str, names: Sequence[str]) -> np.ndarray:
    """The rows' d_COLUMN/d_NAME for each name, as an n x k array; KeyError naming what the run lacks."""
    if not names:
        return np.zeros((len(result.t), 0))
    missing = [f"d_{column}/d_{name}" for name in names if f"d_{column}/d_{name}" not in result.columns]
    if missing:
        raise KeyError(f"the run has no column {missing[0]}: run it with sensitivities={list(names)}")
    return np.column_stack([result[f"d_{column}/d_{name}"] for name in names])


def max_deflection(result: Any, names: Sequence[str], column: str = "tip_uy") -> tuple[float, np.ndarray]:
    """max |y| over the rows (y = column, tip_uy by default) and its gradient sign(y*) dy*/dp at the row where it
    is reached (the derivative of a maximum where one row attains it; it jumps where two peaks trade places)."""
    y = np.asarray(getattr(result, column))
    i = int(np.argmax(np.abs(y)))
    return float(abs(y[i])), np.sign(y[i]) * _derivatives(result, column, names)[i]


def residual_vibration(result: Any, names: Sequence[str], after: float,
                       column: str = "tip_uy") -> tuple[float, np.ndarray]:
    """The amplitude of what remains of the vibration from time `after` on: sqrt(2 var(y)) over the rows with
    t >= after (the amplitude of a sine of that variance; a static offset such as a sag does not count), and its
    gradient 2 cov(y, dy/dp) / amplitude."""
    t = np.asarray(result.t)
    keep = t >= after
    if keep.sum() < 2:
        raise ValueError(f"after: expected a time before the run's last rows (t_end {t[-1]:g} s), got {after:g}")
    y = np.asarray(getattr(result, column))[keep]
    dy = _derivatives(result, column, names)[keep]
    y = y - y.mean()
    dy = dy - dy.mean(axis=0)
    amplitude = float(np.sqrt(2.0 * np.mean(y * y)))
    if amplitude == 0.0:
        return 0.0, np.zeros(len(names))
    return amplitude, 2.0 * (y @ dy) / len(y) / amplitude


def final_error(result: Any, names: Sequence[str], column: str, target: float) -> tuple[float, np.ndarray]:
    """(y(t_end) - target)^2 for y = column (e.g. theta against the angle a manoeuvre should reach) and its
    gradient 2 (y - target) dy/dp at the last row."""
    error = float(np.asarray(getattr(result, column))[-1] - target)
    return error * error, 2.0 * error * _derivatives(result, column, names)[-1]


class Objective:
    """f(x) -> (value, gradient) for scipy.optimize.minimize(f, x0, jac=True): each call runs the scene with the
    parameters `names` (symbols of PARAMETER_KEYS) set to x and their sensitivities on, and applies measure(result,
    names). Scene keys as keywords (ny=8, t_end=20.0) apply to every run; the sensitivities are the names' alone (the
    scene's output.sensitivities is replaced). x holds one value per name, or ValueError. .runs counts the runs made;
    a run that stops before t_end raises hubbeam.RunStopped."""

    def __init__(self, scene: Any, names: Sequence[str], measure: Measure, **keys: Any):
        names = [str(n) for n in np.atleast_1d(np.asarray(names, dtype=object))]
        unknown = [n for n in names if n not in PARAMETER_KEYS]
        if unknown:
            raise ValueError(f"names: expected parameters among {', '.join(PARAMETER_KEYS)}, got {unknown[0]!r}")
        for key in ("sensitivities", "output.sensitivities"):
            if key in keys:
                raise ValueError(f"{key}: expected no such keyword: an Objective takes the sensitivities of its names "
                                 f"({', '.join(names)})")
        self.scene, self.names, self.measure, self.keys = scene, names, measure, dict(keys)
        self.runs = 0

    def __call__(self, x: Sequence[float]) -> tuple[float, np.ndarray]:
        return self._run(x, self.names)

    def value(self, x: Sequence[float]) -> float:
        """The measure alone, from a run without sensitivities (what an optimizer by finite differences calls)."""
        return self._run(x, [])[0]

    def _run(self, x: Sequence[float], sensitivities: list[str]) -> tuple[float, np.ndarray]:
        from . import run  # the package imports this module: import at call time
        x = np.atleast_1d(np.asarray(x, dtype=float))
        if x.ndim != 1 or len(x) != len(self.names):
            raise ValueError(f"x: expected {len(self.names)} value{'s' if len(self.names) != 1 else ''}, one for each "
                             f"of {', '.join(self.names)}, got {len(x) if x.ndim == 1 else x.shape}")
        values = {PARAMETER_KEYS[n]: float(v) for n, v in zip(self.names, x)}
        self.runs += 1
        # The key, not sensitivities=: it replaces what the scene names, which this run does not need.
        result = run(self.scene, check=True, **self.keys, **values, **{"output.sensitivities": ",".join(sensitivities)})
        return self.measure(result, sensitivities)
