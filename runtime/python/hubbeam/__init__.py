"""hubbeam from Python: run scenes, compute modes and linearized models, sweep parameters (docs/python.md).

    import hubbeam
    r = hubbeam.run("cases/spinup_omega4.toml", method="fem", ny=8)
    r.t, r.tip_uy          # numpy arrays (views of one array r.data, no copy per row)
    r.completed, r.variant, r.source, r.max_abs_tip_uy, r.jacobi_drift, r.wall_seconds
    r.plot(); r.save("run.csv"); hubbeam.load("run.csv")   # a figure; the rows and their metadata, read back
"""
from __future__ import annotations

import difflib
import errno
import json
import math
import stat
import os
import re
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

__all__ = ["run", "modes", "linearize", "elastodyn_mode_shapes", "sweep", "load", "plot_campbell", "effective_scene", "Result", "RunStopped",
           "scene_keys", "generator_version", "printable", "Objective", "max_deflection", "residual_vibration",
           "final_error", "PARAMETER_KEYS"]
__version__ = _core.__version__

_KEYS = {name: expected for name, expected, kind, cap in _core.scene_keys()}  # dotted name -> what it takes
_KINDS = {name: kind for name, expected, kind, cap in _core.scene_keys()}  # "number", "integer", "word", "text", "file"
# The keys that name a file the scene reads, with the most bytes the core reads of it: the core's key table says
# which (Kind::file), so a file key added there is an input of every writer here too.
_FILE_KEYS = {name: cap for name, expected, kind, cap in _core.scene_keys() if kind == "file"}
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


def file_keys() -> dict[str, int]:
    """The scene keys that name a file the scene reads (beam.profile, beam.blade_file, motion.file), each with the
    most bytes hubbeam reads of that file: what every writer leaves alone and a sweep keys its points by."""
    return dict(_FILE_KEYS)


def scene_files(scene: Any, **keys: Any) -> dict[str, str]:
    """The files a scene (a file's path, or a dict of tables) reads besides itself with the keywords' keys set, as
    file key -> path resolved as hubbeam opens it (relative to the scene's folder). Only the scene's text is read:
    a scene refused for another key still names its files."""
    text, name = _source(scene)
    if not name:
        text, name = _scene_file_text(text), text
    return dict(_core_call(_core.scene_files, text, name, _overrides(keys)))


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
         "tau": "N m", "theta_ref": "rad", "controller_integral": "rad s", "dissipated": "J", "work": "J",
         "root_edge_moment": "N m", "root_flap_moment": "N m", "root_shear_edge": "N", "root_shear_flap": "N",
         "root_axial_force": "N"}


def unit_of(column: str) -> str:
    """A column's unit: UNITS', a rotor's blade column (tip_uy_2, root_edge_moment_3) its blade's quantity's."""
    return UNITS.get(column, UNITS.get(re.sub(r"_[0-9]+$", "", column), ""))


