"""Figures a compressor engineer expects.

Every function takes the cycle table (``cycle.csv``'s DataFrame,
:attr:`recipsim.results.case_run.CaseRun.cycle`) and an optional ``ax`` and returns the
figure. Figures are built
with the object-oriented API (:class:`matplotlib.figure.Figure`, no pyplot): a library
never chooses a backend, so a notebook's ``plt.show()`` keeps working; ``savefig``
renders without one.
"""

from __future__ import annotations

from collections.abc import Callable, Collection
from typing import TYPE_CHECKING, Any

import pandas as pd

from recipsim.physics.mechanics.crank_trains import FLEXIBLE, PINNED
from recipsim.report.figure_kit import PNG_OPTIONS, angle_axis, fewer_ticks, new_figure
from recipsim.report.figure_names import FIGURE_NAMES, TITLE_Y, check_figure_names
from recipsim.report.mechanics_plots import (
    film_bearings,
    has_orbits,
    plot_bearing_loads,
    plot_orbits,
)

if TYPE_CHECKING:
    from matplotlib.figure import Figure


def _axes(ax: Any) -> tuple[Figure, Any]:
    if ax is None:
        fig = new_figure(figsize=(6.4, 4.4), layout="constrained")
        return fig, fig.add_subplot()
    return ax.figure, ax


def plot_pv(cycle: pd.DataFrame, ax: Any = None, log: bool = False, label: str = "") -> Figure:
    """Indicator diagram, cylinder pressure against volume (log-log with ``log``)."""
    fig, ax = _axes(ax)
    v = cycle["cylinder_volume [m3]"].to_numpy() * 1e6
    p = cycle["cylinder_pressure [Pa]"].to_numpy() / 1e5
    ax.plot(list(v) + [v[0]], list(p) + [p[0]], label=label or None)
    ax.set_xlabel("cylinder volume [cm3]")
    ax.set_ylabel("cylinder pressure [bar]")
    if log:
        from matplotlib.ticker import FormatStrFormatter, LogLocator, NullLocator

        ax.set_xscale("log")
        ax.set_yscale("log")
        # labels and grid lines at 1, 2, 5 x 10^k in plain numbers, no minor ticks: the
        # default labelled ones overlap on the volume axis, and unlabelled ones (six a
        # decade, with their grid lines) slow every draw
        for axis in (ax.xaxis, ax.yaxis):
            axis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
            axis.set_major_formatter(FormatStrFormatter("%g"))
            axis.set_minor_locator(NullLocator())
        ax.set_title("p-V diagram (log-log)", y=TITLE_Y)
    else:
        ax.set_title("p-V diagram", y=TITLE_Y)
        fewer_ticks(ax)
    ax.grid(True, alpha=0.3)
    return fig


def plot_pressure(
    cycle: pd.DataFrame, ax: Any = None, label: str = "", plenum: tuple[float, float] | None = None
) -> Figure:
    """Cylinder pressure against crank angle (plenum pressures dashed)."""
    fig, ax = _axes(ax)
    theta = cycle["crank_angle [deg]"].to_numpy()
    ax.plot(theta, cycle["cylinder_pressure [Pa]"].to_numpy() / 1e5, label=label or "cylinder")
    if plenum is not None:
        ax.axhline(plenum[0] / 1e5, ls="--", lw=0.8, color="tab:blue", label="suction")
        ax.axhline(plenum[1] / 1e5, ls="--", lw=0.8, color="tab:red", label="discharge")
    ax.set_xlabel("crank angle from TDC [deg]")
    ax.set_ylabel("pressure [bar]")
    angle_axis(ax)
    fewer_ticks(ax, x=False)
    ax.set_title("cylinder pressure", y=TITLE_Y)
    ax.grid(True, alpha=0.3)
    ax.legend()
    return fig


def plot_valves(cycle: pd.DataFrame, ax: Any = None) -> Figure:
    """Reed lifts (and mass flows on a second axis) against crank angle."""
    fig, ax = _axes(ax)
    theta = cycle["crank_angle [deg]"].to_numpy()
    ax.plot(theta, cycle["suction_valve_lift [m]"].to_numpy() * 1e3, label="suction lift")
    ax.plot(theta, cycle["discharge_valve_lift [m]"].to_numpy() * 1e3, label="discharge lift")
    ax.set_xlabel("crank angle from TDC [deg]")
    ax.set_ylabel("valve lift [mm]")
    angle_axis(ax)
    fewer_ticks(ax, x=False)
    ax2 = ax.twinx()
    ax2.plot(theta, cycle["suction_mass_flow [kg/s]"].to_numpy() * 1e3, ":", color="tab:blue")
    ax2.plot(theta, cycle["discharge_mass_flow [kg/s]"].to_numpy() * 1e3, ":", color="tab:orange")
    ax2.set_ylabel("mass flow [g/s] (dotted)")
    fewer_ticks(ax2, x=False)
    ax.set_title("valves", y=TITLE_Y)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper left")
    return fig


