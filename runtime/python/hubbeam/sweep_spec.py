"""A sweep's specification: the sweep file or dict read and checked, its points expanded, and each point's key for
resuming (the effective scene it runs: the base scene, the files it reads, its overrides, the version)."""
from __future__ import annotations

import hashlib
import itertools
import json
import os
import tomllib
from typing import Any, Mapping

# What a sweep may keep per point: the run's summary values, its tip series (t, tip_uy), the elastic modes'
# frequencies about the point's steady spin, and the invariant drift relative to the vibration energy.
SUMMARY_VALUES = ("completed", "t_reached", "max_abs_tip_uy", "jacobi_drift", "vibration_energy", "steps",
                  "rejected_steps", "rhs_evals", "jacobian_evals", "wall_seconds", "variant", "source", "stepper")
DERIVED_VALUES = ("relative_drift", "tip_series", "frequencies")
DEFAULT_KEEP = ("max_abs_tip_uy", "relative_drift", "wall_seconds")
# The mode kinds whose frequencies "frequencies" keeps: the beam's elastic modes as the core labels them (a planar
# beam's bending, a blade's edge, flap and twist), as the Campbell diagram draws them (plots.CAMPBELL_KINDS).
ELASTIC_KINDS = ("bending", "edge", "flap", "twist")


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


def _check_path(what: str, path: Any) -> None:
    if not isinstance(path, (str, os.PathLike)) or not os.fspath(path) or "\0" in os.fspath(path):
        raise SweepError(f"{what}: expected a file name (not empty, no NUL character), got "
                         f"{_printable(repr(path), 120)}")


def _read_spec(spec: str | os.PathLike | Mapping[str, Any]) -> tuple[str, str, dict[str, Any]]:
    """The sweep as given, unchecked: (where, for messages; the folder its paths are relative to; its keys). A
    SWEEP.toml file is read as a scene file is; a dict's numpy numbers and arrays become plain values."""
    if isinstance(spec, Mapping):
        from hubbeam import _plain  # numpy's numbers and arrays go into a dict sweep as into every other call

        where, base_dir = "<dict sweep>", os.getcwd()
        sweep = {k: {kk: _plain(vv) for kk, vv in v.items()} if isinstance(v, Mapping) else _plain(v)
                 for k, v in spec.items()}
        if isinstance(sweep.get("points"), list):
            sweep["points"] = [{kk: _plain(vv) for kk, vv in p.items()} if isinstance(p, Mapping) else p
                               for p in sweep["points"]]
        return where, base_dir, sweep
    where = os.fspath(spec)
    _check_path("sweep file", where)
    from hubbeam import _MAX_SCENE_BYTES  # a sweep file is read as a scene file is

    data = _read_input(where, _MAX_SCENE_BYTES, "a sweep file")
    try:
        sweep = tomllib.loads(data.decode("utf-8-sig"))  # a byte order mark, as the scene reader takes it
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as e:
        raise SweepError(f"{_printable(where)}: {_printable(e)}") from None
    return where, os.path.dirname(os.path.abspath(where)), sweep


def load_sweep(spec: str | os.PathLike | Mapping[str, Any]) -> dict[str, Any]:
    """The sweep of a SWEEP.toml file or of a dict with the same keys, checked: scene (the base scene's path),
    set (key -> value for every point), grid (key -> list of values), points (list of key -> value tables), keep
    (names from SUMMARY_VALUES and DERIVED_VALUES), frequencies (how many), output (the CSV; default the sweep
    file's name with .csv). Every path a sweep file gives (scene, output, a file key's value) is relative to the
    sweep file's folder, a dict's to the current folder: base is that folder."""
    where, base_dir, sweep = _read_spec(spec)
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


def _base_scene_text(sweep: Mapping[str, Any]) -> str:
    """The base scene's text, read and checked before any task (SweepError, or the core's ValueError naming the
    key)."""
    import hubbeam

    _check_path("scene", sweep["scene"])
    try:
        scene_text = hubbeam._scene_file_text(sweep["scene"])  # as hubbeam.run reads a scene
    except (OSError, ValueError) as e:
        raise _sweep_error(e) from None
    hubbeam._check_scene(scene_text, sweep["scene"])  # a bad base scene stops the sweep before any task
    return scene_text
