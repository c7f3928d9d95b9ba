"""A sweep's table: its header, rows appended one whole line at a time, the tip series beside it, and an earlier
table read back to resume (its finished rows kept, its stale ones dropped, a cut last line cut off)."""
from __future__ import annotations

import csv
import dataclasses
import errno
import io
import os
import stat
import sys
from typing import Any, Sequence

from .sweep_spec import SweepError, _file_kind, _printable

# The type of each kept value as the table's text reads back (the rest are floats): hubbeam.sweep returns these.
_TEXT_COLUMNS = {"point", "status", "variant", "source", "stepper"}
_INT_COLUMNS = {"steps", "rejected_steps", "rhs_evals", "jacobian_evals"}


def _columns(keys: Sequence[str], keep: Sequence[str], frequencies: int) -> list[str]:
    """The table's header: the point's key, the sweep's keys, its status, the values kept, its run's time."""
    values = []
    for k in keep:
        values += [f"f{i}_hz" for i in range(1, frequencies + 1)] if k == "frequencies" else [k]
    return ["point", *keys, "status", *values, "run_seconds"]


def _cell(value: Any) -> str:
    """A value as its cell's text: empty for None, a float as repr writes it (it reads back the same)."""
    if value is None:
        return ""
    return repr(value) if isinstance(value, float) else str(value)


def _csv_line(values: Sequence[Any]) -> str:
    """One row of the table, its newline included."""
    buffer = io.StringIO()
    csv.writer(buffer, lineterminator="\n").writerow([_cell(v) for v in values])
    return buffer.getvalue()


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


@dataclasses.dataclass
class _Earlier:
    """What an earlier run left in the table: the rows done (point key -> fields), the lines kept, whether rows were
    dropped as stale, the byte length of its complete lines and whether its last line was cut."""
    done: dict[str, list[str]]
    kept_lines: list[str]
    stale: bool
    good_end: int
    cut: bool


def _earlier_rows(path: str, header: list[str], keys: Sequence[str], points: Sequence[dict[str, Any]],
                  ids: Sequence[str], resume: bool) -> _Earlier:
    """The earlier table at path sorted for resuming (nothing with resume=False)."""
    folder = os.path.dirname(os.path.abspath(path))
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
    return _Earlier(done, kept_lines, len(kept_lines) < len(rows), good_end, cut)


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


class _TableOutput:
    """Where a sweep's rows go: the table itself, appended to, or a new table beside it (DIR/.NAME.tmp-PID) that
    replaces it whole. Opened only once the cluster answers, so that a sweep that cannot start writes nothing."""

    def __init__(self, path: str, shown: str):
        self.path, self.shown = path, shown
        self.table: _Table | None = None
        self.temporary: str | None = None

    def open(self, earlier: _Earlier, header: list[str], resume: bool, mode: int, replace_mode: int,
             progress: bool) -> _Table:
        """The table to append to: the old one past its complete lines, or its replacement holding the rows kept."""
        if resume and not earlier.stale:
            if earlier.cut and progress:
                print(f"sweep: {self.shown}: its last line was cut (a write that did not finish): dropped, that point "
                      f"runs again", file=sys.stderr)
            self.table = _Table(self.path, self.shown, earlier.good_end,
                                _csv_line(header) if earlier.good_end == 0 else None, mode)
            return self.table
        # A new table beside the old one, which it replaces whole: with stale rows dropped it starts with the rows
        # kept; with resume=False it replaces the old table only once complete.
        folder = os.path.dirname(os.path.abspath(self.path))
        self.temporary = os.path.join(folder, f".{os.path.basename(self.path)}.tmp-{os.getpid()}")
        self.table = _Table(self.temporary, self.shown, None, _csv_line(header) + "".join(earlier.kept_lines),
                            replace_mode, new=True)
        if resume:
            try:
                os.replace(self.temporary, self.path)
            except OSError as e:
                raise SweepError(f"{self.shown}: cannot replace the table without its stale rows: "
                                 f"{e.strerror}") from None
            self.temporary = None
        return self.table

    def finish(self) -> None:
        """Every row written: the table synced and, if it is a new one, put in place of the old."""
        self.table.close(sync=True)
        self.table = None
        if self.temporary is not None:
            try:
                os.replace(self.temporary, self.path)
            except OSError as e:
                raise SweepError(f"{self.shown}: cannot replace the old table with the new one: {e.strerror}") from None
            self.temporary = None

    def abandon(self) -> None:
        """After finish, nothing; else the table closed as it is, and an unfinished replacement removed (the old
        table stays as it was)."""
        if self.table is not None:
            self.table.close(sync=False)
        if self.temporary is not None:
            try:
                os.remove(self.temporary)
            except OSError:
                pass


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


def _typed_rows(path: str, header: list[str], lines: dict[str, list[str]], ids: Sequence[str],
                points: Sequence[dict[str, Any]], keys: Sequence[str]) -> list[dict[str, Any]]:
    """The table hubbeam.sweep returns: a dict per point in the sweep's order, from the fields of its row."""
    folder = os.path.dirname(os.path.abspath(path))
    by_point = {k: dict(zip(header, row)) for k, row in lines.items()}
    out = []
    for i, k in enumerate(ids):
        row = {c: _typed(c, v, folder) for c, v in by_point[k].items()}
        row.update({key: points[i].get(key) for key in keys})  # the point's own values, as the sweep gave them
        out.append(row)
    return out
