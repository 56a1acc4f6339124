"""Which figures a case report draws, drawing them and writing the report's tables:
shared by the in-process report writer (:mod:`recipsim.report.case_report`) and the
forked report processes (:mod:`recipsim.report.figure_process`). Importing it costs
neither pandas nor matplotlib: the command line decides which figures apply before it
has either, and a report process writes the tables and draws the figures without pandas
(:mod:`.csv_tables`, :class:`recipsim.results.columns.Columns`)."""

from __future__ import annotations

import math
from collections.abc import Collection, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from recipsim.report.csv_tables import write_columns_csv, write_row_csv
from recipsim.results.columns import as_columns

#: A cycle table: the DataFrame, :class:`~recipsim.results.columns.Columns`, or its
#: columns as numpy arrays (what a report process is sent, read through
#: :func:`~recipsim.results.columns.as_columns`).
Table = Any


def report_figure_names(
    cycle: Table, summary_row: Mapping[str, Any], plots: bool | Collection[str] = True
) -> tuple[str, ...]:
    """Names of the figures a report draws: those of ``plots`` (True: all, False: none)
    that apply to the run (e.g. ``valves`` only with the simulated gas, ``loss_breakdown``
    only with the loss chain), in the order of
    :data:`recipsim.report.figure_names.FIGURE_NAMES`."""
    if not plots:
        return ()
    from recipsim.report.figure_names import FIGURE_NAMES, check_figure_names

    wanted = set(FIGURE_NAMES if plots is True else check_figure_names(plots))
    applies = {"p_V", "p_V_loglog", "p_theta", "torque"}
    if "suction_valve_lift [m]" in cycle:
        applies.add("valves")
    if "bearing_force_primary [N]" in cycle:
        applies.add("bearing_loads")
        if any(_moves(cycle, bearing) for bearing in ("primary", "secondary")):
            applies.add("orbits")
    if math.isfinite(summary_row.get("loss_motor [W]", math.nan)):
        applies.add("loss_breakdown")
    return tuple(name for name in FIGURE_NAMES if name in wanted and name in applies)


def _moves(cycle: Table, bearing: str) -> bool:
    """Whether ``bearing``'s journal moves (mechanics_plots.has_orbits, without importing
    matplotlib)."""
    columns = [f"bearing_displacement_{bearing}_{axis} [m]" for axis in "xy"]
    table = as_columns(cycle)
    return all(c in table for c in columns) and any(
        bool(np.any(table[c].to_numpy() != 0.0)) for c in columns
    )


def write_tables(directory: Path, summary_row: Mapping[str, Any], cycle: Table) -> None:
    """Write ``summary.csv`` (one row) and ``cycle.csv`` into ``directory`` (the bytes
    pandas' ``to_csv`` writes, :mod:`.csv_tables`)."""
    table = as_columns(cycle)
    write_row_csv(Path(directory) / "summary.csv", summary_row)
    write_columns_csv(
        Path(directory) / "cycle.csv", {name: table[name].to_numpy() for name in table.columns}
    )


def write_report_share(
    directory: Path,
    cycle: Table,
    summary_row: Mapping[str, Any],
    plenum: tuple[float, float] | None,
    names: Collection[str],
    tables: bool = False,
) -> None:
    """One report process's share of a report: its tables (``tables``), then the figures
    ``names``."""
    table = as_columns(cycle)
    if tables:
        write_tables(directory, summary_row, table)
    if names:
        draw_report_figures(directory, table, summary_row, plenum, names)


def draw_report_figures(
    directory: Path,
    cycle: Table,
    summary_row: Mapping[str, Any],
    plenum: tuple[float, float] | None,
    names: Collection[str],
) -> None:
    """Draw the report figures ``names`` (:func:`report_figure_names`) into ``directory``
    as ``<name>.png``, titled with :func:`run_title`."""
    from recipsim.report.plotting import save_cycle_figures

    title = run_title(summary_row)
    cycle_names = [name for name in names if name != "loss_breakdown"]
    if cycle_names:
        save_cycle_figures(as_columns(cycle), directory, plenum, title, cycle_names)
    if "loss_breakdown" in names:
        from recipsim.report.loss_plot import plot_loss_breakdown
        from recipsim.report.plotting import PNG_OPTIONS, fixed_margins

        figure = plot_loss_breakdown(summary_row, title=title)
        fixed_margins(figure, "waterfall")
        figure.savefig(Path(directory) / "loss_breakdown.png", dpi=110, pil_kwargs=PNG_OPTIONS)


def run_title(row: Mapping[str, Any]) -> str:
    """What was run, for plot titles: case name, mechanics, drive and pressure source."""
    pressure = {"cylinder": "cylinder model", "tabulated": "tabulated pressure"}.get(
        str(row.get("pressure")), str(row.get("pressure"))
    )
    return f"{row.get('case')}: {row.get('mechanics')} crank, {row.get('drive')}, {pressure}"
