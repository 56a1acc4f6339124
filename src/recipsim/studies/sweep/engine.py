"""Run a sweep end to end: plan, resume, compute, record, tabulate, plot.

:func:`run_sweep` is the Python entry point behind ``recipsim sweep``.
"""

from __future__ import annotations

import json
import os
import platform
import sys
import time
import uuid
from collections import Counter
from collections.abc import Collection, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pandas as pd

from recipsim import __version__
from recipsim.atomic import atomic_file, atomic_write, mark_output
from recipsim.errors import RecipsimError
from recipsim.report.case_report import report_dir
from recipsim.studies.sweep.plan import PlannedPoint, plan_sweep
from recipsim.studies.sweep.spec import SweepSpec, load_sweep
from recipsim.studies.sweep.store import PointStore
from recipsim.studies.sweep.worker import OK, SOLVED, PointTask

if TYPE_CHECKING:
    from recipsim.report.figure_process import FigureProcesses

TIMING_COLUMNS = ("wall_time [s]",)
"""Summary columns that differ from run to run (everything else is deterministic)."""

ID_COLUMNS = ("point", "status", "message", "point_id")

#: Map plots to draw: all (True), none (False) or those named (``plots.MAP_NAMES``).
Plots = bool | Collection[str]


class SweepInterrupted(RecipsimError):
    """The sweep was interrupted (Ctrl-C); the finished points are on disk."""


@dataclass
class SweepOutcome:
    """What a sweep run produced.

    Attributes
    ----------
    spec : SweepSpec
        The sweep file as read.
    directory : Path
        Output directory ``<out>/<name>`` (``<out>/<name>+<digest>`` with overrides).
    table : DataFrame
        The summary table (one row per point, in sweep order).
    axes : list of str
        Axis columns of the table.
    computed : list of str
        Point ids computed (or found invalid) by this run.
    reused : list of str
        Point ids taken from an earlier run.
    wall_time : float
        Duration of the whole run [s].
    files : list of Path
        Tables and plots written.
    jobs : int
        Local worker processes used (0 on a Dask cluster or when nothing was run).
    scheduler : str or None
        Address of the Dask scheduler used.
    """

    spec: SweepSpec
    directory: Path
    table: pd.DataFrame
    axes: list[str]
    computed: list[str]
    reused: list[str]
    wall_time: float
    files: list[Path] = field(default_factory=list)
    jobs: int = 1
    scheduler: str | None = None

    @property
    def counts(self) -> dict[str, int]:
        """Number of points per status."""
        return dict(Counter(self.table["status"]))

    @property
    def n_ok(self) -> int:
        """Points that converged."""
        return int((self.table["status"] == OK).sum())

    @property
    def n_failed(self) -> int:
        """Points that did not (``not_converged``, ``invalid``, ``failed``, ``error``)."""
        return len(self.table) - self.n_ok


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


def _record(task: PointTask, result: dict[str, Any], run_id: str) -> dict[str, Any]:
    return {
        "status": result["status"],
        "message": result["message"],
        "summary": result["summary"],
        "overrides": list(task.overrides),
        "run": run_id,
        "finished": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
    }


