"""Report figures drawn in forked helper processes, concurrently with the solve.

A ``recipsim run`` spends about as long drawing its figures (0.6 s of CPU for the
default case, plus 0.2-0.3 s to import matplotlib) as on everything else. The command
line therefore forks :class:`FigureProcesses` before it loads anything heavy: each child
imports matplotlib and the plotting modules while the parent imports numba, loads the
case and solves, then waits for a job on a pipe (not pandas: the tables are written by
:mod:`.csv_tables` and the figures drawn from the columns, 0.3 s of CPU less beside the
solve). At the hand-over the parent
only waits from then on, so the figures and the tables are shared, by their measured
cost (:mod:`.figure_costs`), between as many processes as there are idle cores then
(:meth:`FigureProcesses.drawing_processes`): a child given several shares forks itself
for all but one (the forks inherit its imports, and close the pipes that are not
theirs). The parent writes the rest of the report meanwhile and waits for
every process before its report directory is renamed into place, so the report stays
atomic. On the 2-core machine, one report process (a second's imports would take the
solve's core) that forks a second at the hand-over writes the default case's report in
0.38-0.61 s (median 0.50 s) instead of 0.67-0.95 s (0.80 s) alone, and the warm
``recipsim run`` takes 1.64 s instead of 1.92 s (medians of 11, interleaved; see
docs/speed.md, "Time to answer").

Only the command line forks (a library never starts processes behind its caller's
back), only where ``os.fork`` exists, before any thread or numba's compiler has
started, and only onto cores that other work leaves idle
(:func:`recipsim.machine_load.idle_cores`). A child or fork that fails sends its
exception back; the parent raises the first. A child whose parent dies reads
end-of-file and exits. The figures are the same files as those drawn in-process
(:func:`recipsim.report.report_figures.draw_report_figures`).
"""

from __future__ import annotations

import contextlib
import math
import os
import pickle
import sys
from collections.abc import Callable, Collection, Mapping
from pathlib import Path
from typing import Any

from recipsim import start_up_collector
from recipsim.atomic import write_all
from recipsim.machine_load import busy_cores, idle_cores, usable_cores
from recipsim.report.figure_costs import FIGURE_COST, TABLES, TABLES_COST, share_by_cost
from recipsim.report.process_pipes import read_all, read_exactly, runnable


