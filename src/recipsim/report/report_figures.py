"""Which figures a case report draws, drawing them, and writing the report's tables."""

from __future__ import annotations

import math
from collections.abc import Collection, Mapping
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from recipsim.report.figure_names import FIGURE_NAMES, check_figure_names
from recipsim.report.loss_plot import plot_loss_breakdown
from recipsim.report.plotting import PNG_OPTIONS, fixed_margins, save_cycle_figures
from recipsim.report.summary_text import pressure_label, summary_markdown


def report_figure_names(
    cycle: pd.DataFrame, summary_row: Mapping[str, Any], plots: bool | Collection[str] = True
) -> tuple[str, ...]:
    """Names of the figures a report draws: those of ``plots`` (True: all, False: none)
    that apply to the run (e.g. ``valves`` only with the simulated gas, ``loss_breakdown``
    only with the loss chain), in the order of
    :data:`recipsim.report.figure_names.FIGURE_NAMES`."""
    if not plots:
        return ()
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


def _moves(cycle: pd.DataFrame, bearing: str) -> bool:
    """Whether ``bearing``'s journal moves (its displacement columns are not all zero)."""
    columns = [f"bearing_displacement_{bearing}_{axis} [m]" for axis in "xy"]
    return all(c in cycle for c in columns) and any(
        bool(np.any(cycle[c].to_numpy() != 0.0)) for c in columns
    )


def write_tables(directory: Path, summary_row: Mapping[str, Any], cycle: pd.DataFrame) -> None:
    """Write ``summary.csv`` (one row, SI; pandas writes each float as the shortest text
    that reads back to it), ``summary.md`` (the key figures for a person) and
    ``cycle.csv`` into ``directory``."""
    pd.DataFrame([dict(summary_row)]).to_csv(Path(directory) / "summary.csv", index=False)
    (Path(directory) / "summary.md").write_text(summary_markdown(summary_row))
    cycle.to_csv(Path(directory) / "cycle.csv", index=False)


def draw_report_figures(
    directory: Path,
    cycle: pd.DataFrame,
    summary_row: Mapping[str, Any],
    plenum: tuple[float, float] | None,
    names: Collection[str],
) -> None:
    """Draw the report figures ``names`` (:func:`report_figure_names`) into ``directory``
    as ``<name>.png``, titled with :func:`run_title`."""
    title = run_title(summary_row)
    cycle_names = [name for name in names if name != "loss_breakdown"]
    if cycle_names:
        save_cycle_figures(cycle, directory, plenum, title, cycle_names)
    if "loss_breakdown" in names:
        figure = plot_loss_breakdown(summary_row, title=title)
        fixed_margins(figure, "waterfall")
        figure.savefig(Path(directory) / "loss_breakdown.png", dpi=110, pil_kwargs=PNG_OPTIONS)


def run_title(row: Mapping[str, Any]) -> str:
    """What was run, for plot titles: case name, mechanics, drive and pressure source."""
    pressure = pressure_label(row)
    return f"{row.get('case')}: {row.get('mechanics')} crank, {row.get('drive')}, {pressure}"
