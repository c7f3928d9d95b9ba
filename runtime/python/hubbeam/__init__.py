"""hubbeam from Python: run scenes, compute modes and linearized models, sweep parameters (docs/python.md).

    import hubbeam
    r = hubbeam.run("cases/spinup_omega4.toml", method="fem", ny=8)
    r.t, r.tip_uy          # numpy arrays (views of one array r.data, no copy per row)
    r.completed, r.variant, r.source, r.max_abs_tip_uy, r.jacobi_drift, r.wall_seconds
    r.plot(); r.save("run.csv"); hubbeam.load("run.csv")   # a figure; the rows and their metadata, read back
"""
from __future__ import annotations

import json
import math
import os
import sys
import threading
import unicodedata
from typing import Any, Mapping

try:
    import numpy as np

    from . import _core
except ImportError as _missing:
    # The compiled core is built for one interpreter (Debian's /usr/bin/python3, whose numpy and dask are Debian's
    # packages): any other python3 fails here with a message that does not say why or what to do.
    raise ImportError(
        f"hubbeam: this Python ({sys.executable}, {sys.version.split()[0]}) cannot load hubbeam ({_missing}); "
        f"use the Python it was built for (/usr/bin/python3 on Debian) or a virtual environment over it: "
        f"/usr/bin/python3 -m venv --system-site-packages DIR (docs/python.md)") from _missing

__all__ = ["run", "modes", "linearize", "sweep", "load", "plot_campbell", "effective_scene", "Result", "RunStopped",
           "scene_keys", "generator_version", "printable", "Objective", "max_deflection", "residual_vibration",
           "final_error", "PARAMETER_KEYS"]
__version__ = _core.__version__

_KEYS = {name: expected for name, expected, kind in _core.scene_keys()}  # dotted name -> what it takes
_KINDS = {name: kind for name, expected, kind in _core.scene_keys()}     # -> "number", "integer", "word", "text"
# "ny" -> "discretization.ny"; a leaf that several tables share ("inertia": hub and tip) maps to all of them, and a
# keyword must then name its table.
_LEAVES: dict[str, list[str]] = {}
for _key in _KEYS:
    _LEAVES.setdefault(_key.split(".", 1)[1], []).append(_key)


def printable(text: Any, cap: int = 400) -> str:
    """text for a one-line message: control and format characters (ESC, newlines, U+202E and the other
    bidirectional overrides) shown as escapes (\\x1b, \\u202e) so that a value cannot move the cursor, recolour the
    terminal or reorder what follows; cut at cap characters. Every message the package builds from a value it was
    given goes through it."""
    out = []
    for ch in str(text):
        if len(out) >= cap:
            out.append("...")
            break
        if unicodedata.category(ch) in ("Cc", "Cf", "Zl", "Zp", "Cs", "Co", "Cn") and ch not in " ":
            code = ord(ch)
            out.append(f"\\x{code:02x}" if code < 0x100 else (f"\\u{code:04x}" if code < 0x10000 else f"\\U{code:08x}"))
        else:
            out.append(ch)
    return "".join(out)


def scene_keys() -> dict[str, str]:
    """Every scene key a scene file or a keyword argument may set, with what it takes."""
    return dict(_KEYS)


def generator_version() -> str:
    """The generator's version: on-demand variants and sweep results are keyed by it."""
    return _core.generator_version()


class RunStopped(RuntimeError):
    """Raised by run(..., check=True) when the simulation stopped before t_end; .result holds the rows so far."""

    def __init__(self, result: "Result"):
        super().__init__(f"stopped at t = {result.t_reached:g} s: {printable(result.failure)}")
        self.result = result


# The unit of each column of a run's rows (the columns themselves come from the core, in its order).
UNITS = {"t": "s", "theta": "rad", "theta_dot": "rad/s", "tip_uy": "m", "tip_ux1": "m", "tip_ux": "m",
         "tip_uz": "m", "tip_phi": "rad",
         "kinetic": "J", "potential": "J", "momentum": "kg m^2/s", "jacobi": "J",
         "tau": "N m", "theta_ref": "rad", "controller_integral": "rad s", "dissipated": "J", "work": "J"}


