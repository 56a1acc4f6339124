"""Wall-clock marks of a command's phases, for ``recipsim bench-system``.

Off, and free, unless ``RECIPSIM_TIMELINE`` names a file: then :func:`mark` notes the
time of day [s] and the process's CPU time [s] at named points of ``recipsim run``
(imports done, numba started, case loaded, solved, report handed to the report
processes, written, renamed; in each report process: imports done, job received, job
done), and :func:`flush` appends them to the file as one JSON line per process
(``{"pid", "role", "marks": [[name, time, cpu], ...]}``). Times of day, so the marks
of the parent and of its forked children, and the moment the measuring process
started the command, share one clock.
"""

from __future__ import annotations

import json
import os
import time

_ENV = "RECIPSIM_TIMELINE"
_marks: list[tuple[str, float, float]] = []


def mark(name: str) -> None:
    """Note that ``name`` is reached (only when ``RECIPSIM_TIMELINE`` is set)."""
    if os.environ.get(_ENV):
        _marks.append((name, time.time(), time.process_time()))


def reset() -> None:
    """Forget the marks (a forked child: its parent's are the parent's to write)."""
    _marks.clear()


def flush(role: str) -> None:
    """Append this process's marks to the ``RECIPSIM_TIMELINE`` file, as ``role``."""
    path = os.environ.get(_ENV)
    if not path or not _marks:
        return
    line = json.dumps({"pid": os.getpid(), "role": role, "marks": _marks}) + "\n"
    _marks.clear()
    fd = os.open(path, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o600)
    try:
        os.write(fd, line.encode())  # one write: lines of several processes do not mix
    finally:
        os.close(fd)