class Result:
    """One run: its rows as columns (numpy views of .data, n x 10, more with a scene's optional columns such as tau)
    and its summary as attributes. A column or summary name never replaces one of Result's own attributes (save,
    plot, data, ...): the core's names never do, and hubbeam.load refuses a file whose names would."""

    def __init__(self, raw: dict):
        self.data: np.ndarray = raw.pop("data")
        self.columns: tuple[str, ...] = tuple(raw.pop("columns").split(","))
        self.summary_text: str = raw.pop("summary_text")
        # Where the rows came from (the JSON hubbeam run writes beside its output): save() writes it, load() reads it.
        self.metadata: dict = json.loads(raw.pop("metadata"))
        self.scene_file: str = raw.pop("scene_file")
        # The files the rows came from, (path, what), as the core's scene_inputs names them: save() never replaces
        # one of them.
        self.inputs: list[tuple[str, str]] = [tuple(i) for i in raw.pop("inputs", [])]
        self.summary: dict = raw
        for name in [*raw, *self.columns]:
            if name in _RESERVED:
                raise ValueError(f"{printable(name, 80)}: expected a summary value or column name that is none of "
                                 f"Result's own attributes (data, columns, save, plot, ...)")
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
        df.attrs["units"] = {c: unit_of(c) for c in self.columns}
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
        read-only file, a folder, and any file the run read (its scene, profile, blade file or motion table, compared
        as files, not as names). Returns the path."""
        path = os.fspath(path)
        if not path.endswith((".csv", ".npy")):
            raise ValueError(f"path: expected a file name ending in .csv or .npy, got {printable(repr(path), 200)}")
        meta = dict(self.metadata, output=os.path.basename(path), rows=len(self.data))
        meta.setdefault("scene", {}).setdefault("output", {})["file"] = path
        _core.save_rows(path, self.data, ",".join(self.columns), json.dumps(meta, indent=2) + "\n",
                        [(file, what) for file, what in self.inputs])
        return path

    def __repr__(self) -> str:
        state = "completed" if self.completed else f"stopped at t = {self.t_reached:g} s"
        return f"<hubbeam.Result {self.variant}, {len(self.data)} rows, {state}>"


# Result's own attributes and methods, which no column or summary value may replace (r.save is always the method).
_RESERVED = frozenset(dir(Result)) | {"data", "columns", "summary_text", "metadata", "scene_file", "inputs", "summary"}

# The summary's values by type, as the core writes them (metadata.cpp's summary_json): numbers, which the metadata
# may hold as "inf", "-inf" or "nan" (JSON has no such numbers), texts, booleans and counts. Those Result itself reads
# (__repr__, RunStopped, plot) must be there; any of the others must be of its type where it is; any other key a
# number, a text or a boolean.
_SUMMARY_NUMBERS = ("t_reached", "max_abs_tip_uy", "t_steady", "jacobi_drift", "vibration_energy", "estimated_error",
                    "wall_seconds", "check_wall_seconds")
_SUMMARY_TEXTS = ("variant", "source", "algebra", "stepper", "stepper_why", "newton", "failure", "monitor_off",
                  "error_column", "error_from", "summary_text")
_SUMMARY_BOOLEANS = ("completed", "energy_balance")
_SUMMARY_COUNTS = ("steps", "rejected_steps", "rhs_evals", "jacobian_evals")
_SUMMARY_REQUIRED = ("completed", "failure", "variant", "summary_text", *_SUMMARY_NUMBERS)
METADATA_SUFFIX = ".hubbeam.json"
# The largest scene file read: the core's max_scene_bytes (runtime/include/hubbeam/scene.hpp).
_MAX_SCENE_BYTES = 1 << 20
# The largest metadata file read: a run's is a few kilobytes (its effective scene, summary and files).
MAX_METADATA_BYTES = 1 << 20


def _read_regular(path: str, cap: int | None, what: str) -> bytes:
    """The bytes of an input file, by the rules of every hubbeam reader: a path that is not a regular file (a FIFO,
    a device, a folder) is refused by stat before anything opens it (opening a FIFO blocks until a writer comes), the
    file is opened non-blocking in case it was swapped for one meanwhile, and more than cap bytes are refused without
    being read. FileNotFoundError where there is no file; ValueError naming the file (never quoting it) otherwise."""
    shown = printable(path)
    try:
        st = os.stat(path)
        if not stat.S_ISREG(st.st_mode):
            raise ValueError(f"{shown}: expected {what} (a regular file), got {_file_kind(st.st_mode)}")
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)
    except FileNotFoundError:
        raise FileNotFoundError(errno.ENOENT, f"{shown}: not found: expected {what}", path) from None
    except OSError as e:
        raise ValueError(f"{shown}: cannot open {what}: {e.strerror}") from None
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise ValueError(f"{shown}: expected {what} (a regular file), got {_file_kind(st.st_mode)}")
        chunks, size = [], 0
        while cap is None or size <= cap:
            chunk = os.read(fd, 1 << 20 if cap is None else min(1 << 20, cap + 1 - size))
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
    except OSError as e:
        raise ValueError(f"{shown}: cannot read {what}: {e.strerror}") from None
    finally:
        os.close(fd)
    if cap is not None and size > cap:
        raise ValueError(f"{shown}: expected {what} of at most {cap >> 10} KB, got a larger file")
    return b"".join(chunks)


def _scene_file_text(path: str) -> str:
    """A scene file's text, read as the core reads one (at most its max_scene_bytes, never opening a FIFO)."""
    return _text_of(_read_regular(path, _MAX_SCENE_BYTES, "a scene file"), path, "a scene file")