class Result:
    """One run: its rows as columns (numpy views of .data, n x 10, more with a scene's optional columns such as tau)
    and its summary as attributes."""

    def __init__(self, raw: dict):
        self.data: np.ndarray = raw.pop("data")
        self.columns: tuple[str, ...] = tuple(raw.pop("columns").split(","))
        self.summary_text: str = raw.pop("summary_text")
        # Where the rows came from (the JSON hubbeam run writes beside its output): save() writes it, load() reads it.
        self.metadata: dict = json.loads(raw.pop("metadata"))
        self.scene_file: str = raw.pop("scene_file")
        self.summary: dict = raw
        for name, value in raw.items():
            setattr(self, name, value)
        for i, name in enumerate(self.columns):
            setattr(self, name, self.data[:, i])

    def __getitem__(self, column: str) -> np.ndarray:
        """A column by name, also those that are no Python name (r["d_tip_uy/d_E"])."""
        if column not in self.columns:
            raise KeyError(f"{printable(column, 80)}: expected one of the run's columns {', '.join(self.columns)}")
        return self.data[:, self.columns.index(column)]

    def to_pandas(self):
        """The rows as a pandas DataFrame: one column per quantity (t, theta, ..., as .columns), the units in
        df.attrs["units"] (column -> unit) and the summary in df.attrs["summary"]. Needs pandas (python3-pandas)."""
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("hubbeam: Result.to_pandas() needs pandas: install python3-pandas (Debian) or pandas in "
                              "this environment; the rows are in .data and the columns as attributes without it") \
                from None
        df = pd.DataFrame(self.data, columns=list(self.columns))
        df.attrs["units"] = {c: UNITS.get(c, "") for c in self.columns}
        df.attrs["summary"] = dict(self.summary)
        return df

    def plot(self, what: Any = "tip", *, ax: Any = None, label: str | None = None):
        """Draws columns against time with matplotlib, one panel per unit, and returns the figure: what is "tip"
        (tip_uy; tip_uz and tip_phi for a blade), "axial", "hub" (theta, theta_dot, tau), "energies", a column's
        name or a list of them; ax draws into given Axes (one per panel) to compare runs; label names this run in
        the legend (default: the scene's name and the variant). Needs matplotlib (python3-matplotlib)."""
        from .plots import plot_result
        return plot_result(self, what, ax=ax, label=label)

    def save(self, path: str | os.PathLike) -> str:
        """Writes the rows as hubbeam run does (CSV, or a NumPy array where path ends in .npy, with its column names
        in NAME.columns.txt) and the metadata beside them in PATH.hubbeam.json, all put in place together;
        hubbeam.load(path) reads them back. Refuses (ValueError) what hubbeam run refuses: a symbolic link, a
        read-only file, a folder. Returns the path."""
        path = os.fspath(path)
        if not path.endswith((".csv", ".npy")):
            raise ValueError(f"path: expected a file name ending in .csv or .npy, got {printable(repr(path), 200)}")
        meta = dict(self.metadata, output=os.path.basename(path), rows=len(self.data))
        meta.setdefault("scene", {}).setdefault("output", {})["file"] = path
        _core.save_rows(path, self.data, ",".join(self.columns), json.dumps(meta, indent=2) + "\n")
        return path

    def __repr__(self) -> str:
        state = "completed" if self.completed else f"stopped at t = {self.t_reached:g} s"
        return f"<hubbeam.Result {self.variant}, {len(self.data)} rows, {state}>"


# The summary's numbers that the metadata may hold as "inf", "-inf" or "nan" (JSON has no such numbers).
_SUMMARY_NUMBERS = ("t_reached", "max_abs_tip_uy", "t_steady", "jacobi_drift", "vibration_energy", "estimated_error",
                    "wall_seconds", "check_wall_seconds")
METADATA_SUFFIX = ".hubbeam.json"


