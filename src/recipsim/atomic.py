"""Atomic writes: a file or an output directory appears whole or not at all.

Output directories are also *guarded*: recipsim only ever replaces a directory that it
wrote itself (it carries :data:`MARKER`), or an empty one, and only at a path inside the
directory the user pointed to. A name that would lead elsewhere (``""``, ``"."``,
``".."``, ``"a/b"``, an absolute path) is refused before anything is written
(:func:`checked_name`).
"""

from __future__ import annotations

import os
import re
import shutil
import socket
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager, suppress
from itertools import count
from pathlib import Path
from typing import IO, Any

from recipsim.errors import CaseError

#: File written into every directory recipsim creates as a whole (reports, comparisons,
#: studies, sweeps, benches); a directory without it is never replaced or written into.
MARKER = ".recipsim-output"

#: Longest case, study or sweep name [characters].
MAX_NAME_LENGTH = 100

_NAME = re.compile(r"[A-Za-z0-9._-]+")

#: numbers of the temporary files of :func:`write_bytes_atomically`
_TEMPORARY_NUMBERS = count()


def checked_name(name: object, file: str, key: str = "name") -> str:
    """Return ``name`` if it is a plain file name, else raise :class:`CaseError`.

    Allowed: letters, digits, ``.``, ``_`` and ``-``, 1 to :data:`MAX_NAME_LENGTH`
    characters, not ``.`` or ``..`` and not starting with a dot (recipsim's temporary
    directories do). Such a name, joined to a directory, stays inside it.
    """
    allowed = (
        f"a plain file name (it becomes a directory name): letters, digits, '.', '_' and "
        f"'-', 1 to {MAX_NAME_LENGTH} characters, not starting with '.'"
    )
    if not isinstance(name, str):
        raise CaseError(file, key, f"expected a string, {allowed}")
    if not _NAME.fullmatch(name) or name.startswith(".") or len(name) > MAX_NAME_LENGTH:
        shown = name if len(name) <= 40 else name[:40] + "..."
        raise CaseError(file, key, f"{shown!r} is not allowed as a name; {allowed}")
    return name


def name_from_stem(stem: str) -> str:
    """A safe default name from a file name's stem (other characters become ``_``)."""
    name = re.sub(r"[^A-Za-z0-9._-]", "_", stem).lstrip(".")[:MAX_NAME_LENGTH]
    return name or "case"


def normalised(path: Path | str) -> Path:
    """``path`` made absolute with ``..`` and ``.`` removed as written (``out/x/..`` is
    ``out`` even where ``x`` does not exist yet), so that every later check and write
    sees the same directory."""
    return Path(os.path.normpath(os.path.abspath(path)))


def check_replaceable(target: Path) -> None:
    """Refuse ``target`` if it exists and is neither empty nor a recipsim output."""
    target = normalised(target)
    if target.is_symlink() or (target.exists() and not target.is_dir()):
        raise CaseError(str(target), "--out", "exists and is not a directory; choose another")
    if target.is_dir() and not (target / MARKER).is_file():
        try:
            empty = not any(target.iterdir())
        except OSError as exc:
            raise CaseError(str(target), "--out", f"cannot be read ({exc.strerror})") from None
        if not empty:
            raise CaseError(
                str(target),
                "--out",
                f"exists and was not written by recipsim (no {MARKER}); recipsim replaces "
                "only its own output directories: choose a new or empty directory",
            )


def _temporary_prefix(target: Path) -> str:
    return f".{target.name}.tmp-{socket.gethostname()}-"