def _file_kind(mode: int) -> str:
    """What a file that is not a regular file is, as the core's messages say it."""
    for test, name in ((stat.S_ISDIR, "a directory"), (stat.S_ISFIFO, "a FIFO"), (stat.S_ISCHR, "a character device"),
                       (stat.S_ISBLK, "a block device"), (stat.S_ISSOCK, "a socket")):
        if test(mode):
            return name
    return "not a regular file"


def _text_of(data: bytes, path: str, what: str) -> str:
    """data as UTF-8 text, or ValueError naming the file and the byte where it is not (never the bytes)."""
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise ValueError(f"{printable(path)}: expected {what} (UTF-8 text), got bytes that are not text at byte "
                         f"{e.start}") from None


def _metadata_of(meta_path: str) -> dict:
    """A run's metadata file, read and checked key by key: every value load() and Result use has its type, and no
    name would replace an attribute of Result. ValueError naming the file and the key (never the file's values)."""
    text = _text_of(_read_regular(meta_path, MAX_METADATA_BYTES, "hubbeam's metadata"), meta_path,
                    "hubbeam's metadata")
    shown = printable(meta_path)
    try:
        meta = json.loads(text)
    except json.JSONDecodeError as e:
        raise ValueError(f"{shown}: line {e.lineno}, column {e.colno}: expected hubbeam's metadata (JSON)") from None
    except RecursionError:
        raise ValueError(f"{shown}: expected hubbeam's metadata (JSON), got values nested too deeply") from None

    def bad(key: str, expected: str):
        return ValueError(f"{shown}: {printable(key, 80)}: expected {expected}")

    if not isinstance(meta, dict) or meta.get("format") != "hubbeam-metadata 1":
        raise bad("format", "\"hubbeam-metadata 1\" (hubbeam.load reads the metadata hubbeam run writes)")
    if meta.get("command") != "run":
        raise bad("command", "\"run\" (hubbeam.load reads the metadata of a run)")
    columns = meta.get("columns")
    if not isinstance(columns, list) or not columns or not all(isinstance(c, str) and c for c in columns) or \
            columns[0] != "t":
        raise bad("columns", "a list of column names, the first t")
    if len(set(columns)) != len(columns):
        raise bad("columns", "a list of column names, each once")
    rows = meta.get("rows")
    if not isinstance(rows, int) or isinstance(rows, bool) or rows < 0:
        raise bad("rows", "a number of rows (an integer >= 0)")
    if not isinstance(meta.get("scene_file"), str):
        raise bad("scene_file", "the scene file's name (a string)")
    tables = meta.get("tables", {})
    if not isinstance(tables, dict) or not all(isinstance(t, dict) and isinstance(t.get("path"), str)
                                               for t in tables.values()):
        raise bad("tables", "a table of the files the scene read, each with its \"path\"")
    summary = meta.get("summary")
    if not isinstance(summary, dict):
        raise bad("summary", "a table of the run's summary values")
    for key in _SUMMARY_REQUIRED:
        if key not in summary:
            raise bad(f"summary.{key}", "a value (the key is missing)")
    for key, value in summary.items():
        where = f"summary.{key}"
        if key in _SUMMARY_NUMBERS:
            if not (isinstance(value, (int, float)) and not isinstance(value, bool)) and \
                    value not in ("inf", "-inf", "nan"):
                raise bad(where, "a number (or \"inf\", \"-inf\", \"nan\")")
        elif key in _SUMMARY_TEXTS:
            if not isinstance(value, str):
                raise bad(where, "a text")
        elif key in _SUMMARY_BOOLEANS:
            if not isinstance(value, bool):
                raise bad(where, "true or false")
        elif key in _SUMMARY_COUNTS:
            if not isinstance(value, int) or isinstance(value, bool):
                raise bad(where, "an integer")
        elif not isinstance(value, (str, int, float, bool)):
            raise bad(where, "a number, a text or a boolean")
    for name in [*(k for k in summary if k != "summary_text"), *columns]:  # Result keeps summary_text as itself
        if name in _RESERVED:
            raise bad(name, "a summary value or column name that is none of Result's own attributes (data, columns, "
                            "save, plot, ...)")
    if set(summary) & set(columns):
        raise bad(sorted(set(summary) & set(columns))[0], "a name that is a column or a summary value, not both")
    return meta


