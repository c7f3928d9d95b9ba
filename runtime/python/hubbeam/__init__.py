"""hubbeam from Python: run scenes, compute modes and linearized models, sweep parameters (README "Python module").

    import hubbeam
    r = hubbeam.run("cases/spinup_omega4.toml", method="fem", ny=8)
    r.t, r.tip_uy          # numpy arrays (views of one array r.data, no copy per row)
    r.completed, r.variant, r.source, r.max_abs_tip_uy, r.jacobi_drift, r.wall_seconds
"""
from __future__ import annotations

import json
import math
import os
from typing import Any, Mapping

import numpy as np

from . import _core

__all__ = ["run", "modes", "linearize", "sweep", "Result", "RunStopped", "scene_keys", "generator_version"]
__version__ = _core.__version__

_KEYS = dict(_core.scene_keys())                 # dotted name -> what it takes
_LEAVES = {k.split(".", 1)[1]: k for k in _KEYS}  # "ny" -> "discretization.ny" (leaf names are unique)


def scene_keys() -> dict[str, str]:
    """Every scene key a scene file or a keyword argument may set, with what it takes."""
    return dict(_KEYS)


def generator_version() -> str:
    """The generator's version: on-demand variants and sweep results are keyed by it."""
    return _core.generator_version()


class RunStopped(RuntimeError):
    """Raised by run(..., check=True) when the simulation stopped before t_end; .result holds the rows so far."""

    def __init__(self, result: "Result"):
        super().__init__(f"stopped at t = {result.t_reached:g} s: {result.failure}")
        self.result = result


class Result:
    """One run: its rows as columns (numpy views of .data, n x 10) and its summary as attributes."""

    def __init__(self, raw: dict):
        self.data: np.ndarray = raw.pop("data")
        self.columns: tuple[str, ...] = tuple(raw.pop("columns").split(","))
        self.summary_text: str = raw.pop("summary_text")
        self.summary: dict = raw
        for name, value in raw.items():
            setattr(self, name, value)
        for i, name in enumerate(self.columns):
            setattr(self, name, self.data[:, i])

    def __repr__(self) -> str:
        state = "completed" if self.completed else f"stopped at t = {self.t_reached:g} s"
        return f"<hubbeam.Result {self.variant}, {len(self.data)} rows, {state}>"


def _value_text(name: str, value: Any) -> str:
    """A keyword's value as the command line would type it."""
    if isinstance(value, bool):
        raise ValueError(f"{name}: expected {_KEYS[name]}, got {value}")
    if isinstance(value, float):
        return repr(value)
    return str(value)


def _overrides(keywords: Mapping[str, Any]) -> list[tuple[str, str]]:
    """Keyword arguments (leaf names such as ny, or dotted names) as scene-key overrides."""
    out = []
    for name, value in keywords.items():
        key = name if name in _KEYS else _LEAVES.get(name)
        if key is None:
            raise ValueError(f"{name}: expected a scene key (README: Scene files; hubbeam.scene_keys()), got an "
                             f"unknown keyword")
        out.append((key, _value_text(key, value)))
    return out


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return repr(value) if math.isfinite(value) else ("nan" if math.isnan(value) else ("inf" if value > 0 else "-inf"))
    if isinstance(value, str):
        return json.dumps(value)  # a JSON string is a TOML basic string
    raise ValueError(f"expected a number or a string in a scene, got {value!r}")


def _scene_text(scene: Mapping[str, Mapping[str, Any]]) -> str:
    """A scene given as a dict of tables ({"beam": {"length": 8.0, ...}, ...}) as TOML text."""
    lines = []
    for table, keys in scene.items():
        if not isinstance(keys, Mapping):
            raise ValueError(f"{table}: expected a table (a dict of keys), got {keys!r}")
        lines.append(f"[{table}]")
        lines += [f"{key} = {_toml_value(value)}" for key, value in keys.items()]
    return "\n".join(lines) + "\n"


def _source(scene: Any) -> tuple[str, str]:
    """(text, name) for the core: a path with an empty name (the core reads it), or a dict's TOML."""
    if isinstance(scene, (str, os.PathLike)):
        return os.fspath(scene), ""
    if isinstance(scene, Mapping):
        return _scene_text(scene), "<dict scene>"
    raise ValueError(f"scene: expected a scene file's path or a dict of tables, got {type(scene).__name__}")


def run(scene: Any, *, check: bool = False, **keys: Any) -> Result:
    """Runs a scene (a file's path, or a dict of tables) with scene keys overridden by keyword (ny=8,
    method="fem", rtol=1e-10, or dotted names via **{"discretization.ny": 8}).

    Bad input raises ValueError with the command line's one-line message. A run that stops before t_end (unstable,
    untrustworthy, out of steps) returns its rows so far with completed False and the reason in .failure; with
    check=True it raises RunStopped instead. The GIL is released while integrating.
    """
    text, name = _source(scene)
    result = Result(_core.run(text, name, _overrides(keys)))
    if check and not result.completed:
        raise RunStopped(result)
    return result


def modes(scene: Any, omega: Any = 0.0, **keys: Any) -> dict[str, Any]:
    """Every natural mode of the scene's variant linearized about a steady spin at each rate of omega (rad/s):
    equal-length arrays omega, mode, kind, rad_s, hz, dimensionless, growth, and the variant's name."""
    text, name = _source(scene)
    rates = [float(w) for w in np.atleast_1d(omega)]
    if any(not (w >= 0.0 and math.isfinite(w)) for w in rates):
        raise ValueError(f"omega: expected spin rates >= 0 (rad/s), got {omega!r}")
    out = _core.modes(text, name, _overrides(keys), rates)
    out["kind"] = np.array(out["kind"])
    return out


def linearize(scene: Any, omega: float, **keys: Any) -> dict[str, Any]:
    """x' = A x + B v, y = C x + D v about the steady spin omega (rad/s): A, B, C, D as arrays and the names of
    the states, inputs and outputs (README "A linearized model to take away")."""
    text, name = _source(scene)
    if not (omega >= 0.0 and math.isfinite(omega)):
        raise ValueError(f"omega: expected a spin rate >= 0 (rad/s), got {omega!r}")
    return _core.linearize(text, name, _overrides(keys), float(omega))


def _run_text(text: str, name: str, keys: Mapping[str, Any]) -> Result:
    """run() of a scene's text (named name in messages): for the sweep's workers, which get the text, not a file."""
    return Result(_core.run(text, name, _overrides(keys)))


def _modes_text(text: str, name: str, keys: Mapping[str, Any], omegas: list[float]) -> dict[str, Any]:
    out = _core.modes(text, name, _overrides(keys), omegas)
    out["kind"] = np.array(out["kind"])
    return out


def _check_scene(text: str, name: str) -> None:
    _core.check(text, name)


def sweep(*args: Any, **kwargs: Any):
    """Runs a parameter sweep on Dask (hubbeam.sweeps.run_sweep; README "Parameter sweeps")."""
    from .sweeps import run_sweep
    return run_sweep(*args, **kwargs)