def build_table(
    planned: Sequence[PlannedPoint], records: dict[str, dict[str, Any]]
) -> pd.DataFrame:
    """Assemble the summary table: one row per point, in sweep order.

    Columns: ``point``, the axis columns, ``status``, ``message``, the summary columns
    of :func:`recipsim.results.tables.summary` (those not already given by an axis) and
    ``point_id``.
    """
    axes: list[str] = list(dict.fromkeys(c for p in planned for c in p.columns))
    summary_columns: list[str] = []
    seen: set[str] = set(axes) | set(ID_COLUMNS)
    in_order = [records[p.point_id] for p in planned]
    ordered = sorted(in_order, key=lambda r: r["status"] != OK)  # ok rows first, stable
    for record in ordered:
        for column in record["summary"]:
            if column not in seen:
                seen.add(column)
                summary_columns.append(column)
    rows = []
    for point in planned:
        record = records[point.point_id]
        row: dict[str, Any] = {"point": point.index}
        row.update({c: point.columns.get(c) for c in axes})
        row["status"] = record["status"]
        row["message"] = record["message"]
        summary = record["summary"]
        row.update({c: summary.get(c) for c in summary_columns})
        row["point_id"] = point.point_id
        rows.append(row)
    columns = ["point", *axes, "status", "message", *summary_columns, "point_id"]
    return pd.DataFrame(rows, columns=columns)


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
    figures: FigureProcesses | None = None,
) -> SweepOutcome:
    """Run (or resume) a sweep.

    Parameters
    ----------
    path : str, Path or SweepSpec
        Sweep file, or a sweep built in Python (:func:`recipsim.api.sweep`).
    jobs : int, optional
        Local worker processes (default: the CPUs available); 1 runs the points in
        this process. Ignored with ``scheduler``.
    scheduler : str, optional
        Address of a Dask distributed scheduler to run the points on.
    out : str or Path
        Parent of the sweep's output directory (default ``reports/sweeps``): the sweep
        goes to ``<out>/<name>``, or ``<out>/<name>+<digest of the overrides>``.
    overrides : iterable of str
        ``KEY=VALUE`` overrides for every point (``--set``).
    reports : bool
        Also write a full report per point (``reports/<point_id>/``).
    plots : bool or collection of str
        Draw the map plots (and the figures of per-point reports); a collection names
        the map plots to draw (:data:`recipsim.studies.sweep.plots.MAP_NAMES`).
    parquet : bool
        Also write ``summary.parquet`` (needs pyarrow).
    retry_failed : bool
        Recompute points recorded with a status other than ``ok``.
    fresh : bool
        Forget every finished point and compute everything again.
    progress : bool
        Show a progress bar on standard error if it is a terminal.
    argv : list of str, optional
        Command line, for the provenance file.
    started : float, optional
        :func:`time.perf_counter` value at which the command started (so that the
        reported wall time includes its imports); default: now.
    max_points : int, optional
        Refuse sweeps of more points (default: the sweep file's ``max_points``, else
        100 000), checked before any point is built.
    scheduler_timeout : float
        Seconds to wait for the Dask scheduler to answer [s].
    allow_external_paths : bool
        Let the sweep's ``base`` and the cases name files outside their directory.
    figures : FigureProcesses, optional
        Forked processes that draw the map plots, shared between them
        (:func:`recipsim.report.figure_process.start_figure_processes`, the command
        line's); None draws them here, one after the other.

    Returns
    -------
    SweepOutcome

    Raises
    ------
    CaseError
        Invalid sweep file (or an unknown case key in it), more points than allowed,
        an output directory that recipsim did not write, or one that recorded other
        overrides (unless ``fresh``).
    SweepInterrupted
        Ctrl-C; finished points are kept and a rerun resumes.
    WorkerLost
        A worker died; finished points are kept and a rerun resumes.
    """
    start = time.perf_counter() if started is None else started
    spec = path if isinstance(path, SweepSpec) else load_sweep(path, allow_external_paths)
    if parquet:
        _check_parquet()
    if plots is not True and plots:  # names of map plots, checked before any point runs
        from recipsim.studies.sweep.plots import check_map_names

        plots = check_map_names(plots)
    spec.check_size(max_points)
    overrides = list(overrides)
    # <name>+<digest> with --set, as `recipsim run` names reports: other overrides never
    # share (or resume into) one directory; a new, empty or earlier sweep directory
    root = report_dir(Path(out), spec.name, overrides)
    planned = plan_sweep(spec, overrides, max_points, allow_external_paths)
    mark_output(root)
    store = PointStore(root)
    store.claim(overrides, fresh)
    store.clean_temporaries()
    if fresh:
        store.clear()
    run_id = uuid.uuid4().hex
    records: dict[str, dict[str, Any]] = {}
    reused: list[str] = []
    computed: list[str] = []
    tasks: list[PointTask] = []
    queued: set[str] = set()
    for point in planned:
        pid = point.point_id
        if pid in records or pid in queued:
            continue  # the same case twice in the sweep: computed once
        record = store.load(pid, point.overrides)
        if record is not None and _keep(record, retry_failed, reports, store, pid):
            records[pid] = record
            reused.append(pid)
        else:
            queued.add(pid)
            tasks.append(
                PointTask(
                    index=point.index,
                    point_id=pid,
                    case=str(spec.base),
                    overrides=point.overrides,
                    report_dir=str(store.report_dir(pid).resolve()) if reports else None,
                    plots=bool(plots),
                    allow_external_paths=allow_external_paths,
                )
            )

    bar: Any = None
    not_ok = 0

    def on_start() -> None:
        nonlocal bar
        if progress and tasks and sys.stderr.isatty():
            try:
                from tqdm import tqdm
            except ImportError:  # no progress bar, nothing else lost
                return
            bar = tqdm(
                total=len(tasks), desc=spec.name, unit="pt", file=sys.stderr, dynamic_ncols=True
            )

    def on_result(task: PointTask, result: dict[str, Any]) -> None:
        nonlocal not_ok
        record = _record(task, result, run_id)
        store.save(task.point_id, record)
        records[task.point_id] = record
        computed.append(task.point_id)
        if bar is not None:
            if record["status"] != OK:
                not_ok += 1
                bar.set_postfix(failed=not_ok, refresh=False)
            bar.update(1)

    used_jobs = 0 if scheduler or not tasks else max(1, min(jobs or default_jobs(), len(tasks)))
    try:
        if tasks:
            _execute(tasks, scheduler, used_jobs, on_result, on_start, scheduler_timeout)
    except KeyboardInterrupt:
        done = len(records)
        raise SweepInterrupted(
            f"interrupted: {done} of {len(set(p.point_id for p in planned))} points are "
            f"finished and kept in {store.points}"
        ) from None
    finally:
        if bar is not None:
            bar.close()

    table = build_table(planned, records)
    axes = [c for c in table.columns if c in {c for p in planned for c in p.columns}]
    files = _write_outputs(spec, root, table, axes, plots, parquet, figures)
    wall = time.perf_counter() - start
    outcome = SweepOutcome(
        spec=spec,
        directory=root,
        table=table,
        axes=axes,
        computed=computed,
        reused=reused,
        wall_time=wall,
        files=files,
        jobs=used_jobs,
        scheduler=scheduler if tasks else None,
    )
    _write_provenance(outcome, scheduler, argv)
    return outcome


