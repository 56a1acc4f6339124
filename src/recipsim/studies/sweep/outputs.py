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

from recipsim import __version__
from recipsim.atomic import atomic_file, atomic_write
from recipsim.report.csv_tables import record_column, write_columns_csv
from recipsim.studies.sweep.plan import PlannedPoint
from recipsim.studies.sweep.spec import SweepSpec
from recipsim.studies.sweep.worker import OK

if TYPE_CHECKING:
    import pandas as pd

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
    columns : dict of str to array or list
        The summary table's columns in order (:func:`build_columns`): what
        ``summary.csv`` holds, without pandas.
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
    columns: dict[str, Any]
    axes: list[str]
    computed: list[str]
    reused: list[str]
    wall_time: float
    files: list[Path] = field(default_factory=list)
    jobs: int = 1
    scheduler: str | None = None
    _table: pd.DataFrame | None = field(default=None, init=False, repr=False, compare=False)

    @property
    def table(self) -> pd.DataFrame:
        """The summary table (one row per point, in sweep order), made from
        :attr:`columns` when first asked for (the sweep itself needs no DataFrame: the
        command line's process does not import pandas for it)."""
        if self._table is None:
            import pandas as pd

            self._table = pd.DataFrame(self.columns)
        return self._table

    @property
    def n_points(self) -> int:
        """Rows of the table."""
        return len(self.columns["point"])

    @property
    def solve_seconds(self) -> float:
        """The points' solve times (``wall_time [s]``) added up, 0 for a point without
        one [s]."""
        times = self.columns.get("wall_time [s]", ())
        return float(sum(t for t in times if t is not None and t == t))

    @property
    def counts(self) -> dict[str, int]:
        """Number of points per status."""
        return dict(Counter(self.columns["status"]))

    @property
    def n_ok(self) -> int:
        """Points that converged."""
        return sum(status == OK for status in self.columns["status"])

    @property
    def n_failed(self) -> int:
        """Points that did not (``not_converged``, ``invalid``, ``failed``, ``error``)."""
        return self.n_points - self.n_ok


def build_columns(
    planned: Sequence[PlannedPoint], records: dict[str, dict[str, Any]]
) -> dict[str, Any]:
    """The summary table's columns: one value per point, in sweep order.

    Columns: ``point``, the axis columns, ``status``, ``message``, the summary columns
    of :func:`recipsim.results.tables.summary` (those not already given by an axis, in
    the order the ``ok`` points' records name them, then the others') and ``point_id``.
    Each is held as ``pandas.DataFrame(rows)`` would hold it
    (:func:`recipsim.report.csv_tables.record_column`): numbers as an int64 or float64
    array (NaN where a point has no value), the rest as a list.
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
    values: dict[str, Sequence[Any]] = {"point": [p.index for p in planned]}
    for column in axes:
        values[column] = [p.columns.get(column) for p in planned]
    values["status"] = [record["status"] for record in in_order]
    values["message"] = [record["message"] for record in in_order]
    # a row of summary values per point, then transposed (C loops, not one per value)
    rows = [list(map(record["summary"].get, summary_columns)) for record in in_order]
    values.update(zip(summary_columns, zip(*rows, strict=True), strict=True))
    values["point_id"] = [p.point_id for p in planned]
    return {name: record_column(cells) for name, cells in values.items()}


def write_outputs(
    spec: SweepSpec,
    root: Path,
    columns: dict[str, Any],
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
    columns : dict of str to array or list
        The summary table's columns (:func:`build_columns`), written to ``summary.csv``.
    axes : list of str
        Axis columns of the table (the map plots' axes).
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

        submit_map_plots(figures, columns, axes, root, None if plots is True else plots)
    files = []
    csv = root / "summary.csv"
    # the bytes of ``DataFrame(columns).to_csv(p, index=False)``, without pandas
    atomic_write(csv, lambda p: write_columns_csv(p, columns))
    files.append(csv)
    if parquet:
        import pandas as pd

        pq = root / "summary.parquet"
        atomic_write(pq, lambda p: pd.DataFrame(columns).to_parquet(p, index=False))
        files.append(pq)
    with atomic_file(root / "sweep.toml") as handle:
        handle.write(spec.text)
    if plots and figures is not None:
        from recipsim.studies.sweep.plots import MAP_NAMES

        drawn = {path.name: path for written in figures.wait() for path in written}
        files.extend(drawn[f"map_{n}.png"] for n in MAP_NAMES if f"map_{n}.png" in drawn)
    elif plots:
        from recipsim.studies.sweep.plots import save_map_plots

        files.extend(save_map_plots(columns, axes, root, None if plots is True else plots))
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
        "points": outcome.n_points,
        "computed": len(outcome.computed),
        "reused": len(outcome.reused),
        "status_counts": outcome.counts,
        "wall_time_s": outcome.wall_time,
        "created": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
        "command": argv or sys.argv,
    }
    with atomic_file(outcome.directory / "provenance.json") as handle:
        json.dump(meta, handle, indent=2, default=str)
