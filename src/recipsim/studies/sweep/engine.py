"""Run a sweep end to end: plan, resume, compute, record, tabulate, plot.

:func:`run_sweep` is the Python entry point behind ``recipsim sweep``; it calls one
function per step: :func:`_checked_options` (refuse bad options and oversized sweeps
before any point is built), :func:`_plan` (the output directory and the points),
:func:`_open_store` (claim the output directory), :func:`_resume` (reuse finished points,
queue the others), :func:`_compute` (run the queued points, recording each as it
finishes) and :func:`_outcome` with :mod:`.outputs` (tables, plots, provenance).
"""

from __future__ import annotations

import os
import sys
import time
import uuid
import warnings
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from tqdm import TqdmWarning

with warnings.catch_warnings():
    # without ipywidgets, tqdm.auto warns (at import) and takes its text bar, which
    # _bar_disabled shows in a notebook too: the warning would only be noise
    warnings.simplefilter("ignore", TqdmWarning)
    from tqdm.auto import tqdm

from recipsim.atomic import mark_output
from recipsim.errors import RecipsimError
from recipsim.report.case_report import report_dir
from recipsim.studies.sweep import runner
from recipsim.studies.sweep.outputs import (
    Plots,
    SweepOutcome,
    summary_table,
    write_outputs,
    write_provenance,
)
from recipsim.studies.sweep.plan import PlannedPoint, plan_sweep
from recipsim.studies.sweep.plots import check_map_names
from recipsim.studies.sweep.spec import SweepSpec, load_sweep
from recipsim.studies.sweep.store import PointStore, SolveAndSave, point_record
from recipsim.studies.sweep.worker import OK, SOLVED, PointTask

TIMING_COLUMNS = ("wall_time [s]",)
"""Summary columns that differ from run to run (everything else is deterministic)."""


class SweepInterrupted(RecipsimError):
    """The sweep was interrupted (Ctrl-C); the finished points are on disk."""


