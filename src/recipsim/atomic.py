"""Atomic replacement of an output directory (reports, studies)."""

from __future__ import annotations

import os
import shutil
import time
from pathlib import Path


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
