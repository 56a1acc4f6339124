"""What a sweep leaves behind: its outcome, the summary table and the files written
(``summary.csv``, ``summary.parquet``, ``sweep.toml``, the map plots, ``provenance.json``).
"""

from __future__ import annotations

import json
import platform
import sys
import time
from collections import Counter
from collections.abc import Collection, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pandas as pd

from recipsim import __version__
from recipsim.atomic import atomic_file, atomic_write
from recipsim.report.csv_tables import write_columns_csv
from recipsim.studies.sweep.plan import PlannedPoint
from recipsim.studies.sweep.spec import SweepSpec
from recipsim.studies.sweep.worker import OK

if TYPE_CHECKING:
    from recipsim.report.figure_process import FigureProcesses

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


def write_outputs(
    spec: SweepSpec,
    root: Path,
    table: pd.DataFrame,
    axes: list[str],
    plots: Plots,
    parquet: bool,
    figures: FigureProcesses | None = None,
) -> list[Path]:
    """Write the sweep's tables, its sweep file and its map plots into ``root``.

    Parameters
    ----------
    spec : SweepSpec
        The sweep (its text is copied to ``sweep.toml``).
    root : Path
        The sweep's output directory.
    table : DataFrame
        The summary table (:func:`build_table`), written to ``summary.csv``.
    axes : list of str
        Axis columns of ``table`` (the map plots' axes).
    plots : bool or collection of str
        Draw all map plots, none, or those named.
    parquet : bool
        Also write ``summary.parquet``.
    figures : FigureProcesses, optional
        Processes that draw the map plots while the tables are written; None draws them
        here after the tables.

    Returns
    -------
    list of Path
        The tables, then the map plots drawn (in :data:`~.plots.MAP_NAMES` order).
    """
    if plots and figures is not None:
        from recipsim.studies.sweep.plots import submit_map_plots

        submit_map_plots(figures, table, axes, root, None if plots is True else plots)
    files = []
    csv = root / "summary.csv"
    # the bytes of ``table.to_csv(p, index=False)``, faster (1000 points: 50-65 ms, not 100)
    columns = {name: table[name].to_numpy() for name in table.columns}
    atomic_write(csv, lambda p: write_columns_csv(p, columns))
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
