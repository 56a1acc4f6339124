"""``startup.png``: the start-up from rest against time (speed, motor torque, cylinder
and plenum pressures, bearing loads), from the ``startup.csv`` table
(:func:`recipsim.results.startup.startup_table`)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import pandas as pd

from recipsim.report.figure_kit import new_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure


def plot_startup(table: pd.DataFrame, title: str = "") -> Figure:
    """Four stacked panels sharing the time axis [s]: crank speed [rpm], motor torque
    [N m], cylinder pressure with the suction and discharge plenums [bar], and the load
    of every bearing [N]. Returns the figure (no backend is chosen)."""
    fig = new_figure(figsize=(8.0, 10.0), layout="constrained")
    axes = fig.subplots(4, 1, sharex=True)
    t = table["time [s]"]
    axes[0].plot(t, table["crank_speed [rpm]"], lw=0.8)
    axes[0].set_ylabel("crank speed [rpm]")
    axes[1].plot(t, table["motor_torque [N m]"], lw=0.8)
    axes[1].set_ylabel("motor torque [N m]")
    axes[2].plot(t, table["cylinder_pressure [Pa]"] / 1e5, lw=0.5, label="cylinder")
    axes[2].plot(t, table["suction_pressure [Pa]"] / 1e5, lw=1.2, label="suction")
    axes[2].plot(t, table["discharge_pressure [Pa]"] / 1e5, lw=1.2, label="discharge")
    axes[2].set_ylabel("pressure [bar]")
    axes[2].legend(loc="upper left", fontsize="small")
    for column in table.columns:
        if column.startswith("bearing_load_"):
            name = column.removeprefix("bearing_load_").removesuffix(" [N]")
            axes[3].plot(t, table[column], lw=0.5, label=name)
    axes[3].set_ylabel("bearing load [N]")
    axes[3].legend(loc="upper left", fontsize="small", ncol=3)
    axes[3].set_xlabel("time from standstill [s]")
    if title:
        fig.suptitle(title)
    return fig
