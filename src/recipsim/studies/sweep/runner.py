"""Run sweep points: in the calling process or in a local process pool (on Dask:
:mod:`recipsim.studies.sweep.dask_runner`).

Every runner calls ``on_result(task, result)`` in the calling process, once per
point, as soon as that point is finished, so that the caller can write it to disk
before the next one arrives. None of them distributes work by itself beyond the
standard library's :class:`concurrent.futures.ProcessPoolExecutor` or an existing
Dask cluster.

Ctrl-C (:class:`KeyboardInterrupt`): no new point is started, pending points are
cancelled, the points already running in local workers are collected (a second
Ctrl-C abandons them) and the interrupt is raised again for the caller. The workers
ignore Ctrl-C themselves. In the calling process (``--jobs 1``) Ctrl-C stops after
the current point (a second one exits at once), because an interrupt raised inside
the solver's CoolProp callback would be swallowed by ctypes with an undefined result.
A local worker that dies (killed, crashed) stops the sweep with :class:`WorkerLost`;
the finished points are on disk and a rerun resumes.
"""

from __future__ import annotations

import multiprocessing
import os
import signal
import sys
import threading
import time
from collections.abc import Callable, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from typing import Any

from recipsim.errors import RecipsimError
from recipsim.studies.sweep.worker import (
    PointTask,
    init_worker,
    run_point,
    run_points,
)

ResultCallback = Callable[[PointTask, dict[str, Any]], None]
#: solves one point where it runs (picklable): run_point, or SolveAndSave
Solve = Callable[[PointTask], dict[str, Any]]
StartCallback = Callable[[], None]


class WorkerLost(RecipsimError):
    """A worker process died, or the Dask cluster went away, during a sweep."""


def nothing() -> None:
    """The default ``on_start``: no progress bar to open."""
    return None


class _DeferredInterrupt:
    """Turn Ctrl-C into a request to stop between two points (main thread only).

    The solver calls CoolProp through a ctypes callback; a :class:`KeyboardInterrupt`
    raised inside it is swallowed by ctypes and the callback's result is then
    undefined, which could corrupt the point being solved. So in ``--jobs 1`` the
    first Ctrl-C only asks to stop after the current point; a second one ends the
    process at once (every file on disk is whole, written atomically, and a point record
    cut short is detected and not trusted: :mod:`recipsim.studies.sweep.record_segments`).
    """

    def __init__(self) -> None:
        self.requested = False
        self._previous: Any = None
        self._installed = False

    def _handle(self, signum: int, frame: Any) -> None:
        if self.requested:
            print("recipsim: interrupted again; stopping now", file=sys.stderr, flush=True)
            os._exit(130)
        self.requested = True
        print(
            "recipsim: interrupted; finishing the current point (Ctrl-C again to stop at once)",
            file=sys.stderr,
            flush=True,
        )

    def __enter__(self) -> _DeferredInterrupt:
        if threading.current_thread() is threading.main_thread():
            self._previous = signal.signal(signal.SIGINT, self._handle)
            self._installed = True
        return self

    def __exit__(self, *exc: object) -> None:
        if self._installed:
            signal.signal(signal.SIGINT, self._previous)


def run_inline(
    tasks: Sequence[PointTask],
    on_result: ResultCallback,
    on_start: StartCallback = nothing,
    solve: Solve = run_point,
) -> None:
    """Run the points one after the other in this process (``--jobs 1``) with ``solve``
    (default :func:`~recipsim.studies.sweep.worker.run_point`)."""
    on_start()
    with _DeferredInterrupt() as interrupt:
        for task in tasks:
            result = solve(task)
            on_result(task, result)
            if interrupt.requested:
                raise KeyboardInterrupt


def _context() -> Any:
    # fork after the parent imported CoolProp and the solver: a worker starts with them
    # instead of importing them again. Elsewhere the platform's default (spawn).
    if sys.platform == "linux":
        return multiprocessing.get_context("fork")
    return multiprocessing.get_context()