def plot_torque(cycle: pd.DataFrame, ax: Any = None, label: str = "") -> Figure:
    """Driving, gas and inertia torques on the crankshaft against crank angle [N m].

    One sign convention in every report (``reports/README.md``, "Torques"): a torque is
    positive when it turns the crank in its direction of rotation. The driving torque
    is positive on average; the gas torque, the torque of the gas force on the crank,
    is negative while the piston compresses and positive during re-expansion; the
    inertia torque is the driving torque plus the gas torque (what accelerates the
    bodies and, on flexible bearings, what the bearings take).
    """
    fig, ax = _axes(ax)
    theta = cycle["crank_angle [deg]"].to_numpy()
    ax.plot(theta, cycle["shaft_torque [N m]"].to_numpy(), label=label or "driving torque")
    if not label:
        ax.plot(theta, cycle["gas_torque [N m]"].to_numpy(), "--", lw=0.9, label="gas torque")
        inertia = cycle["inertia_torque [N m]"].to_numpy()
        ax.plot(theta, inertia, ":", lw=0.9, label="inertia torque")
    ax.axhline(0.0, color="0.5", lw=0.6)
    ax.set_xlabel("crank angle from TDC [deg]")
    ax.set_ylabel("torque on the crankshaft [N m]")
    angle_axis(ax)
    fewer_ticks(ax, x=False)
    ax.set_title("torques (positive: along the rotation)", y=TITLE_Y)
    ax.grid(True, alpha=0.3)
    ax.legend()
    return fig


# Fixed margins of the report's figures [inch] (left, right, bottom, top), instead of
# the constrained layout engine, which measures every label at every draw. Sizes fit
# the report's labels at its font size.
# The loss waterfall's are those its constrained layout found for its fixed labels.
_MARGINS = {
    "single": (0.85, 0.25, 0.6, 0.65),
    "panels": (0.85, 0.25, 0.6, 0.65),
    "twin": (0.85, 0.8, 0.6, 0.65),
    "waterfall": (1.83, 0.09, 0.48, 0.23),
}


def fixed_margins(fig: Figure, kind: str = "single") -> None:
    """Replace ``fig``'s layout engine by fixed margins (see ``_MARGINS``) [inch]."""
    left, right, bottom, top = _MARGINS[kind]
    width, height = fig.get_size_inches()
    # no layout engine at all: savefig draws a figure that has one (even the "none"
    # placeholder) twice, once to lay it out
    fig.set_layout_engine(None)
    if fig.get_layout_engine() is not None:  # a matplotlibrc that asks for one
        fig.set_layout_engine("none")
    # subplots_adjust refuses a figure made with a layout engine: the same by hand
    fig.subplotpars.update(
        left=left / width,
        right=1.0 - right / width,
        bottom=bottom / height,
        top=1.0 - top / height,
        hspace=0.45 if len(fig.axes) > 2 else None,
        wspace=0.18 if len(fig.axes) > 2 else None,
    )
    for ax in fig.axes:
        spec = ax.get_subplotspec()
        if spec is not None:
            ax.set_position(spec.get_position(fig))


def save_cycle_figures(
    cycle: pd.DataFrame,
    directory: Any,
    plenum: tuple[float, float] | None = None,
    title: str = "",
    only: Collection[str] | None = None,
) -> list[str]:
    """Write the standard figures of one case as PNG files; returns the file names.

    ``title`` (what was run: case, mechanics, drive, pressure source) heads every figure.
    ``only`` (names of :data:`FIGURE_NAMES`) draws just those of them that apply.
    Each figure is drawn and written before the next is built, with fixed margins
    (:func:`fixed_margins`).
    """
    from pathlib import Path

    directory = Path(directory)
    wanted = set(FIGURE_NAMES if only is None else check_figure_names(only))
    written = []
    for name, kind, make in _figure_makers(cycle, plenum):
        if name not in wanted:
            continue
        if kind == "single":
            fig = make(single_axes())
        else:
            fig = make()
            if kind is not None:
                fixed_margins(fig, kind)
        if title:
            fig.suptitle(title, fontsize="medium")
        fig.savefig(directory / f"{name}.png", dpi=110, pil_kwargs=PNG_OPTIONS)
        written.append(f"{name}.png")
    return written


def single_axes(figsize: tuple[float, float] = (6.4, 4.4)) -> Any:
    """The Axes of a new one-panel figure in the fixed margins ``"single"``."""
    fig = new_figure(figsize=figsize)
    ax = fig.add_subplot()
    fixed_margins(fig, "single")
    return ax


#: Makes one figure, on the given Axes where it has one panel (else it ignores it).
Maker = Callable[..., "Figure"]


def _figure_makers(
    cycle: pd.DataFrame, plenum: tuple[float, float] | None
) -> list[tuple[str, str | None, Maker]]:
    """(name, margins or None to keep the figure's layout, maker) of the figures that
    apply to ``cycle``. Margins ``"single"``: one panel, the maker takes an optional Axes
    to draw on."""
    makers: list[tuple[str, str | None, Maker]] = [
        ("p_V", "single", lambda ax=None: plot_pv(cycle, ax=ax)),
        ("p_V_loglog", "single", lambda ax=None: plot_pv(cycle, ax=ax, log=True)),
        ("p_theta", "single", lambda ax=None: plot_pressure(cycle, ax=ax, plenum=plenum)),
        ("torque", "single", lambda ax=None: plot_torque(cycle, ax=ax)),
    ]
    if "suction_valve_lift [m]" in cycle:  # the gas is simulated (not a tabulated pressure)
        makers.append(("valves", "twin", lambda: plot_valves(cycle)))
    if "bearing_force_primary [N]" in cycle:
        flexible = has_orbits(cycle)
        label = (FLEXIBLE if flexible else PINNED).name
        makers.append(("bearing_loads", "panels", lambda: plot_bearing_loads({label: cycle})))
        if flexible:
            # lubricated journals: every film bearing inside its clearance circle
            orbit_bearings = film_bearings(cycle) or ("primary", "secondary")
            # equal-aspect panels: left to the layout engine
            makers.append(("orbits", None, lambda: plot_orbits({label: cycle}, orbit_bearings)))
    return makers