def _csv_rows(path: str) -> tuple[list[str], np.ndarray]:
    """A run CSV's header and rows (an n x width array), or ValueError naming the file and the line and column
    where it is not one (never a cell's text: the file may be anyone's)."""
    shown = printable(path)
    text = _text_of(_read_regular(path, None, "a run's CSV"), path, "a run's CSV")
    lines = text.split("\n")
    header = lines[0].rstrip("\r").split(",")
    body = lines[1:]
    if body and body[-1] == "":
        body.pop()  # the newline that ends the last row
    try:
        data = np.loadtxt(body, delimiter=",", ndmin=2, dtype=float) if body else np.empty((0, len(header)))
    except ValueError:
        # Where it failed, found again here: numpy's message quotes the cell.
        for n, line in enumerate(body, start=2):
            cells = line.rstrip("\r").split(",")
            if len(cells) != len(header):
                raise ValueError(f"{shown}: line {n}: expected {len(header)} fields, got {len(cells)}") from None
            for c, cell in enumerate(cells, start=1):
                try:
                    float(cell)
                except ValueError:
                    raise ValueError(f"{shown}: line {n}, column {c}: expected a number") from None
        raise ValueError(f"{shown}: expected rows of numbers separated by commas") from None
    return header, data


def _npy_rows(path: str) -> tuple[list[str], np.ndarray]:
    """A run's .npy rows and the column names of NAME.columns.txt beside them, or ValueError naming the file."""
    import io

    try:
        data = np.load(io.BytesIO(_read_regular(path, None, "a run's .npy rows")), allow_pickle=False)
    except (ValueError, OSError, EOFError) as e:
        if isinstance(e, FileNotFoundError):
            raise
        raise ValueError(f"{printable(path)}: expected a run's rows as a .npy array of numbers") from None
    if not isinstance(data, np.ndarray) or data.dtype.kind not in "fiu":
        raise ValueError(f"{printable(path)}: expected a run's rows as a .npy array of numbers")
    columns = os.path.splitext(path)[0] + ".columns.txt"
    text = _text_of(_read_regular(columns, MAX_METADATA_BYTES, "the rows' column names"), columns,
                    "the rows' column names")
    return text.split("\n", 1)[0].rstrip("\r").split(","), data


def load(path: str | os.PathLike) -> Result:
    """Reads a run's output back, CSV or .npy, with the metadata written beside it (PATH.hubbeam.json, by hubbeam run
    or Result.save) into the Result that hubbeam.run returned: its columns, summary, to_pandas() and plot(). Raises
    FileNotFoundError without the metadata, ValueError where the metadata is not a run's (a key missing or of
    another type, a name that is one of Result's own attributes) or does not describe the file (another row count or
    header: the file was changed or replaced since), or where a file is not a regular file (a FIFO is refused
    without being opened). No message quotes a file's content: the file, the line and column or key, and what was
    expected."""
    path = os.fspath(path)
    meta_path = path + METADATA_SUFFIX
    try:
        meta = _metadata_of(meta_path)
    except FileNotFoundError:
        raise FileNotFoundError(errno.ENOENT, f"{printable(meta_path)}: not found: hubbeam.load reads a run's output "
                                f"with the metadata that hubbeam run and Result.save write beside it", meta_path) \
            from None
    columns = meta["columns"]
    header, data = _npy_rows(path) if path.endswith(".npy") else _csv_rows(path)
    if header != columns or data.ndim != 2 or data.shape != (meta["rows"], len(columns)):
        raise ValueError(f"{printable(path)}: expected the rows and columns that {printable(meta_path)} describes, "
                         f"got {'another header' if header != columns else 'another number of rows or columns'}: the "
                         f"file was changed or replaced after its metadata was written")
    raw = dict(meta["summary"])
    for k in _SUMMARY_NUMBERS:
        raw[k] = float(raw[k])
    inputs = [(meta["scene_file"], "the scene itself")]
    inputs += [(t["path"], f"the scene's {key}") for key, t in meta.get("tables", {}).items()]
    raw.update(data=np.ascontiguousarray(data, dtype=float), columns=",".join(columns),
               metadata=json.dumps(meta), scene_file=meta["scene_file"], inputs=inputs)
    return Result(raw)


