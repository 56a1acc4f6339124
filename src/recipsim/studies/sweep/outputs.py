"""What a sweep leaves behind: its outcome, the summary table and the files written
(``summary.csv``, ``summary.parquet``, ``sweep.toml``, the map plots, ``provenance.json``).
"""

from __future__ import annotations

import platform
import sys
import time
from collections import Counter
from collections.abc import Callable, Collection, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pandas as pd

from recipsim.atomic import atomic_file, atomic_write
from recipsim.report.case_report import json_text
from recipsim.results.provenance import git_commit
from recipsim.studies.sweep.plan import PlannedPoint
from recipsim.studies.sweep.plots import save_map_plots
from recipsim.studies.sweep.spec import SweepSpec
from recipsim.studies.sweep.worker import OK
from recipsim.version import __version__

ID_COLUMNS = ("point", "status", "message", "point_id")

#: Map plots to draw: all (True), none (False) or those named (``plots.MAP_NAMES``).
Plots = bool | Collection[str]


@dataclass
class SweepOutcome:
    """What a sweep run produced.

    Attributes
    ----------
    spec : SweepSpec
        The sweep file as read.
    directory : Path
        Output directory ``<out>/<name>`` (``<out>/<name>+<digest>`` with overrides).
    table : pandas.DataFrame
        The summary table (:func:`summary_table`), one row per point in sweep order:
        what ``summary.csv`` holds.
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
    def n_points(self) -> int:
        """Rows of the table."""
        return len(self.table)

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
        return self.n_points - self.n_ok


def summary_table(
    planned: Sequence[PlannedPoint], records: dict[str, dict[str, Any]]
) -> pd.DataFrame:
    """The summary table: one row per point, in sweep order.

    Columns: ``point``, the axis columns, ``status``, ``message``, the summary columns
    of :func:`recipsim.results.tables.summary` (those not already given by an axis, in
    the order the ``ok`` points' records name them, then the others') and ``point_id``.
    A point without a value of a column has None there (NaN in a numeric column).
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
    order = ["point", *axes, "status", "message", *summary_columns, "point_id"]
    rows = []
    for point, record in zip(planned, in_order, strict=True):
        row = dict(record["summary"])
        row |= {"point": point.index, "status": record["status"], "message": record["message"]}
        row |= {column: point.columns.get(column) for column in axes}
        row["point_id"] = point.point_id
        rows.append([row.get(column) for column in order])
    return pd.DataFrame.from_records(rows, columns=order)


def write_outputs(
    spec: SweepSpec,
    root: Path,
    table: pd.DataFrame,
    axes: list[str],
    plots: tuple[Plots, Callable[[int], Any] | None],
    parquet: bool,
) -> list[Path]:
    """Write the sweep's tables, its sweep file and its map plots into ``root``.

    Parameters
    ----------
    spec : SweepSpec
        The sweep (its text is copied to ``sweep.toml``).
    root : Path
        The sweep's output directory.
    table : pandas.DataFrame
        The summary table (:func:`summary_table`), written to ``summary.csv``.
    axes : list of str
        Axis columns of the table (the map plots' axes).
    plots : (bool or collection of str, callable or None)
        Draw all map plots, none, or those named; a progress bar for them, made given
        their number (:func:`~.plots.save_map_plots`).
    parquet : bool
        Also write ``summary.parquet``.

    Returns
    -------
    list of Path
        The tables, then the map plots drawn (in :data:`~.plots.MAP_NAMES` order).
    """
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
    maps, bar = plots
    if maps:
        files.extend(save_map_plots(table, axes, root, None if maps is True else maps, bar))
    return files


def write_provenance(outcome: SweepOutcome, scheduler: str | None, argv: list[str] | None) -> None:
    """Write ``provenance.json`` beside the tables: versions, commit, counts, wall time [s].

    Parameters
    ----------
    outcome : SweepOutcome
        The finished sweep.
    scheduler : str or None
        Address of the Dask scheduler asked for.
    argv : list of str, optional
        Command line (default: :data:`sys.argv`).
    """
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
        "points": outcome.n_points,
        "computed": len(outcome.computed),
        "reused": len(outcome.reused),
        "status_counts": outcome.counts,
        "wall_time_s": outcome.wall_time,
        "created": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
        "command": argv or sys.argv,
    }
    with atomic_file(outcome.directory / "provenance.json") as handle:
        handle.write(json_text(meta))
