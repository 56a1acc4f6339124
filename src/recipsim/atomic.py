"""Atomic writes: a file or an output directory appears whole or not at all."""

from __future__ import annotations

import os
import shutil
import tempfile
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import IO, Any


@contextmanager
def _temporary_beside(path: Path) -> Iterator[Path]:
    """A temporary file name beside ``path``, renamed to ``path`` when the block ends.

    If the block raises, the temporary file is removed and ``path`` is untouched.
    """
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(
        prefix=f".{path.stem}.", suffix=f"{path.suffix}.tmp", dir=path.parent
    )
    os.close(fd)
    try:
        yield Path(tmp)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
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

    A reader sees either the old or the new directory, never a half-written one.
    """
    old = None
    if target.exists():
        old = target.with_name(f".{target.name}.old-{os.getpid()}-{time.time_ns()}")
        os.replace(target, old)
    os.replace(new, target)
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)
