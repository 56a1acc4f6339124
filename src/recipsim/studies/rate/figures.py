"""The figures a maker prints: capacity and power input against evaporating temperature,
a line per condensing temperature (the model's points, the fitted polynomial, catalogue
points and a maker's polynomial where given), and the envelope of the grid with the
points that failed marked.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import pandas as pd

from recipsim.report.figure_kit import fewer_ticks, new_figure
from recipsim.studies.rate.coefficients import PUBLISHED_UNITS, Polynomial, unit_factor
from recipsim.studies.rate.grid import RatingGrid
from recipsim.studies.rate.polynomial import from_kelvin, to_kelvin
from recipsim.studies.sweep.worker import OK

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

#: The quantities drawn against evaporating temperature, with their axis labels.
PANELS = {"cooling_capacity": "cooling capacity", "power_input": "power input"}
_SYMBOL = {"degC": "C", "degF": "F"}


def _curve(polynomial: Polynomial, grid: RatingGrid, s: np.ndarray, d: float) -> np.ndarray:
    """A polynomial along ``s`` at ``d`` (the grid's unit), in the rating's published unit."""
    unit = grid.temperature_unit
    factor = unit_factor(PUBLISHED_UNITS[unit][polynomial.quantity], polynomial.quantity)
    si = polynomial.si(to_kelvin(s, unit), to_kelvin(np.full_like(s, d), unit))
    return si / factor


def plot_quantity(
    ax: Axes,
    quantity: str,
    ratings: pd.DataFrame,
    grid: RatingGrid,
    fitted: dict[str, Polynomial],
    makers: dict[str, Polynomial] | None = None,
    catalogue: pd.DataFrame | None = None,
) -> Axes:
    """One quantity against evaporating temperature on ``ax``: a colour per condensing
    temperature, the model's points as markers, the fitted polynomial as a line, a maker's
    polynomial dashed, catalogue values as black crosses."""
    unit = grid.temperature_unit
    published = PUBLISHED_UNITS[unit][quantity]
    column = f"{quantity} [{published}]"
    evap = f"evaporating_temperature [{unit}]"
    from matplotlib import colormaps

    colours = iter(colormaps["viridis"](np.linspace(0.0, 0.85, len(grid.condensing))))
    s_fine = np.linspace(min(grid.evaporating), max(grid.evaporating), 60)
    for d in grid.condensing:
        colour = next(colours)
        rows = ratings[
            (ratings[f"condensing_temperature [{unit}]"] == d) & (ratings["status"] == OK)
        ]
        label = f"{d:g} {_SYMBOL[unit]}"
        if column in rows:
            ax.plot(rows[evap], rows[column], "o", color=colour, ms=4, label=label)
        if quantity in fitted:
            ax.plot(s_fine, _curve(fitted[quantity], grid, s_fine, d), "-", color=colour, lw=1.2)
        if makers and quantity in makers:
            ax.plot(s_fine, _curve(makers[quantity], grid, s_fine, d), "--", color=colour, lw=1.0)
    if catalogue is not None and len(catalogue):
        _catalogue_points(ax, quantity, catalogue, grid)
    ax.set_xlabel(f"evaporating temperature [{_SYMBOL[unit]}]")
    ax.set_ylabel(f"{PANELS.get(quantity, quantity)} [{published}]")
    ax.grid(True, alpha=0.3)
    fewer_ticks(ax)
    return ax


def _catalogue_points(ax: Axes, quantity: str, catalogue: pd.DataFrame, grid: RatingGrid) -> None:
    """The catalogue's values of ``quantity`` at the rating's standard, as black crosses."""
    wanted = {"cooling_capacity": "cooling_capacity", "power_input": "motor_electrical_power"}
    rows = catalogue[
        (catalogue["quantity"] == wanted.get(quantity, quantity))
        & (catalogue["standard"] == grid.standard)
    ]
    if not len(rows):
        return
    unit = grid.temperature_unit
    factor = unit_factor(PUBLISHED_UNITS[unit][quantity], quantity)
    ax.plot(
        from_kelvin(rows["evaporating_temperature [K]"].to_numpy(dtype=float), unit),
        rows["catalogue"].to_numpy(dtype=float) / factor,
        "x",
        color="black",
        ms=6,
        label="catalogue",
    )


def rating_figure(
    ratings: pd.DataFrame,
    grid: RatingGrid,
    fitted: dict[str, Polynomial],
    makers: dict[str, Polynomial] | None = None,
    catalogue: pd.DataFrame | None = None,
    title: str = "",
) -> Figure:
    """Capacity and power input against evaporating temperature, side by side."""
    fig = new_figure(figsize=(10.0, 4.4), layout="constrained")
    axes = fig.subplots(1, 2)
    for ax, quantity in zip(axes, PANELS, strict=True):
        plot_quantity(ax, quantity, ratings, grid, fitted, makers, catalogue)
    handles, labels = axes[0].get_legend_handles_labels()
    axes[1].legend(handles, labels, title="condensing", fontsize="small", loc="best")
    notes = "markers: model; lines: polynomial"
    if makers:
        notes += "; dashed: maker's polynomial"
    fig.suptitle(f"{title} ({grid.standard}; {notes})", fontsize="medium")
    return fig


def envelope_figure(
    ratings: pd.DataFrame, grid: RatingGrid, fitted: dict[str, Polynomial], title: str = ""
) -> Figure:
    """The grid in the evaporating-condensing plane: good points, failed points (red
    crosses, with their status) and the polynomial's range of validity."""
    unit = grid.temperature_unit
    fig = new_figure(figsize=(6.0, 4.8), layout="constrained")
    ax = fig.add_subplot()
    evap, cond = f"evaporating_temperature [{unit}]", f"condensing_temperature [{unit}]"
    good = ratings[ratings["status"] == OK]
    bad = ratings[ratings["status"] != OK]
    ax.plot(good[evap], good[cond], "o", color="tab:blue", ms=5, label=f"{len(good)} ok")
    if len(bad):
        ax.plot(bad[evap], bad[cond], "x", color="tab:red", ms=8, mew=2, label=f"{len(bad)} failed")
        for _, row in bad.iterrows():
            ax.annotate(row["status"], (row[evap], row[cond]), fontsize="x-small",
                        xytext=(4, 4), textcoords="offset points", color="tab:red")  # fmt: skip
    if fitted:
        first = next(iter(fitted.values()))
        s_lo, s_hi, d_lo, d_hi = first.bounds
        ax.plot([s_lo, s_hi, s_hi, s_lo, s_lo], [d_lo, d_lo, d_hi, d_hi, d_lo], "--",
                color="grey", lw=1.0, label="polynomial's range")  # fmt: skip
    ax.set_xlabel(f"evaporating (suction dew) temperature [{_SYMBOL[unit]}]")
    ax.set_ylabel(f"condensing (discharge dew) temperature [{_SYMBOL[unit]}]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small", loc="best")
    ax.set_title(f"{title}: rating grid ({grid.standard})", fontsize="medium")
    fewer_ticks(ax)
    return fig