def load(path: str | os.PathLike) -> Result:
    """Reads a run's output back, CSV or .npy, with the metadata written beside it (PATH.hubbeam.json, by hubbeam run
    or Result.save) into the Result that hubbeam.run returned: its columns, summary, to_pandas() and plot(). Raises
    FileNotFoundError without the metadata, ValueError where the metadata is not a run's or does not describe the
    file (another row count or header: the file was changed or replaced since)."""
    path = os.fspath(path)
    meta_path = path + METADATA_SUFFIX
    try:
        with open(meta_path, encoding="utf-8") as f:
            meta = json.load(f)
    except FileNotFoundError:
        raise FileNotFoundError(f"{printable(meta_path)}: not found: hubbeam.load reads a run's output with the "
                                f"metadata that hubbeam run and Result.save write beside it") from None
    except (json.JSONDecodeError, UnicodeDecodeError) as e:
        raise ValueError(f"{printable(meta_path)}: expected hubbeam's metadata (JSON), got {printable(e)}") from None
    if not isinstance(meta, dict) or meta.get("format") != "hubbeam-metadata 1":
        raise ValueError(f"{printable(meta_path)}: expected \"format\": \"hubbeam-metadata 1\", got "
                         f"{printable(repr(meta.get('format') if isinstance(meta, dict) else meta), 80)}")
    if meta.get("command") != "run":
        raise ValueError(f"{printable(meta_path)}: expected the metadata of a run, got that of "
                         f"{printable(repr(meta.get('command')), 40)} (hubbeam.load reads runs)")
    columns = list(meta["columns"])
    if path.endswith(".npy"):
        data = np.load(path, allow_pickle=False)
        with open(os.path.splitext(path)[0] + ".columns.txt", encoding="utf-8") as f:
            header = f.readline().rstrip("\n").split(",")
    else:
        with open(path, encoding="utf-8") as f:
            header = f.readline().rstrip("\n").split(",")
            data = np.loadtxt(f, delimiter=",", ndmin=2).reshape(-1, len(header))
    if header != columns or data.ndim != 2 or data.shape != (meta["rows"], len(columns)):
        raise ValueError(f"{printable(path)}: expected the {meta['rows']} rows of columns {','.join(columns)} that "
                         f"{printable(meta_path)} describes, got {data.shape[0]} rows of {','.join(header)}: the file "
                         f"was changed or replaced after its metadata was written")
    raw = dict(meta["summary"])
    for k in _SUMMARY_NUMBERS:
        raw[k] = float(raw[k])
    raw.update(data=np.ascontiguousarray(data, dtype=float), columns=",".join(columns),
               metadata=json.dumps(meta), scene_file=meta["scene_file"])
    return Result(raw)


def effective_scene(scene: Any, **keys: Any) -> str:
    """The scene as TOML with every key it runs with, defaults filled and the keywords applied (what
    hubbeam run --print-scene prints); a file saved from it runs the same."""
    text, name = _source(scene)
    return _core_call(_core.effective_scene, text, name, _overrides(keys))


def plot_campbell(m: dict, **options: Any):
    """A Campbell diagram of modes(...) with matplotlib: the tracked modes' frequencies (Hz) against the spin rate,
    the excitation lines n x Omega and the critical speeds; returns the figure (hubbeam.plots.plot_campbell for the
    options: kinds, harmonics, ax, label). Needs matplotlib (python3-matplotlib)."""
    from .plots import plot_campbell as draw
    return draw(m, **options)


def _plain(value: Any) -> Any:
    """A numpy scalar or 0-d array as the Python number, bool or string it holds; an array as a list of them; anything
    else as it is. Every value the package takes passes through it, so numpy's values go wherever Python's do."""
    if isinstance(value, np.ndarray):
        return value.tolist()  # 0-d: the scalar itself
    if isinstance(value, np.generic):
        return value.item()
    return value


def _value_text(keyword: str, key: str, value: Any) -> str:
    """A keyword's value as the command line would type it; ValueError naming the keyword where the value is not of
    the key's kind (a string is no number even where it reads as one)."""
    value = _plain(value)
    kind = _KINDS[key]
    if isinstance(value, os.PathLike) and kind == "text":
        value = os.fspath(value)
    if kind in ("number", "integer"):
        good = isinstance(value, int) if kind == "integer" else isinstance(value, (int, float))
        if good and not isinstance(value, bool):
            return repr(value) if isinstance(value, float) else str(value)
    elif isinstance(value, str) and "\0" not in value:
        return value
    note = " (no NUL character)" if kind in ("word", "text") else ""
    raise ValueError(f"{printable(keyword, 80)}: expected {_KEYS[key]}{note}, got "
                     f"{'the string ' if isinstance(value, str) and not note else ''}{printable(repr(value), 120)}")


def _overrides(keywords: Mapping[str, Any]) -> list[tuple[str, str, str]]:
    """Keyword arguments (leaf names such as ny, or dotted names) as scene-key overrides: (dotted key, value as
    text, the keyword, which messages name)."""
    out = []
    for name, value in keywords.items():
        keys = [name] if name in _KEYS else _LEAVES.get(name, [])
        if not keys:
            raise ValueError(f"{printable(name, 80)}: expected a scene key (docs/scene.md; hubbeam.scene_keys()), "
                             f"got an unknown keyword")
        if len(keys) > 1:
            raise ValueError(f"{name}: expected one scene key, got a name that " + " and ".join(keys) +
                             f" share: name the table, e.g. **{{\"{keys[0]}\": ...}}")
        key = keys[0]
        out.append((key, _value_text(name, key, value), name))
    return out


