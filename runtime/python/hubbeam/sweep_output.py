"""Where a sweep may write, checked before anything is written: the table's name and permissions, its lock beside it,
and the temporary files a killed writer left there."""
from __future__ import annotations

import fcntl
import os
import re
import stat
from typing import Sequence

from .sweep_spec import SweepError, _check_path, _file_kind, _printable


def _same_file(a: str, b: str) -> bool:
    """Whether a and b are one file: the same device and inode (through links); False when either does not exist."""
    try:
        sa, sb = os.stat(a), os.stat(b)
    except OSError:
        return False
    return (sa.st_dev, sa.st_ino) == (sb.st_dev, sb.st_ino)


def _check_output(path: str, inputs: Sequence[tuple[str, str]]) -> None:
    """SweepError unless path can be the table: a regular file its owner may write, or a new name in an existing
    folder; never a symbolic link (an attacker's link in a shared folder would point the table at their victim),
    and none of the sweep's inputs (what, path), compared as files, not as names."""
    _check_path("--output", path)
    from hubbeam import _core  # the one check of an output's name, every writer's (printable.hpp)

    if why := _core.unsafe_character(os.fsencode(path)):
        raise SweepError(f"-o: expected a file name without control or format characters, got {why}")
    shown = _printable(path)
    try:
        st = os.lstat(path)
    except FileNotFoundError:
        st = None
    except OSError as e:
        raise SweepError(f"{shown}: cannot open for writing: {e.strerror}") from None
    if st is not None and stat.S_ISLNK(st.st_mode):
        raise SweepError(f"{shown}: expected a regular file or the name of a new one, got a symbolic link (hubbeam "
                         f"does not write through a link: give the file it points to)")
    if st is not None and stat.S_ISDIR(st.st_mode):
        raise SweepError(f"{shown}: expected a file for the sweep's table, got a directory (give -o DIR/NAME.csv)")
    if st is not None and not stat.S_ISREG(st.st_mode):
        raise SweepError(f"{shown}: expected a regular file for the sweep's table, got {_file_kind(st.st_mode)}")
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise SweepError(f"{shown}: expected a file in an existing folder, got a folder that does not exist")
    if st is not None and not st.st_mode & stat.S_IWUSR:
        # The rule of every hubbeam writer (output_file.cpp), root included.
        raise SweepError(f"{shown} is read-only (mode {stat.S_IMODE(st.st_mode):04o}): hubbeam does not replace a "
                         f"file you protected; chmod u+w it or choose another output")
    if not os.access(folder, os.W_OK) or (st is not None and not os.access(path, os.W_OK)):
        raise SweepError(f"{shown}: cannot write there (permission denied)")
    for what, other in inputs:
        if _same_file(path, other):
            raise SweepError(f"{shown}: expected an output other than the {what} ({_printable(other)}), got the "
                             f"same file")


def _table_mode(inputs: Sequence[os.stat_result]) -> int:
    """The permissions the table and its series files are created with (before the umask): read and write for
    everyone, less group's if one input is not readable by its group and less others' if one is not readable by
    others, so the table (whose rows come from those files) is never readable by someone who cannot read them."""
    mode = 0o666
    for st in inputs:
        if not st.st_mode & stat.S_IRGRP:
            mode &= ~0o070
        if not st.st_mode & stat.S_IROTH:
            mode &= ~0o007
    return mode


def _replace_mode(path: str, mode: int) -> int:
    """The permissions of a table that replaces the one at path: mode, and no wider than the old table either (the
    rule of every hubbeam writer)."""
    try:
        return mode & (stat.S_IMODE(os.stat(path).st_mode) | 0o600)
    except OSError:
        return mode


# DIR/.NAME.tmp-PID or .NAME.tmp-PID-N: a temporary file of a hubbeam writer (output_file.cpp names them so too).
_TEMPORARY = re.compile(r"\.(.+)\.tmp-(\d+)(?:-\d+)?")


def _clean_leftovers(folder: str, name: str | None) -> None:
    """Removes the temporary files of name (every name when None) in folder that a killed writer left: its pid no
    longer runs and the file is this user's. Called holding the table's lock, so no live hubbeam writes them."""
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return
    for entry in entries:
        m = _TEMPORARY.fullmatch(entry.name)
        if not m or (name is not None and m.group(1) != name) or int(m.group(2)) == os.getpid():
            continue
        try:
            os.kill(int(m.group(2)), 0)
            continue  # alive (or another user's): not ours to remove
        except ProcessLookupError:
            pass
        except (PermissionError, OverflowError):
            continue
        try:
            st = entry.stat(follow_symlinks=False)
            if stat.S_ISREG(st.st_mode) and st.st_uid == os.geteuid():
                os.remove(entry.path)
        except OSError:
            pass


def _series_dir(path: str) -> str:
    """The folder of the tip series of the table at path: TABLE.series beside TABLE.csv."""
    return os.path.splitext(path)[0] + ".series"


def _prepare_folders(path: str, keep: Sequence[str]) -> None:
    """Removes what a killed writer of the table at path left beside it and in its series folder. A series folder
    that is a link or no folder is refused before anything is written or removed (the table's header included), not
    at the first point's series; one the sweep keeps no series in is left alone."""
    folder = os.path.dirname(os.path.abspath(path))
    series_folder = _series_dir(os.path.abspath(path))
    if os.path.islink(series_folder) or (os.path.lexists(series_folder) and not os.path.isdir(series_folder)):
        if "tip_series" in keep:
            raise SweepError(f"{_printable(series_folder)}: expected the table's folder of tip series, got a "
                             f"symbolic link or a file (hubbeam does not write through a link)")
    else:
        _clean_leftovers(series_folder, None)
    _clean_leftovers(folder, os.path.basename(path))  # what a killed writer of this table left


class _OutputLock:
    """The lock every hubbeam writer takes beside its output, DIR/.NAME.lock (flock, as runtime/src/io/output_file.cpp):
    while one sweep or command writes a table, another that would write it is refused at once. The lock file is
    removed when released, so once locked it must still be the file at that path, else it is taken again."""

    def __init__(self, path: str, shown: str):
        target = os.path.abspath(path)
        self.path = os.path.join(os.path.dirname(target), "." + os.path.basename(target) + ".lock")
        for _ in range(100):
            try:
                fd = os.open(self.path, os.O_RDONLY | os.O_CREAT | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC,
                             0o666)
            except OSError as e:
                raise SweepError(f"{shown}: cannot create its lock file {_printable(self.path)}: {e.strerror}") \
                    from None
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError:
                os.close(fd)
                raise SweepError(f"another hubbeam is writing {shown} (it holds {_printable(self.path)}): wait for "
                                 f"it to finish, or write to another file") from None
            held = os.fstat(fd)
            try:
                now = os.stat(self.path)
                if (now.st_dev, now.st_ino) == (held.st_dev, held.st_ino):
                    self.fd = fd
                    return
            except OSError:
                pass
            os.close(fd)
        raise SweepError(f"{shown}: its lock file {_printable(self.path)} keeps changing")

    def release(self) -> None:
        try:
            os.remove(self.path)  # while still holding it: a writer waiting on this file re-checks and retries
        except OSError:
            pass
        os.close(self.fd)