def default_jobs() -> int:
    """Number of CPUs this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


def _check_parquet() -> None:
    try:
        import pyarrow  # noqa: F401
    except ImportError:
        raise RecipsimError(
            "--parquet needs pyarrow: pip install pyarrow (or pip install 'recipsim[parquet]')"
        ) from None


def run_sweep(
    path: str | Path | SweepSpec,
    *,
    jobs: int | None = None,
    scheduler: str | None = None,
    out: str | Path = Path("reports/sweeps"),
    overrides: Iterable[str] = (),
    reports: bool = False,
    plots: Plots = True,
    parquet: bool = False,
    retry_failed: bool = False,
    fresh: bool = False,
    progress: bool = False,
    argv: list[str] | None = None,
    started: float | None = None,
    max_points: int | None = None,
    scheduler_timeout: float = 10.0,
    allow_external_paths: bool = False,
) -> SweepOutcome:
    """Run (or resume) a sweep; what it produced, as a :class:`SweepOutcome`.

    Parameters
    ----------
    path : str, Path or SweepSpec
        Sweep file, or a sweep built in Python (:func:`recipsim.api.sweep`).
    jobs, scheduler, scheduler_timeout : int, optional; str, optional; float
        Local worker processes (default: the CPUs available; 1 runs the points in this
        process), ignored with ``scheduler``: the address of a Dask distributed
        scheduler to run the points on; seconds to wait for it to answer [s].
    out : str or Path
        Parent of the output directory ``<out>/<name>`` (``<out>/<name>+<digest of the
        overrides>`` with overrides); default ``reports/sweeps``.
    overrides : iterable of str
        ``KEY=VALUE`` overrides for every point (``--set``).
    reports, parquet : bool
        Also write a full report per point (``reports/<point_id>/``); also write
        ``summary.parquet`` (needs pyarrow).
    plots : bool or collection of str
        Draw the map plots (and the figures of per-point reports), or the map plots
        named (:data:`recipsim.studies.sweep.plots.MAP_NAMES`).
    retry_failed, fresh : bool
        Recompute the points recorded with a status other than ``ok``; forget every
        finished point and compute everything again.
    progress : bool
        Show a progress bar (``tqdm.auto``: on standard error in a terminal, a widget in
        a notebook, nothing when standard error is a file).
    argv, started : list of str; float, optional
        Command line, for the provenance file; :func:`time.perf_counter` value at which
        the command started (the reported wall time includes its imports; default: now).
    max_points : int, optional
        Refuse sweeps of more points (default: the sweep file's ``max_points``, else
        100 000), checked before any point is built.
    allow_external_paths : bool
        Let the sweep's ``base`` and the cases name files outside their directory.

    Raises
    ------
    CaseError
        Invalid sweep file (or an unknown case key in it), more points than allowed, an
        output directory that recipsim did not write, or one that recorded other
        overrides (unless ``fresh``).
    SweepInterrupted, WorkerLost
        Ctrl-C, a worker that died; finished points are kept and a rerun resumes.
    """
    start = time.perf_counter() if started is None else started
    spec = path if isinstance(path, SweepSpec) else load_sweep(path, allow_external_paths)
    plots = _checked_options(spec, parquet, plots, max_points)
    overrides = list(overrides)
    root, planned = _plan(spec, Path(out), overrides, max_points, allow_external_paths)
    store = _open_store(root, overrides, fresh)
    work = _resume(spec, planned, store, retry_failed, reports, bool(plots), allow_external_paths)
    where = (scheduler, jobs, scheduler_timeout)
    ran = (_compute(work, store, planned, spec.name, where, progress), scheduler)
    maps_bar = (lambda n: progress_bar(n, f"{spec.name} maps", "fig")) if progress else None
    outcome = _outcome(spec, root, planned, work, (plots, parquet, maps_bar), ran, start)
    write_provenance(outcome, scheduler, argv)
    return outcome


def _plan(
    spec: SweepSpec,
    out: Path,
    overrides: list[str],
    max_points: int | None,
    allow_external_paths: bool,
) -> tuple[Path, list[PlannedPoint]]:
    """The sweep's output directory and its points.

    The directory is ``<out>/<name>+<digest>`` with ``--set``, as ``recipsim run`` names
    reports: other overrides never share (or resume into) one directory; it must be new,
    empty or an earlier sweep's.
    """
    root = report_dir(out, spec.name, overrides)
    return root, plan_sweep(spec, overrides, max_points, allow_external_paths)


def _checked_options(spec: SweepSpec, parquet: bool, plots: Plots, max_points: int | None) -> Plots:
    """Refuse, before any point is built, ``--parquet`` without pyarrow, unknown map plot
    names and a sweep over the point limit; the plots to draw."""
    if parquet:
        _check_parquet()
    if plots is not True and plots:  # names of map plots, checked before any point runs
        plots = check_map_names(plots)
    spec.check_size(max_points)
    return plots


def _outcome(
    spec: SweepSpec,
    root: Path,
    planned: list[PlannedPoint],
    work: _Work,
    outputs: tuple[Plots, bool, Callable[[int], Any] | None],
    ran: tuple[int, str | None],
    start: float,
) -> SweepOutcome:
    """Tabulate the points and write the sweep's files.

    ``outputs``: the plots, parquet and the maps' progress bar (given their number);
    ``ran``: the worker processes
    used and the scheduler (used if any point was computed); the wall time is taken from
    ``start``.
    """
    plots, parquet, maps_bar = outputs
    table = summary_table(planned, work.records)
    axis_columns = {c for p in planned for c in p.columns}
    axes = [c for c in table.columns if c in axis_columns]
    files = write_outputs(spec, root, table, axes, (plots, maps_bar), parquet)
    wall = time.perf_counter() - start
    return SweepOutcome(
        spec=spec,
        directory=root,
        table=table,
        axes=axes,
        computed=work.computed,
        reused=work.reused,
        wall_time=wall,
        files=files,
        jobs=ran[0],
        scheduler=ran[1] if work.tasks else None,
    )


@dataclass
class _Work:
    """The points of one run: those taken from disk and those still to compute."""

    records: dict[str, dict[str, Any]] = field(default_factory=dict)
    reused: list[str] = field(default_factory=list)
    computed: list[str] = field(default_factory=list)
    tasks: list[PointTask] = field(default_factory=list)


def _open_store(root: Path, overrides: list[str], fresh: bool) -> PointStore:
    """Claim the sweep's output directory for ``overrides`` (emptied with ``fresh``)."""
    mark_output(root)
    store = PointStore(root)
    store.check_links()
    store.claim(overrides, fresh)
    store.clean_temporaries()
    if fresh:
        store.clear()
    return store