def _keep(
    record: dict[str, Any], retry_failed: bool, reports: bool, store: PointStore, pid: str
) -> bool:
    """Whether a stored point is taken as it is."""
    if retry_failed and record["status"] != OK:
        return False
    if reports and record["status"] in SOLVED:
        return (store.report_dir(pid) / "summary.csv").is_file()
    return True


def _execute(
    tasks: list[PointTask],
    scheduler: str | None,
    jobs: int,
    on_result: Any,
    on_start: Any,
    scheduler_timeout: float,
) -> None:
    from recipsim.studies.sweep import runner

    if scheduler:
        runner.run_dask(tasks, scheduler, on_result, on_start, scheduler_timeout)
        return
    if jobs > 1:
        # import the solver here, before the workers are forked: they start warm
        import recipsim.model.build  # noqa: F401
        import recipsim.results.tables  # noqa: F401
        import recipsim.solve.periodic  # noqa: F401

        runner.run_pool(tasks, jobs, on_result, on_start)
    else:
        runner.run_inline(tasks, on_result, on_start)


def _write_outputs(
    spec: SweepSpec,
    root: Path,
    table: pd.DataFrame,
    axes: list[str],
    plots: Plots,
    parquet: bool,
    figures: FigureProcesses | None = None,
) -> list[Path]:
    if plots and figures is not None:
        from recipsim.studies.sweep.plots import submit_map_plots

        submit_map_plots(figures, table, axes, root, None if plots is True else plots)
    files = []
    csv = root / "summary.csv"
    atomic_write(csv, lambda p: table.to_csv(p, index=False))
    files.append(csv)
    if parquet:
        pq = root / "summary.parquet"
        atomic_write(pq, lambda p: table.to_parquet(p, index=False))
        files.append(pq)
    with atomic_file(root / "sweep.toml") as handle:
        handle.write(spec.text)
    if plots and figures is not None:
        from recipsim.studies.sweep.plots import MAP_NAMES

        drawn = {path.name: path for written in figures.wait() for path in written}
        files.extend(drawn[f"map_{n}.png"] for n in MAP_NAMES if f"map_{n}.png" in drawn)
    elif plots:
        from recipsim.studies.sweep.plots import save_map_plots

        files.extend(save_map_plots(table, axes, root, None if plots is True else plots))
    return files


def _write_provenance(outcome: SweepOutcome, scheduler: str | None, argv: list[str] | None) -> None:
    from recipsim.results.provenance import git_commit

    versions = {}
    for module in ("CoolProp", "numpy", "scipy", "numba", "pandas", "dask", "distributed"):
        mod = sys.modules.get(module)
        if mod is not None:
            versions[module] = getattr(mod, "__version__", "")
    meta = {
        "recipsim": __version__,
        "git_commit": git_commit(),
        "python": sys.version.split()[0],
        "platform": platform.platform(),
        **versions,
        "sweep": str(outcome.spec.path),
        "base": str(outcome.spec.base),
        "scheduler": scheduler,
        "jobs": outcome.jobs,
        "points": len(outcome.table),
        "computed": len(outcome.computed),
        "reused": len(outcome.reused),
        "status_counts": outcome.counts,
        "wall_time_s": outcome.wall_time,
        "created": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
        "command": argv or sys.argv,
    }
    with atomic_file(outcome.directory / "provenance.json") as handle:
        json.dump(meta, handle, indent=2, default=str)