#: Wall time a batch of points sent to a worker should take [s]: long enough that the
#: cost of a round trip (pickling, a pipe, waking the parent) is a small part of it,
#: short enough that Ctrl-C and the progress bar stay responsive.
CHUNK_SECONDS = 0.25


def chunk_size(point_seconds: float, remaining: int, jobs: int) -> int:
    """Points per batch: about :data:`CHUNK_SECONDS` of work, and at least four batches
    per worker so that the last ones finish together.

    Parameters
    ----------
    point_seconds : float
        Measured wall time of one point [s].
    remaining : int
        Points left to send.
    jobs : int
        Worker processes.

    Returns
    -------
    int
        At least 1.
    """
    by_time = int(CHUNK_SECONDS / point_seconds) if point_seconds > 0.0 else remaining
    return max(1, min(by_time, remaining // (4 * jobs)))


def run_pool(
    tasks: Sequence[PointTask],
    jobs: int,
    on_result: ResultCallback,
    on_start: StartCallback = nothing,
    solve: Solve = run_point,
) -> None:
    """Run the points on ``jobs`` persistent local worker processes, each point with
    ``solve`` (default :func:`~recipsim.studies.sweep.worker.run_point`; a
    :class:`~recipsim.studies.sweep.store.SolveAndSave` writes each record where it was
    solved).

    Where workers are forked (Linux) the first point is solved here first: the solver's
    compiled code, the base case and its property table are then loaded once, in this
    process, and every worker starts with them (elsewhere each worker loads them at its
    first point). Its time sizes the batches of points sent to the workers
    (:func:`chunk_size`). At most two batches per worker are queued at a time, so that
    an interrupt has little to cancel.
    """
    queue = list(reversed(tasks))
    point_seconds = 0.0
    context = _context()
    started = False
    if context.get_start_method() == "fork" and len(queue) > jobs:
        started = True
        on_start()
        started_at = time.perf_counter()
        run_inline([queue.pop()], on_result, solve=solve)
        point_seconds = time.perf_counter() - started_at
    window = 2 * jobs
    running: dict[Future[list[dict[str, Any]]], list[PointTask]] = {}
    executor = ProcessPoolExecutor(max_workers=jobs, mp_context=context, initializer=init_worker)
    try:
        try:
            while queue or running:
                while queue and len(running) < window:
                    size = chunk_size(point_seconds, len(queue), jobs) if point_seconds else 1
                    batch = [queue.pop() for _ in range(min(size, len(queue)))]
                    running[executor.submit(run_points, batch, solve)] = batch
                if not started:  # the workers exist once the first point was submitted
                    started = True
                    on_start()
                done, _ = wait(list(running), return_when=FIRST_COMPLETED)
                for future in done:
                    batch = running.pop(future)
                    for task, result in zip(batch, future.result(), strict=True):
                        on_result(task, result)
        except KeyboardInterrupt:
            _drain(running, on_result)
            raise
        except BrokenProcessPool:
            raise WorkerLost(
                "a worker process died (killed or crashed) while computing a point"
            ) from None
    finally:
        executor.shutdown(wait=False, cancel_futures=True)


def _drain(
    running: dict[Future[list[dict[str, Any]]], list[PointTask]], on_result: ResultCallback
) -> None:
    """After Ctrl-C: cancel what has not started, collect what is running."""
    for future in list(running):
        if future.cancel():
            del running[future]
    if not running:
        return
    count = sum(len(batch) for batch in running.values())
    print(
        f"recipsim: interrupted; finishing {count} point(s) in progress "
        "(Ctrl-C again to abandon them)",
        file=sys.stderr,
    )
    try:
        for future in list(running):
            try:
                results = future.result()
            except (BrokenProcessPool, Exception):
                continue
            for task, result in zip(running.pop(future), results, strict=True):
                on_result(task, result)
    except KeyboardInterrupt:
        pass