def _resume(
    spec: SweepSpec,
    planned: list[PlannedPoint],
    store: PointStore,
    retry_failed: bool,
    reports: bool,
    plots: bool,
    allow_external_paths: bool,
) -> _Work:
    """Take each finished point from ``store`` and queue the others, each point id once."""
    work = _Work()
    queued: set[str] = set()
    for point in planned:
        pid = point.point_id
        if pid in work.records or pid in queued:
            continue  # the same case twice in the sweep: computed once
        record = store.load(pid, point.overrides)
        if record is not None and _keep(record, retry_failed, reports, store, pid):
            work.records[pid] = record
            work.reused.append(pid)
        else:
            queued.add(pid)
            work.tasks.append(
                PointTask(
                    index=point.index,
                    point_id=pid,
                    case=str(spec.base),
                    overrides=point.overrides,
                    report_dir=str(store.report_dir(pid).resolve()) if reports else None,
                    plots=plots,
                    allow_external_paths=allow_external_paths,
                )
            )
    return work


def _compute(
    work: _Work,
    store: PointStore,
    planned: list[PlannedPoint],
    name: str,
    where: tuple[str | None, int | None, float],
    progress: bool,
) -> int:
    """Run ``work.tasks``, saving each point as it finishes, with an optional progress bar.

    ``where``: the Dask scheduler's address (or None), the local worker processes asked
    for (None: the CPUs available) and the seconds to wait for the scheduler.

    Returns
    -------
    int
        Local worker processes used (0 on a Dask cluster or with nothing to run).

    Raises
    ------
    SweepInterrupted
        On Ctrl-C, saying how many points are finished and where they are kept.
    """
    scheduler, asked, scheduler_timeout = where
    tasks = work.tasks
    jobs = 0 if scheduler or not tasks else max(1, min(asked or default_jobs(), len(tasks)))
    if not tasks:
        return jobs
    run_id = uuid.uuid4().hex
    bar: Any = None
    not_ok = 0

    def on_start() -> None:
        nonlocal bar
        if progress:  # a bar in a terminal or a notebook, nothing in a log file
            bar = progress_bar(len(tasks), name, "pt")

    def on_record(task: PointTask, record: dict[str, Any]) -> None:
        nonlocal not_ok
        work.records[task.point_id] = record
        work.computed.append(task.point_id)
        if bar is not None:
            if record["status"] != OK:
                not_ok += 1
                bar.set_postfix(failed=not_ok, refresh=False)
            bar.update(1)

    def on_result(task: PointTask, result: dict[str, Any]) -> None:
        record = point_record(task, result, run_id)
        store.save(task.point_id, record)
        on_record(task, record)

    try:
        if scheduler:
            # the optional dependency dask is imported only for a sweep on a cluster
            from recipsim.studies.sweep.dask_runner import run_dask

            run_dask(tasks, scheduler, on_result, on_start, scheduler_timeout)
        elif jobs > 1:  # local workers share this file system: each saves its points
            save = SolveAndSave(str(store.root), run_id)
            runner.run_pool(tasks, jobs, on_record, on_start, solve=save)
        else:
            runner.run_inline(tasks, on_result, on_start)
    except KeyboardInterrupt:
        done = len(work.records)
        raise SweepInterrupted(
            f"interrupted: {done} of {len(set(p.point_id for p in planned))} points are "
            f"finished and kept in {store.points}"
        ) from None
    finally:
        store.close()
        if bar is not None:
            bar.close()
    return jobs


def progress_bar(total: int, name: str, unit: str) -> Any:
    """A ``tqdm.auto`` bar on standard error: a widget in a notebook with ipywidgets,
    else a text bar in a notebook or a terminal, nothing when standard error is a file
    (:func:`_bar_disabled`)."""
    return tqdm(total=total, desc=name, unit=unit, file=sys.stderr, disable=_bar_disabled())


def _bar_disabled() -> bool | None:
    """tqdm's ``disable``: False where standard error is a notebook's output (ipykernel's
    stream: no terminal, yet it shows the text bar), else None (tqdm's rule: a bar on a
    terminal only)."""
    return False if type(sys.stderr).__module__.startswith("ipykernel") else None


def _keep(
    record: dict[str, Any], retry_failed: bool, reports: bool, store: PointStore, pid: str
) -> bool:
    """Whether a stored point is taken as it is."""
    if retry_failed and record["status"] != OK:
        return False
    if reports and record["status"] in SOLVED:
        return (store.report_dir(pid) / "summary.csv").is_file()
    return True
