"""Pipe input and output and process states of the forked report processes
(:mod:`recipsim.report.figure_process`)."""

from __future__ import annotations

import os


def read_exactly(fd: int, size: int) -> bytes:
    """``size`` bytes read from ``fd``, fewer at end-of-file."""
    chunks, left = [], size
    while left and (chunk := os.read(fd, min(left, 1 << 20))):
        chunks.append(chunk)
        left -= len(chunk)
    return b"".join(chunks)


def read_all(fd: int) -> bytes:
    """Everything read from ``fd`` up to end-of-file."""
    chunks = []
    while chunk := os.read(fd, 1 << 20):
        chunks.append(chunk)
    return b"".join(chunks)


def runnable(pid: int) -> bool:
    """Whether process ``pid`` is runnable now (Linux's ``/proc``; False elsewhere)."""
    try:
        with open(f"/proc/{pid}/stat", encoding="ascii") as handle:
            return handle.read().rsplit(")", 1)[1].split()[0] == "R"
    except (OSError, IndexError):
        return False