def pid_alive(pid: int) -> bool:
    """Whether process ``pid`` runs on this host (one of another user counts)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def clean_stale_temporaries(target: Path) -> None:
    """Remove the temporary and old copies of ``target`` that recipsim runs on this host
    made and left behind when they were killed.

    Only names recipsim makes are considered, each carrying the process id of the run
    that made it: ``.<name>.tmp-<host>-<pid>-<n>`` (a report being built) and
    ``.<name>.old-<pid>-<ns>`` (the previous report, moved aside while the new one is
    renamed into place, which also carries recipsim's marker). Such a directory is
    removed only when its process is gone; anything else (a user's
    ``.<name>.old-mybackup``, a link) is never touched.
    """
    tmp_name = re.compile(re.escape(_temporary_prefix(target)) + r"(\d+)-\d+")
    old_name = re.compile(re.escape(f".{target.name}.old-") + r"(\d+)-\d+")
    try:
        entries = list(target.parent.iterdir())
    except OSError:
        return
    for entry in entries:
        tmp, old = tmp_name.fullmatch(entry.name), old_name.fullmatch(entry.name)
        match = tmp or old
        if match is None or entry.is_symlink() or not entry.is_dir():
            continue
        if pid_alive(int(match.group(1))):
            continue
        if old is not None and not (entry / MARKER).is_file():
            continue
        shutil.rmtree(entry, ignore_errors=True)


@contextmanager
def atomic_directory(target: Path) -> Iterator[Path]:
    """Build a directory beside ``target``; it replaces ``target`` when the block ends.

    ``target`` must be replaceable (:func:`check_replaceable`); the new directory gets
    :data:`MARKER`. If the block raises, ``target`` is untouched and the temporary
    directory removed; one left by a killed process is removed by the next call.
    """
    target = normalised(target)
    check_replaceable(target)
    target.parent.mkdir(parents=True, exist_ok=True)
    clean_stale_temporaries(target)
    tmp = _create_directory(str(target.parent / f"{_temporary_prefix(target)}{os.getpid()}-"))
    try:
        yield tmp
        (tmp / MARKER).write_text("written by recipsim; recipsim may replace this directory\n")
        check_replaceable(target)  # it may have appeared while we were writing
        swap_in(tmp, target)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise


def mark_output(directory: Path) -> None:
    """Create ``directory`` (if needed) and mark it as a recipsim output directory."""
    directory = normalised(directory)
    check_replaceable(directory)
    directory.mkdir(parents=True, exist_ok=True)
    marker = directory / MARKER
    if not marker.is_file():
        marker.write_text("written by recipsim; recipsim may replace this directory\n")


def _create_directory(prefix: str) -> Path:
    """Create a new directory ``<prefix><n>`` exclusively, with the permissions the
    user's umask gives (``n`` from this process's counter: :func:`create_new_file`)."""
    while True:
        path = f"{prefix}{next(_TEMPORARY_NUMBERS)}"
        try:
            os.mkdir(path, 0o777)
        except FileExistsError:
            continue
        return Path(path)


def _create_temporary(path: Path) -> tuple[int, Path]:
    """Create a temporary file beside ``path``, exclusively, creating the directory if it
    is missing; returns its open descriptor and its path (:func:`_create_temporary_at`)."""
    fd, tmp = _create_temporary_at(os.fspath(path))
    return fd, Path(tmp)


#: A temporary file name of :func:`_create_temporary_at` (its process id in group 1).
_TEMPORARY_FILE = re.compile(r"\.[^/]*\.(\d+)-\d+[^/]*\.tmp")


def clean_stale_temporary_files(folder: Path) -> None:
    """Remove from ``folder`` the temporary files (:func:`_create_temporary_at`) that
    processes of this host left when they were killed: only names recipsim makes, only
    regular files (never a link), only where that process is gone."""
    for tmp in folder.glob(".*.tmp"):
        match = _TEMPORARY_FILE.fullmatch(tmp.name)
        if match and tmp.is_file() and not tmp.is_symlink() and not pid_alive(int(match[1])):
            tmp.unlink(missing_ok=True)


def _create_temporary_at(target: str) -> tuple[int, str]:
    """:func:`_create_temporary` on a path as a string.

    Its name ``.<stem>.<pid>-<n><suffix>.tmp`` is unique to this process
    (:func:`create_new_file`).
    """
    head, name = os.path.split(target)
    stem, suffix = os.path.splitext(name)
    prefix = os.path.join(head, f".{stem}.{os.getpid()}-")
    return create_new_file(lambda number: f"{prefix}{number}{suffix}.tmp")


def create_new_file(name: Callable[[int], str], flags: int = 0) -> tuple[int, str]:
    """Create ``name(n)`` exclusively, with the permissions the user's umask gives, and
    open it for writing (with the extra ``flags``, e.g. :data:`os.O_APPEND`); its
    descriptor and path.

    ``n`` comes from this process's counter: a name that exists (a file left by a killed
    process of the same id) makes it take the next number; a missing directory is
    created.
    """
    flags |= os.O_WRONLY | os.O_CREAT | os.O_EXCL
    while True:
        path = name(next(_TEMPORARY_NUMBERS))
        try:
            return os.open(path, flags, 0o666), path
        except FileNotFoundError:
            os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
        except FileExistsError:
            continue


def write_all(fd: int, data: bytes) -> None:
    """Write all of ``data`` to the descriptor ``fd`` (a write may take only part)."""
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view) :]


@contextmanager
def _temporary_beside(path: Path) -> Iterator[Path]:
    """A temporary file name beside ``path``, renamed to ``path`` when the block ends.

    If the block raises, the temporary file is removed and ``path`` is untouched.
    """
    fd, tmp = _create_temporary(path)
    os.close(fd)
    try:
        yield tmp
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def write_bytes_atomically(path: str | Path, data: bytes) -> None:
    """Write ``data`` to ``path`` as :func:`atomic_file` does (a temporary file beside
    it, renamed over it), through the temporary file's descriptor: one write, no file
    object."""
    target = os.fspath(path)
    fd, tmp = _create_temporary_at(target)
    try:
        try:
            write_all(fd, data)
        finally:
            os.close(fd)
        os.replace(tmp, target)
    except BaseException:
        with suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


@contextmanager
def atomic_file(path: Path, mode: str = "w") -> Iterator[IO[Any]]:
    """Open a temporary file beside ``path``; it becomes ``path`` when the block ends."""
    with _temporary_beside(Path(path)) as tmp, open(tmp, mode) as handle:
        yield handle


def atomic_write(path: Path, write: Callable[[Path], None]) -> None:
    """Call ``write(tmp_path)`` then rename ``tmp_path`` to ``path`` (for writers taking a path)."""
    with _temporary_beside(Path(path)) as tmp:
        write(tmp)


def swap_in(new: Path, target: Path) -> None:
    """Replace directory ``target`` by ``new`` with renames (the old one is removed after).

    A reader sees either the old or the new directory, never a half-written one. Callers
    check first that ``target`` may be replaced (:func:`atomic_directory` does).
    """
    old = None
    if target.exists():
        old = target.with_name(f".{target.name}.old-{os.getpid()}-{time.time_ns()}")
        os.replace(target, old)
    os.replace(new, target)
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)
