"""How many cores other work leaves idle now: the command line starts its helper
processes (report figures, the compile-ahead child) only onto those.

On Linux it counts the runnable tasks of ``/proc/loadavg`` (its fourth field,
``running/total``) less this process's own runnable threads, read three times 1 ms
apart, the largest kept: what competes for the cores at this moment. The one-minute
load average, the fallback elsewhere, lags by a minute: right after a command it still
counts that command's own processes, so a `recipsim run` started just after another saw
one idle core of two where both were idle.
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


def _own_running_tasks() -> int:
    """This process's threads that are runnable now (numpy's BLAS threads spin for a
    few ms after numpy is imported); 1 where ``/proc/self/task`` is not readable."""
    try:
        tasks = os.listdir("/proc/self/task")
    except OSError:
        return 1
    running = 0
    for task in tasks:
        try:
            with open(f"/proc/self/task/{task}/stat", encoding="ascii") as handle:
                # the state follows the command name, which is in parentheses
                running += handle.read().rsplit(")", 1)[1].split()[0] == "R"
        except (OSError, IndexError):
            continue
    return max(running, 1)


def _runnable_elsewhere(path: str) -> int:
    """Runnable tasks in the load file ``path`` besides this process's own, the largest
    of three reads 1 ms apart."""
    elsewhere = 0
    for read in range(3):
        if read:
            time.sleep(0.001)
        with open(path, encoding="ascii") as handle:
            field = handle.read().split()[3]
        elsewhere = max(elsewhere, int(field.split("/", 1)[0]) - _own_running_tasks())
    return elsewhere


def busy_cores() -> float:
    """Cores other work keeps busy now: the runnable tasks besides this process, or the
    one-minute load average where the kernel does not say (NaN where neither is known)."""
    try:
        return float(max(_runnable_elsewhere(LOADAVG), 0))
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