def _toml_value(value: Any) -> str:
    value = _plain(value)
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return repr(value) if math.isfinite(value) else ("nan" if math.isnan(value) else ("inf" if value > 0 else "-inf"))
    if isinstance(value, str):
        return json.dumps(value)  # a JSON string is a TOML basic string
    raise ValueError(f"expected a number or a string in a scene, got {printable(repr(value), 120)}")


def _scene_text(scene: Mapping[str, Mapping[str, Any]]) -> str:
    """A scene given as a dict of tables ({"beam": {"length": 8.0, ...}, ...}) as TOML text."""
    lines = []
    for table, keys in scene.items():
        if not isinstance(keys, Mapping):
            raise ValueError(f"{printable(table, 80)}: expected a table (a dict of keys), got {printable(repr(keys), 120)}")
        lines.append(f"[{table}]")
        lines += [f"{key} = {_toml_value(value)}" for key, value in keys.items()]
    return "\n".join(lines) + "\n"


def _source(scene: Any) -> tuple[str, str]:
    """(text, name) for the core: a path with an empty name (the core reads it), or a dict's TOML."""
    if isinstance(scene, (str, os.PathLike)):
        return os.fspath(scene), ""
    if isinstance(scene, Mapping):
        return _scene_text(scene), "<dict scene>"
    raise ValueError(f"scene: expected a scene file's path or a dict of tables, got {printable(type(scene).__name__)}")


def run(scene: Any, *, check: bool = False, torque: Any = None, sensitivities: Any = None, **keys: Any) -> Result:
    """Runs a scene (a file's path, or a dict of tables) with scene keys overridden by keyword (ny=8,
    method="fem", rtol=1e-10, or dotted names via **{"discretization.ny": 8}).

    torque=f makes the hub free and drives it by f(t, state) -> tau (N m), called at every evaluation of the
    equations with state a dict of theta (rad), theta_dot (rad/s), tip_uy (m) and tip_uy_dot (m/s); the scene's
    motion and [control] are then not used, and the rows gain the columns tau and work. An exception in f stops the
    run and is raised here. Each call costs some microseconds (docs/python.md, "A torque law in Python").

    Bad input raises ValueError with the command line's one-line message. A run that stops before t_end (unstable,
    untrustworthy, out of steps) returns its rows so far with completed False and the reason in .failure; with
    check=True it raises RunStopped instead. The GIL is released while integrating.

    sensitivities=["E", "kp", ...] (parameter symbols, docs/sensitivities.md) integrates the derivatives of the
    state by those parameters beside it: the rows gain the columns d_OUTPUT/d_PARAM (r["d_tip_uy/d_E"]) for the
    outputs theta, theta_dot, tip_uy, tip_ux1 and tip_ux. Where the scene or a key already sets
    output.sensitivities to other parameters, ValueError names both.

    Numbers may be numpy's (ny=np.int64(8)); a string is no number. Ctrl-C raises KeyboardInterrupt within 0.1 s.
    """
    text, name = _source(scene)
    names = None if sensitivities is None else _sensitivities(sensitivities)
    if torque is not None and not callable(torque):
        raise ValueError(f"torque: expected a callable f(t, state) -> tau (N m), got {printable(repr(torque), 120)}")
    result = Result(_core_call(_core.run, text, name, _overrides(keys), False, torque, names))
    if check and not result.completed:
        raise RunStopped(result)
    return result


def _sensitivities(names: Any) -> list[str]:
    """sensitivities= as a list of symbols: from a list, tuple or array of them, or one comma-separated string."""
    names = _plain(names)
    if isinstance(names, str):
        return [n.strip() for n in names.split(",")] if names.strip() else []
    if isinstance(names, (list, tuple)) and all(isinstance(n, str) and "," not in n and "\0" not in n for n in names):
        return [n.strip() for n in names]
    raise ValueError(f"sensitivities: expected a list of parameter symbols (docs/sensitivities.md), got "
                     f"{printable(repr(names), 120)}")


def modes(scene: Any, omega: Any = 0.0, harmonics: Any = (1, 2, 3), **keys: Any) -> dict[str, Any]:
    """Every natural mode of the scene's variant linearized about a steady spin at each rate of omega (rad/s):
    equal-length arrays omega, mode, kind, rad_s, hz, dimensionless, growth, undamped_rad_s, damping_ratio (zero
    without damping), label (the tracked mode, "bending 1", ...) and mac (to its shape at the rate before, NaN
    where it begins), and the variant's name; the closed loop's with [control]. Under "critical", the critical
    speeds, where a tracked mode meets the excitation omega = n Omega for n in harmonics: arrays label, harmonic,
    omega, rad_s and hz."""
    text, name = _source(scene)
    out = _core_call(_core.modes, text, name, _overrides(keys),
                     _rates(omega, "spin rates >= 0 (rad/s): a number or a list"), _harmonics(harmonics))
    return _modes_arrays(out)


