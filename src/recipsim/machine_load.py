"""How many cores other work leaves idle now: the command line starts its helper
processes (report figures, the compile-ahead child) only onto those.

On Linux it counts the runnable tasks of ``/proc/loadavg`` (its fourth field,
``running/total``, this process included), read three times 1 ms apart, the largest
kept: what competes for the cores at this moment. The one-minute load average, the
fallback elsewhere, lags by a minute: right after a command it still counts that
command's own processes, so a `recipsim run` started just after another saw one idle
core of two where both were idle.
"""

from __future__ import annotations

import math
import os
import time

#: the kernel's load file (its fourth field: runnable tasks / all tasks)
LOADAVG = "/proc/loadavg"


def usable_cores() -> int:
    """Cores this process may run on."""
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


def _runnable_now(path: str) -> int:
    """Runnable tasks in the load file ``path``, the largest of three reads 1 ms apart."""
    running = 0
    for read in range(3):
        if read:
            time.sleep(0.001)
        with open(path, encoding="ascii") as handle:
            field = handle.read().split()[3]
        running = max(running, int(field.split("/", 1)[0]))
    return running


def busy_cores() -> float:
    """Cores other work keeps busy now: the runnable tasks besides this process, or the
    one-minute load average where the kernel does not say (NaN where neither is known)."""
    try:
        return float(max(_runnable_now(LOADAVG) - 1, 0))
    except (OSError, ValueError, IndexError):
        pass
    try:
        return os.getloadavg()[0]
    except (AttributeError, OSError):
        return math.nan


def idle_cores(most: int, unknown: int | None = None) -> int:
    """Usable cores less :func:`busy_cores`, rounded to the nearest whole core, between 0
    and ``most``; ``unknown`` (default ``most``) where the load is not known."""
    busy = busy_cores()
    if math.isnan(busy):
        return most if unknown is None else unknown
    return max(0, min(most, int(usable_cores() - busy + 0.5)))
