"""Report figures drawn in forked helper processes, concurrently with the solve.

A ``recipsim run`` spends about as long drawing its figures (0.6 s of CPU for the
default case, plus 0.2-0.3 s to import matplotlib) as on everything else. The command
line therefore forks :class:`FigureProcesses` before it loads anything heavy: each child
imports matplotlib and the plotting modules while the parent imports numba, loads the
case and solves, then waits for a job on a pipe. The parent sends the cycle table and
the names of the figures each child draws (split by their measured cost,
:data:`FIGURE_COST`), writes its tables meanwhile, and waits for the children before its
report directory is renamed into place, so the report stays atomic.

Only the command line forks (a library never starts processes behind its caller's
back), only where ``os.fork`` exists, before any thread or numba's compiler has
started, and only onto cores that other work leaves idle
(:func:`recipsim.machine_load.idle_cores`). A child
that fails sends its exception back; the parent raises it. A child whose parent dies
reads end-of-file and exits. The figures are the same files as
those drawn in-process (:func:`recipsim.report.report_figures.draw_report_figures`).
"""

from __future__ import annotations

import os
import pickle
import sys
from collections.abc import Collection, Mapping
from pathlib import Path
from typing import Any

from recipsim.machine_load import idle_cores

#: Measured CPU cost of each figure of the default case [s] (warm, 2-core machine; each
#: drawn alone in a process that had drawn none, median of 6), used only to share the
#: figures evenly between the children. A one-panel figure drawn after another in the
#: same child costs less (it reuses its Axes, :func:`recipsim.report.plotting.save_cycle_figures`).
FIGURE_COST = {
    "p_V": 0.070,
    "p_V_loglog": 0.061,
    "p_theta": 0.069,
    "torque": 0.072,
    "valves": 0.094,
    "bearing_loads": 0.20,
    "orbits": 0.25,
    "loss_breakdown": 0.083,
}


def _read_exactly(fd: int, size: int) -> bytes:
    chunks, left = [], size
    while left and (chunk := os.read(fd, min(left, 1 << 20))):
        chunks.append(chunk)
        left -= len(chunk)
    return b"".join(chunks)


def _read_all(fd: int) -> bytes:
    chunks = []
    while chunk := os.read(fd, 1 << 20):
        chunks.append(chunk)
    return b"".join(chunks)


def _write_all(fd: int, data: bytes) -> None:
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view) :]


def _child(jobs: int, results: int, preload: tuple[str, ...]) -> None:
    """Body of a forked child: import ``preload``, run one job, report.

    A job is a length-prefixed pickle of ``(module, function, kwargs)``; length 0 (or
    end-of-file: the parent is gone) means none. Length-prefixed rather than read to
    end-of-file, because processes the parent forks later (sweep workers) inherit the
    pipe's write end.
    """
    import importlib
    import signal

    from recipsim import timeline

    timeline.reset()

    # Ctrl-C reaches the whole process group: the parent handles it and tells the
    # children to stop (no job), so that its own exit status is the one reported
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    reply: Any = b""
    try:
        for module in preload:
            importlib.import_module(module)
        timeline.mark("imports")
        size = int.from_bytes(_read_exactly(jobs, 8) or bytes(8), "little")
        if size:
            module, function, kwargs = pickle.loads(_read_exactly(jobs, size))
            timeline.mark("job received")
            value = getattr(importlib.import_module(module), function)(**kwargs)
            timeline.mark("job done")
            reply = pickle.dumps((True, value))
    except BaseException as exc:  # noqa: BLE001 - everything goes back to the parent
        try:
            reply = pickle.dumps((False, exc))
        except Exception:  # noqa: BLE001 - an exception that cannot be pickled
            reply = pickle.dumps((False, RuntimeError(f"figure process: {exc!r}")))
    timeline.flush("report process")
    _write_all(results, reply)


#: What the children of a case report import before their job arrives: pandas first
#: (``recipsim run`` leaves the tables to them and never imports it itself).
REPORT_PRELOAD = (
    "pandas",
    "recipsim.report.loss_plot",
    "recipsim.report.plotting",
    "recipsim.report.report_figures",
)

#: The same without figures (``--no-plots``): the tables only.
TABLES_PRELOAD = ("pandas", "recipsim.report.report_figures")