def _harmonics(harmonics: Any) -> list[int]:
    """harmonics= as a list of integers from 1 to 1000, or ValueError naming what it got."""
    values = list(np.atleast_1d(np.asarray(harmonics, dtype=object)))
    if np.ndim(harmonics) > 1 or not values or not all(
            isinstance(n, (int, np.integer)) and not isinstance(n, (bool, np.bool_)) and 1 <= n <= 1000 for n in values):
        raise ValueError(f"harmonics: expected a list of integers from 1 to 1000, got {printable(repr(harmonics), 120)}")
    return [int(n) for n in values]


def _modes_arrays(out: dict[str, Any]) -> dict[str, Any]:
    """modes' text columns as numpy arrays, as its numbers are."""
    out["kind"] = np.array(out["kind"])
    out["label"] = np.array(out["label"])
    out["critical"]["label"] = np.array(out["critical"]["label"])
    return out


def linearize(scene: Any, omega: float, **keys: Any) -> dict[str, Any]:
    """x' = A x + B v, y = C x + D v about the steady spin omega (rad/s): A, B, C, D as arrays and the names of
    the states, inputs and outputs (docs/python.md "Modes and linearized models"); with [control] the closed loop,
    and the open loop under "open"."""
    text, name = _source(scene)
    if np.ndim(omega) != 0:
        raise ValueError(f"omega: expected a spin rate >= 0 (rad/s), got {printable(repr(omega), 120)}")
    return _core_call(_core.linearize, text, name, _overrides(keys), _rates(omega, "a spin rate >= 0 (rad/s)")[0])


def _core_call(function, *args):
    """A call into the core whose ValueError message shows every control and format character as an escape."""
    try:
        return function(*args)
    except ValueError as e:
        raise ValueError(printable(e, 2000)) from None


def _rates(omega: Any, expected: str) -> list[float]:
    """omega (a number or a list of numbers) as finite rates >= 0, or ValueError naming what it got: a string,
    None or a bool is not a rate even where float() would take it."""
    def bad():
        return ValueError(f"omega: expected {expected}, got {printable(repr(omega), 120)}")
    values = np.atleast_1d(np.asarray(omega, dtype=object))
    if values.ndim != 1 or values.size == 0:
        raise bad()
    rates = []
    for w in values:
        if isinstance(w, (bool, np.bool_)) or not isinstance(w, (int, float, np.integer, np.floating)):
            raise bad()
        w = float(w)
        if not (w >= 0.0 and math.isfinite(w)):
            raise bad()
        rates.append(w)
    return rates


def _run_text(text: str, name: str, keys: Mapping[str, Any]) -> Result:
    """run() of a scene's text (named name in messages): for the sweep's workers, which get the text, not a file.
    The run stops early when _cancel_runs() is called meanwhile (an interrupted sweep on local threads)."""
    return Result(_core_call(_core.run, text, name, _overrides(keys), True))


def _cancel_runs() -> None:
    _core.cancel_runs()


def _modes_text(text: str, name: str, keys: Mapping[str, Any], omegas: list[float]) -> dict[str, Any]:
    """modes() of a scene's text, for the sweep's workers; it stops early (RuntimeError) when _cancel_runs() is
    called meanwhile."""
    return _modes_arrays(_core_call(_core.modes, text, name, _overrides(keys), omegas, [1, 2, 3], True))


def _check_scene(text: str, name: str) -> None:
    _core_call(_core.check, text, name)


def _stop_runs_after_ctrl_c() -> None:
    """At the interpreter's exit, before it waits for its threads: if the main thread ended on Ctrl-C, the runs of
    other threads stop and raise KeyboardInterrupt too (Python delivers signals to the main thread only, and would
    wait for those runs to end)."""
    last = getattr(sys, "last_exc", None) or getattr(sys, "last_value", None)
    if isinstance(last, KeyboardInterrupt):
        _core.interrupt_runs()


if hasattr(threading, "_register_atexit"):  # called before the non-daemon threads are joined
    threading._register_atexit(_stop_runs_after_ctrl_c)


def sweep(*args: Any, **kwargs: Any):
    """Runs a parameter sweep on Dask (hubbeam.sweeps.run_sweep; docs/python.md, "Sweeps")."""
    from .sweeps import run_sweep
    return run_sweep(*args, **kwargs)


from .design import PARAMETER_KEYS, Objective, final_error, max_deflection, residual_vibration  # noqa: E402