def effective_scene(scene: Any, **keys: Any) -> str:
    """The scene as TOML with every key it runs with, defaults filled and the keywords applied (what
    hubbeam run --print-scene prints); a file saved from it runs the same."""
    text, name = _source(scene)
    return _core_call(_core.effective_scene, text, name, _overrides(keys))


def plot_campbell(m: Any, **options: Any):
    """A Campbell diagram of modes(...) (or of a modes CSV's path) with matplotlib, as rotor engineers draw it: the
    tracked modes' frequencies (Hz) against the spin rate in their families' shades, named at their ends, the
    per-rev lines and the critical speeds, the damping ratios in a panel below with the unstable points marked;
    returns the figure (hubbeam.plots.plot_campbell for the options: kinds, count, harmonics, spin_unit, blades,
    operating_range, max_frequency, ax, label). Needs matplotlib (python3-matplotlib)."""
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


def _nearest_key(name: str) -> str:
    """ " (did you mean NAME?)" for a keyword that looks like a typo of a scene key's leaf or dotted name, else ""."""
    if not isinstance(name, str):
        return ""
    near = difflib.get_close_matches(name, [*_LEAVES, *_KEYS], n=1, cutoff=0.75)
    return f" (did you mean {near[0]}?)" if near else ""


def _overrides(keywords: Mapping[str, Any]) -> list[tuple[str, str, str]]:
    """Keyword arguments (leaf names such as ny, or dotted names) as scene-key overrides: (dotted key, value as
    text, the keyword, which messages name)."""
    out = []
    for name, value in keywords.items():
        keys = [name] if name in _KEYS else _LEAVES.get(name, [])
        if not keys:
            raise ValueError(f"{printable(name, 80)}: expected a scene key (docs/scene.md; hubbeam.scene_keys()), "
                             f"got an unknown keyword{_nearest_key(name)}")
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
    """(text, name) for the core: a path with an empty name (the core reads it), or a dict's TOML. FileNotFoundError
    for a path where there is no file, as open() raises it (the core's other refusals of a path are ValueErrors)."""
    if isinstance(scene, (str, os.PathLike)):
        path = os.fspath(scene)
        if isinstance(path, str) and path and "\0" not in path:
            try:
                os.stat(path)
            except FileNotFoundError:  # also a link to nothing; any other failure is the core's to word
                raise FileNotFoundError(errno.ENOENT, f"{printable(path)}: no such scene file", path) from None
            except OSError:
                pass
        return path, ""
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


def modes(scene: Any, omega: Any = 0.0, harmonics: Any = (1, 2, 3), frame: Any = None, **keys: Any) -> dict[str, Any]:
    """Every natural mode of the scene's variant linearized about a steady spin at each rate of omega (rad/s):
    equal-length arrays omega, mode, kind, rad_s, hz, dimensionless, growth, undamped_rad_s, damping_ratio (zero
    without damping), label (the tracked mode, "bending 1", ...) and mac (to its shape at the rate before, NaN
    where it begins), and the variant's name; the closed loop's with [control]. Under gravity in the plane of
    rotation a rate > 0 has no steady state: its modes are the Floquet modes of the periodic motion (hubbeam modes'
    too, docs/model.md section 10.1), those one revolution resolves. Under "critical", the critical speeds, where a
    tracked mode meets the excitation omega = n Omega for n in harmonics: arrays label, harmonic, omega, rad_s and
    hz; harmonics=None (or "none") searches none, and they are empty. A rotor of 3 or more identical blades has its
    modes in multi-blade coordinates (frame "fixed", the default where they apply: kinds "collective flap", "BW edge",
    "FW edge", "differential flap", "hub x", ...; docs/model.md section 13.2), or each blade's in its own frame with
    frame="rotating"; frame="fixed" where they do not apply is a ValueError naming why."""
    text, name = _source(scene)
    out = _core_call(_core.modes, text, name, _overrides(keys),
                     _rates(omega, "spin rates >= 0 (rad/s): a number or a list"), _harmonics(harmonics), False,
                     _frame(frame))
    return _modes_arrays(out)


