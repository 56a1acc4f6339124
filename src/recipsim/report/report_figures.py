"""Which figures a case report draws and drawing them: shared by the in-process report
writer (:mod:`recipsim.report.case_report`) and the forked figure processes
(:mod:`recipsim.report.figure_process`). Importing it costs pandas, not matplotlib."""

from __future__ import annotations

import math
from collections.abc import Collection, Mapping
from pathlib import Path
from typing import Any

import pandas as pd


def report_figure_names(
    cycle: pd.DataFrame, summary_row: Mapping[str, Any], plots: bool | Collection[str] = True
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


def _moves(cycle: pd.DataFrame, bearing: str) -> bool:
    """Whether ``bearing``'s journal moves (mechanics_plots.has_orbits, without importing
    matplotlib)."""
    columns = [f"bearing_displacement_{bearing}_{axis} [m]" for axis in "xy"]
    return all(c in cycle for c in columns) and bool((cycle[columns] != 0.0).to_numpy().any())


def draw_report_figures(
    directory: Path,
    cycle: pd.DataFrame,
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
        save_cycle_figures(cycle, directory, plenum, title, cycle_names)
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