def _child(jobs: int, results: int, preload: tuple[str, ...], role: str) -> None:
    """Body of a forked child: import ``preload``, run one job, report.

    A job is a length-prefixed pickle of ``(module, function, calls)``, ``calls`` a list
    of keyword arguments: the child forks one process for each call but its first at
    once (:func:`_run_calls`). Length 0 (or end-of-file: the parent is gone) means
    none. Length-prefixed rather than read to end-of-file, because processes the parent
    forks later (sweep workers) inherit the pipe's write end.
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
        start_up_collector.resume()  # forked while the command line's start-up paused it
        timeline.mark("imports")
        size = int.from_bytes(read_exactly(jobs, 8) or bytes(8), "little")
        if size:
            module, function, calls = pickle.loads(read_exactly(jobs, size))
            timeline.mark("job received")
            values = _run_calls(module, function, calls, (jobs, results))
            timeline.mark("job done")
            reply = pickle.dumps((True, values))
    except BaseException as exc:  # noqa: BLE001 - everything goes back to the parent
        try:
            reply = pickle.dumps((False, exc))
        except Exception:  # noqa: BLE001 - an exception that cannot be pickled
            reply = pickle.dumps((False, RuntimeError(f"figure process: {exc!r}")))
    timeline.flush(role)
    write_all(results, reply)


def _run_calls(
    module: str, function: str, calls: list[dict[str, Any]], own: tuple[int, ...]
) -> list[Any]:
    """``module.function(**kwargs)`` for each of ``calls``: the first here, the others
    in processes forked now (they inherit what this one imported, and close
    its pipes ``own``). Returns the values in the order of ``calls``; raises the first
    failure, after every fork has ended (they write into the same report)."""
    import importlib

    target = getattr(importlib.import_module(module), function)
    forks = None
    if len(calls) > 1:
        forks = FigureProcesses(len(calls) - 1, preload=(), inherited=own, role="report fork")
        forks.submit(module, function, calls[1:])
    try:
        first = target(**calls[0])
    except BaseException:
        if forks is not None:
            with contextlib.suppress(BaseException):
                forks.wait()
        raise
    return [first, *(forks.wait() if forks is not None else ())]


#: What the children of a case report import before their job arrives (not pandas:
#: neither they nor ``recipsim run``'s parent need it, :mod:`.csv_tables`).
REPORT_PRELOAD = (
    "recipsim.report.loss_plot",
    "recipsim.report.plotting",
    "recipsim.report.report_figures",
)

#: The same without figures (``--no-plots``): the tables only.
TABLES_PRELOAD = ("recipsim.report.report_figures",)


#: Most processes that draw one report's figures after a fan-out: the costliest figure
#: (bearing loads, 0.2 s of the 0.65 s of the default case's seven) bounds the time.
FAN_OUT_MOST = 4


class FigureProcesses:
    """Forked children that draw a report's figures (see the module docstring).

    Parameters
    ----------
    count : int
        Children to fork (0 or more).
    preload : tuple of str
        Modules each child imports while it waits for its job.
    fan_out : bool
        :meth:`draw` shares the figures between as many processes as there are idle
        cores at the hand-over (at most :data:`FAN_OUT_MOST`): the children fork the
        others then. False: between the children.
    inherited : tuple of int
        File descriptors of the forking process that the children close (a child
        forking: its own pipes to its parent).
    role : str
        The children's name in the timeline (:mod:`recipsim.timeline`).
    """

    def __init__(
        self,
        count: int,
        preload: tuple[str, ...] = REPORT_PRELOAD,
        fan_out: bool = False,
        inherited: tuple[int, ...] = (),
        role: str = "report process",
    ) -> None:
        self._children: list[tuple[int, int, int]] = []  # pid, job fd, result fd
        self._jobs_open = True
        self._fan_out = fan_out
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
                    for fd in inherited:
                        os.close(fd)
                    for _pid, job, result in self._children:
                        os.close(job)
                        os.close(result)
                    _child(job_read, result_write, preload, role)
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

    def drawing_processes(self, most: int = FAN_OUT_MOST) -> int:
        """How many processes :meth:`draw` shares the figures between: the children,
        or with ``fan_out`` the cores that other work leaves idle now, this process's
        and its children's included (this one only waits from now on), at most
        ``most`` (default :data:`FAN_OUT_MOST`)."""
        children = len(self._children)
        if not self._fan_out or not children:
            return children
        busy = busy_cores()
        if math.isnan(busy):
            return children
        busy -= sum(runnable(pid) for pid in self.pids)  # children still importing
        return max(children, min(most, int(usable_cores() - busy + 0.5)))

    def draw(
        self,
        directory: Path,
        cycle: Any,
        summary_row: Mapping[str, Any],
        plenum: tuple[float, float] | None,
        names: Collection[str],
        tables: bool = False,
    ) -> None:
        """Send the figures ``names`` of one case report, and with ``tables`` its
        ``summary.csv`` and ``cycle.csv``, to the children, shared by cost between
        :meth:`drawing_processes` (:func:`recipsim.report.report_figures.write_report_share`).
        ``cycle``: the cycle table or its columns (numpy arrays, cheaper to send; the
        child builds the table).

        Returns at once; :meth:`wait` waits for the files. Call it (or :meth:`submit`)
        once.
        """
        cost = {name: FIGURE_COST.get(name, 0.1) for name in names}
        if tables:
            cost[TABLES] = TABLES_COST

        def job(share: list[str]) -> dict[str, Any]:
            return {
                "directory": Path(directory),
                "cycle": cycle,
                "summary_row": dict(summary_row),
                "plenum": plenum,
                "names": tuple(name for name in share if name != TABLES),
                "tables": TABLES in share,
            }

        self.submit_shared("recipsim.report.report_figures", "write_report_share", cost, job)

    def submit_shared(
        self,
        module: str,
        function: str,
        cost: Mapping[str, float],
        job: Callable[[list[str]], dict[str, Any]],
        most: int = FAN_OUT_MOST,
    ) -> None:
        """Share the items of ``cost`` (name to measured cost [s]) between
        :meth:`drawing_processes` (at most ``most``) by cost (:func:`share_by_cost`) and
        :meth:`submit` ``module.function(**job(share))`` for each share; returns at
        once."""
        shares = share_by_cost(list(cost), self.drawing_processes(most), cost)
        # the lightest share first, drawn by the child that forks for the others: it
        # forks and sends their jobs before it draws (CPU of the two shares on 2 cores,
        # medians of 8 runs: 0.47 and 0.47 s this way, 0.50 and 0.38 s the other)
        shares.sort(key=lambda share: sum(cost[name] for name in share))
        self.submit(module, function, [job(share) for share in shares])

    def submit(self, module: str, function: str, jobs: list[dict[str, Any]]) -> None:
        """Run ``module.function(**kwargs)`` for each ``kwargs`` of ``jobs``: job ``i``
        goes to child ``i`` modulo the children, and a child given several forks itself
        for all but one of them when they arrive. Children without a job get none.

        Returns at once; :meth:`wait` waits for them.
        """
        if not self._jobs_open:
            raise RuntimeError("the figure processes had their jobs already")
        if jobs and not self._children:
            raise ValueError(f"{len(jobs)} jobs for no figure process")
        count = len(self._children)
        for index, (_pid, job, _result) in enumerate(self._children):
            calls = jobs[index::count]
            data = b""
            if calls:
                data = pickle.dumps((module, function, calls), pickle.HIGHEST_PROTOCOL)
            write_all(job, len(data).to_bytes(8, "little") + data)
            os.close(job)
        self._jobs_open = False

    def close(self) -> None:
        """Tell the children that no (more) job comes: they finish and exit."""
        if self._jobs_open:
            self._jobs_open = False
            for _pid, job, _result in self._children:
                try:
                    write_all(job, bytes(8))  # no job
                except OSError:
                    pass  # the child is gone: wait() reports it
                os.close(job)

    def wait(self) -> list[Any]:
        """Wait for every child (and its forks); re-raise the first failure.

        Returns
        -------
        list
            What each job's function returned, in the order of the jobs.

        Raises
        ------
        Exception
            What a child (or a fork of it) raised; RuntimeError when a child died.
        """
        self.close()
        failure: BaseException | None = None
        values: dict[int, Any] = {}
        count = len(self._children)
        for index, (pid, _job, result) in enumerate(self._children):
            reply = read_all(result)
            os.close(result)
            _, status = os.waitpid(pid, 0)
            if reply:
                ok, value = pickle.loads(reply)
                if ok:
                    values.update((index + call * count, v) for call, v in enumerate(value))
                elif failure is None:
                    failure = value
            elif failure is None and status != 0:
                failure = RuntimeError(f"figure process {pid} ended with status {status}")
        self._children = []
        if failure is not None:
            raise failure
        return [values[job] for job in sorted(values)]


def start_figure_processes(
    count: int | None = None,
    preload: tuple[str, ...] = REPORT_PRELOAD,
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
        ``at_least``. Without either, :meth:`FigureProcesses.draw` fans out onto the
        cores idle at the hand-over; with them the children alone draw (the setting
        is the number of processes that draw, 0: none, in-process).
    preload : tuple of str
        Modules the children import while they wait (default: the case report's).
        Each child imports them itself: no parent that forks figure processes
        imports pandas or matplotlib for them (``recipsim run`` and ``compare`` need
        neither, and since their tables are written from columns neither does the
        sweep), so on a busy machine one child costs no import twice, which is why
        ``recipsim run`` asks for ``at_least=1``.
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
    fan_out = count is None and not setting.isdigit()
    if count is None and setting.isdigit():
        count = int(setting)
    if not hasattr(os, "fork") or count == 0:
        return None
    if count is None:
        spare = 1 if busy_parent else 0
        count = max(idle_cores(2 + spare) - spare, at_least)
        if count == 0:
            return None
    return FigureProcesses(count, preload, fan_out=fan_out)
