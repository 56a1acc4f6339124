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
back), only where ``os.fork`` exists, and before any thread or numba's compiler has
started. A child that fails sends its exception back; the parent raises it. A child
whose parent dies reads end-of-file and exits. The figures are the same files as
those drawn in-process (:func:`recipsim.report.report_figures.draw_report_figures`).
"""

from __future__ import annotations

import os
import pickle
import sys
from collections.abc import Collection, Mapping
from pathlib import Path
from typing import Any

#: Measured CPU cost of each figure of the default case [s] (warm, 2-core machine),
#: used only to share the figures evenly between the children.
FIGURE_COST = {
    "p_V": 0.057,
    "p_V_loglog": 0.073,
    "p_theta": 0.071,
    "torque": 0.077,
    "valves": 0.087,
    "bearing_loads": 0.25,
    "orbits": 0.25,
    "loss_breakdown": 0.08,
}


def _read_all(fd: int) -> bytes:
    chunks = []
    while chunk := os.read(fd, 1 << 20):
        chunks.append(chunk)
    return b"".join(chunks)


def _write_all(fd: int, data: bytes) -> None:
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view) :]


def _child(jobs: int, results: int) -> None:
    """Body of a forked child: import the plotting modules, draw one job, report."""
    reply: Any = None
    try:
        import recipsim.report.loss_plot  # noqa: F401 - imports matplotlib
        import recipsim.report.plotting  # noqa: F401
        import recipsim.report.report_figures  # noqa: F401

        data = _read_all(jobs)
        if data:
            from recipsim.report.report_figures import draw_report_figures

            draw_report_figures(**pickle.loads(data))
    except BaseException as exc:  # noqa: BLE001 - everything goes back to the parent
        try:
            reply = pickle.dumps(exc)
        except Exception:  # noqa: BLE001 - an exception that cannot be pickled
            reply = pickle.dumps(RuntimeError(f"figure process: {exc!r}"))
    _write_all(results, reply or b"")


class FigureProcesses:
    """Forked children that draw a report's figures (see the module docstring).

    Parameters
    ----------
    count : int
        Children to fork (at least 1).
    """

    def __init__(self, count: int) -> None:
        self._children: list[tuple[int, int, int]] = []  # pid, job fd, result fd
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
                    _child(job_read, result_write)
                except BaseException:  # noqa: BLE001 - never return into the parent's code
                    status = 1
                finally:
                    os._exit(status)
            os.close(job_read)
            os.close(result_write)
            self._children.append((pid, job_write, result_read))

    def draw(
        self,
        directory: Path,
        cycle: Any,
        summary_row: Mapping[str, Any],
        plenum: tuple[float, float] | None,
        names: Collection[str],
    ) -> None:
        """Send the figures ``names`` of one report to the children, shared by cost.

        Returns at once; :meth:`wait` waits for the files. Can be called once.
        """
        shares: list[list[str]] = [[] for _ in self._children]
        loads = [0.0] * len(self._children)
        for name in sorted(names, key=lambda n: -FIGURE_COST.get(n, 0.1)):
            least = loads.index(min(loads))
            shares[least].append(name)
            loads[least] += FIGURE_COST.get(name, 0.1)
        for (_pid, job, _result), share in zip(self._children, shares, strict=True):
            if share:
                job_data = {
                    "directory": Path(directory),
                    "cycle": cycle,
                    "summary_row": dict(summary_row),
                    "plenum": plenum,
                    "names": tuple(share),
                }
                _write_all(job, pickle.dumps(job_data, protocol=pickle.HIGHEST_PROTOCOL))
        self.close()

    def close(self) -> None:
        """Tell the children that no (more) job comes: they finish and exit."""
        for _pid, job, _result in self._children:
            try:
                os.close(job)
            except OSError:
                pass  # already closed

    def wait(self) -> None:
        """Wait for every child; re-raise the first failure of a child.

        Raises
        ------
        Exception
            What a child raised while drawing; RuntimeError when a child died.
        """
        self.close()
        failure: BaseException | None = None
        for pid, _job, result in self._children:
            reply = _read_all(result)
            os.close(result)
            _, status = os.waitpid(pid, 0)
            if failure is None and reply:
                failure = pickle.loads(reply)
            elif failure is None and status != 0:
                failure = RuntimeError(f"figure process {pid} ended with status {status}")
        self._children = []
        if failure is not None:
            raise failure


def start_figure_processes(count: int | None = None) -> FigureProcesses | None:
    """Fork the figure children of one report, or None where forking is not available.

    Parameters
    ----------
    count : int, optional
        Children; default ``RECIPSIM_FIGURE_PROCESSES`` when set, else the usable
        cores, at most 2 (more do not pay for their start-up on a report's 7 figures).

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
        cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else 1
        count = max(1, min(2, cores))
    # pandas, which the parent needs anyway, is imported once before forking: the
    # children import only matplotlib (0.25 s each instead of 0.5 s)
    import recipsim.report.report_figures  # noqa: F401

    return FigureProcesses(count)