class FigureProcesses:
    """Forked children that draw a report's figures (see the module docstring).

    Parameters
    ----------
    count : int
        Children to fork (at least 1).
    preload : tuple of str
        Modules each child imports while it waits for its job.
    """

    def __init__(self, count: int, preload: tuple[str, ...] = REPORT_PRELOAD) -> None:
        self._children: list[tuple[int, int, int]] = []  # pid, job fd, result fd
        self._jobs_open = True
        for _ in range(count):
            job_read, job_write = os.pipe()
            result_read, result_write = os.pipe()
            sys.stdout.flush()
            sys.stderr.flush()
            pid = os.fork()
            if pid == 0:  # child
                status = 0
                try:
                    os.close(job_write)
                    os.close(result_read)
                    for _pid, job, result in self._children:
                        os.close(job)
                        os.close(result)
                    _child(job_read, result_write, preload)
                except BaseException:  # noqa: BLE001 - never return into the parent's code
                    status = 1
                finally:
                    os._exit(status)
            os.close(job_read)
            os.close(result_write)
            self._children.append((pid, job_write, result_read))

    @property
    def pids(self) -> list[int]:
        """Process ids of the children."""
        return [pid for pid, _job, _result in self._children]

    def draw(
        self,
        directory: Path,
        cycle: Any,
        summary_row: Mapping[str, Any],
        plenum: tuple[float, float] | None,
        names: Collection[str],
        tables: bool = False,
    ) -> None:
        """Send the figures ``names`` of one case report to the children, shared by cost,
        and with ``tables`` its ``summary.csv`` and ``cycle.csv`` to the least loaded one
        (:func:`recipsim.report.report_figures.write_report_share`). ``cycle``: the cycle
        table or its columns (numpy arrays, cheaper to send; the child builds the table).

        Returns at once; :meth:`wait` waits for the files. Call it (or :meth:`submit`)
        once.
        """
        shares = share_by_cost(names, len(self.pids), FIGURE_COST)
        if tables and len(shares) < len(self.pids):
            shares.append([])  # a child without figures writes the tables
        loads = [sum(FIGURE_COST.get(name, 0.1) for name in share) for share in shares]
        lightest = loads.index(min(loads)) if tables else -1
        jobs = [
            {
                "directory": Path(directory),
                "cycle": cycle,
                "summary_row": dict(summary_row),
                "plenum": plenum,
                "names": tuple(share),
                "tables": index == lightest,
            }
            for index, share in enumerate(shares)
        ]
        self.submit("recipsim.report.report_figures", "write_report_share", jobs)

    def submit(self, module: str, function: str, jobs: list[dict[str, Any]]) -> None:
        """Run ``module.function(**kwargs)`` for each ``kwargs`` of ``jobs``, one per child
        (at most as many jobs as children); the other children get none.

        Returns at once; :meth:`wait` waits for them.
        """
        if not self._jobs_open:
            raise RuntimeError("the figure processes had their jobs already")
        if len(jobs) > len(self._children):
            raise ValueError(f"{len(jobs)} jobs for {len(self._children)} figure processes")
        for index, (_pid, job, _result) in enumerate(self._children):
            data = b""
            if index < len(jobs):
                data = pickle.dumps((module, function, jobs[index]), pickle.HIGHEST_PROTOCOL)
            _write_all(job, len(data).to_bytes(8, "little") + data)
            os.close(job)
        self._jobs_open = False

    def close(self) -> None:
        """Tell the children that no (more) job comes: they finish and exit."""
        if self._jobs_open:
            self._jobs_open = False
            for _pid, job, _result in self._children:
                try:
                    _write_all(job, bytes(8))  # no job
                except OSError:
                    pass  # the child is gone: wait() reports it
                os.close(job)

    def wait(self) -> list[Any]:
        """Wait for every child; re-raise the first failure of a child.

        Returns
        -------
        list
            What each job's function returned, in the order of the jobs.

        Raises
        ------
        Exception
            What a child raised; RuntimeError when a child died.
        """
        self.close()
        failure: BaseException | None = None
        values = []
        for pid, _job, result in self._children:
            reply = _read_all(result)
            os.close(result)
            _, status = os.waitpid(pid, 0)
            if reply:
                ok, value = pickle.loads(reply)
                if ok:
                    values.append(value)
                elif failure is None:
                    failure = value
            elif failure is None and status != 0:
                failure = RuntimeError(f"figure process {pid} ended with status {status}")
        self._children = []
        if failure is not None:
            raise failure
        return values


def share_by_cost(names: Collection[str], parts: int, cost: Mapping[str, float]) -> list[list[str]]:
    """``names`` shared into at most ``parts`` non-empty lists of about equal total
    ``cost`` (largest first, each to the lightest list; unknown names cost 0.1)."""
    shares: list[list[str]] = [[] for _ in range(parts)]
    loads = [0.0] * parts
    for name in sorted(names, key=lambda n: -cost.get(n, 0.1)):
        lightest = loads.index(min(loads))
        shares[lightest].append(name)
        loads[lightest] += cost.get(name, 0.1)
    return [share for share in shares if share]


def start_figure_processes(
    count: int | None = None,
    preload: tuple[str, ...] = REPORT_PRELOAD,
    share_pandas: bool = True,
    at_least: int = 0,
    busy_parent: bool = False,
) -> FigureProcesses | None:
    """Fork the figure children of one report, or None where forking is not available.

    Parameters
    ----------
    count : int, optional
        Children; default ``RECIPSIM_FIGURE_PROCESSES`` when set, else the cores other
        work leaves idle now (:func:`recipsim.machine_load.idle_cores`), at most 2
        (more do not pay for their start-up on a report's 7 figures), and at least
        ``at_least``.
    preload : tuple of str
        Modules the children import while they wait (default: the case report's).
    share_pandas : bool
        Import pandas here before forking, so that the children have it (a parent that
        needs pandas anyway: the sweep). ``recipsim run`` does not: its parent never
        imports pandas or matplotlib, so one child costs no import twice and pays on a
        busy machine too, which is why it asks for ``at_least=1``.
    at_least : int
        Fewest children where ``count`` is not given.
    busy_parent : bool
        The parent keeps a core busy while the children start (``recipsim run``
        solves): they count only the idle cores besides one. On the 2-core machine a
        warm run with one report process took 1.32-1.66 s (median 1.40 s, 5 runs)
        against 1.43-1.66 s (1.51 s) with two, which took their cores from the solve.

    Returns
    -------
    FigureProcesses or None
        None without ``os.fork`` (Windows) or with a count of 0; the caller then draws
        in-process.
    """
    setting = os.environ.get("RECIPSIM_FIGURE_PROCESSES", "").strip()
    if count is None and setting.isdigit():
        count = int(setting)
    if not hasattr(os, "fork") or count == 0:
        return None
    if count is None:
        spare = 1 if busy_parent else 0
        count = max(idle_cores(2 + spare) - spare, at_least)
        if count == 0:
            return None
    if share_pandas:
        # pandas, which the parent needs anyway, is imported once before forking: the
        # children import only matplotlib (0.25 s each instead of 0.5 s)
        import pandas  # noqa: F401

    return FigureProcesses(count, preload)