def _frame(frame: Any) -> str:
    """frame= as the core takes it: "" for None (fixed where multi-blade coordinates apply), "fixed" or "rotating";
    ValueError naming what it got otherwise."""
    if frame is None:
        return ""
    if not isinstance(frame, str) or frame not in ("fixed", "rotating"):
        raise ValueError(f"frame: expected \"fixed\", \"rotating\" or None, got {printable(repr(frame), 120)}")
    return frame


def _harmonics(harmonics: Any) -> list[int]:
    """harmonics= as a list of integers from 1 to 1000 (None or "none": no critical speed searched, an empty list),
    or ValueError naming what it got."""
    if harmonics is None or (isinstance(harmonics, str) and harmonics == "none"):
        return []
    values = list(np.atleast_1d(np.asarray(harmonics, dtype=object)))
    if np.ndim(harmonics) > 1 or not values or not all(
            isinstance(n, (int, np.integer)) and not isinstance(n, (bool, np.bool_)) and 1 <= n <= 1000 for n in values):
        raise ValueError(f"harmonics: expected a list of integers from 1 to 1000, or None, got "
                         f"{printable(repr(harmonics), 120)}")
    return [int(n) for n in values]


def _modes_arrays(out: dict[str, Any]) -> dict[str, Any]:
    """modes' text columns as numpy arrays, as its numbers are."""
    out["kind"] = np.array(out["kind"])
    out["label"] = np.array(out["label"])
    out["critical"]["label"] = np.array(out["critical"]["label"])
    return out


def linearize(scene: Any, omega: float, frame: Any = None, **keys: Any) -> dict[str, Any]:
    """x' = A x + B v, y = C x + D v about the steady spin omega (rad/s): A, B, C, D as arrays and the names of
    the states, inputs and outputs (docs/python.md "Modes and linearized models"); with [control] the closed loop,
    and the open loop under "open". A rotor of 3 or more identical blades in multi-blade coordinates (states
    "B1_coll", "B1_cos1", ...) unless frame="rotating", as modes takes frame."""
    text, name = _source(scene)
    if np.ndim(omega) != 0:
        raise ValueError(f"omega: expected a spin rate >= 0 (rad/s), got {printable(repr(omega), 120)}")
    return _core_call(_core.linearize, text, name, _overrides(keys), _rates(omega, "a spin rate >= 0 (rad/s)")[0],
                      _frame(frame))


def elastodyn_mode_shapes(scene: Any, omega: float = 0.0, **keys: Any) -> dict[str, Any]:
    """A blade's mode shapes about the steady spin omega (rad/s) fitted as ElastoDyn takes them (hubbeam modes
    --elastodyn; docs/python.md): under "BldFl1Sh", "BldFl2Sh" and "BldEdgSh" (flap 1, flap 2, edge 1) the mode's
    name, rad_s, hz, coefficients (of x^2 .. x^6, summing to 1), residual (the fit's RMS error, a fraction of the tip
    deflection) and the samples xi, phi (normalised to 1 at the tip); "section", the blade file's BLADE MODE SHAPES
    lines. ValueError for a scene without flapwise coordinates (discretization.nz = 0)."""
    text, name = _source(scene)
    if np.ndim(omega) != 0:
        raise ValueError(f"omega: expected a spin rate >= 0 (rad/s), got {printable(repr(omega), 120)}")
    return _core_call(_core.elastodyn_mode_shapes, text, name, _overrides(keys),
                      _rates(omega, "a spin rate >= 0 (rad/s)")[0])


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
