"""Overlay figures of two (or more) cases: one curve per case on the same axes.

Every function takes cycle tables (:func:`recipsim.results.tables.cycle_table`, the columns of
``cycle.csv``) keyed by the case label used in the legend, and returns a
:class:`matplotlib.figure.Figure` built with the object-oriented API (no pyplot), or
None when no table has the columns the figure needs. :func:`save_overlay_figures`
writes the set of ``overlay_*.png`` files of ``recipsim compare``.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

from recipsim.physics.mechanics.layout import BEARING_NAMES
from recipsim.report.figure_kit import new_figure
from recipsim.report.figure_names import OVERLAY_NAMES
from recipsim.report.mechanics_plots import (
    ANGLE_COLUMN,
    LINE_STYLES,
    TORQUE_COLUMN,
    displacement,
    force_magnitude,
    has_orbits,
    plot_bearing_loads,
    plot_drive_torque,
    save_figure,
)

if TYPE_CHECKING:
    from matplotlib.figure import Figure

PRESSURE_COLUMN = "cylinder_pressure [Pa]"
VOLUME_COLUMN = "cylinder_volume [m3]"
SHAFT_TORQUE_COLUMN = "shaft_torque [N m]"
#: Bearings whose journal orbits are drawn (rotor to housing, as in the paper's Fig. 11).
ORBIT_BEARINGS: tuple[str, ...] = ("primary", "secondary")


def _style(k: int) -> dict[str, Any]:
    """Line style of the k-th case: dashes cycle, later lines thinner (coinciding curves
    stay visible)."""
    return {
        "color": f"C{k % 10}",
        "ls": LINE_STYLES[k % len(LINE_STYLES)],
        "lw": max(2.2 - 0.6 * k, 0.9),
    }


def _closed(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return np.append(x, x[:1]), np.append(y, y[:1])


def plot_pressure_overlay(
    cycles: Mapping[str, pd.DataFrame],
    plenum: Mapping[str, tuple[float, float]] | None = None,
) -> Figure | None:
    """Cylinder pressure [bar] against crank angle [deg], one curve per case.

    Parameters
    ----------
    cycles : mapping of str to pandas.DataFrame
        Cycle tables by case label; a table without ``cylinder_pressure [Pa]`` is
        skipped (for a tabulated case the column holds the applied curve).
    plenum : mapping of str to (float, float), optional
        Suction and discharge plenum pressure [Pa] per label, drawn as thin dotted
        lines in the colour of the case's curve.

    Returns
    -------
    matplotlib.figure.Figure or None
        None when no table has the pressure column.
    """
    tables = {k: t for k, t in cycles.items() if PRESSURE_COLUMN in t and ANGLE_COLUMN in t}
    if not tables:
        return None
    fig = new_figure(figsize=(7.0, 4.6), layout="constrained")
    ax = fig.subplots()
    for k, label in enumerate(cycles):  # the k-th case keeps its style in every figure
        if label not in tables:
            continue
        table = tables[label]
        angle = table[ANGLE_COLUMN].to_numpy(dtype=float)
        p = table[PRESSURE_COLUMN].to_numpy(dtype=float) / 1e5
        (line,) = ax.plot(*_closed_angle(angle, p), label=label, **_style(k))
        if plenum is not None and label in plenum:
            for level in plenum[label]:
                ax.axhline(level / 1e5, color=line.get_color(), ls=":", lw=0.8)
    ax.set_xlabel("crank angle from TDC [deg]")
    ax.set_ylabel("cylinder pressure [bar]")
    ax.set_xlim(0.0, 360.0)
    ax.set_xticks(np.arange(0.0, 361.0, 90.0))
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")
    ax.set_title("cylinder pressure (dotted: suction and discharge plenum)")
    return fig


def _closed_angle(angle: np.ndarray, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Append the first sample at +360 deg when the samples cover one revolution."""
    if angle.size > 1 and 300.0 < angle[-1] - angle[0] < 360.0:
        return np.append(angle, angle[0] + 360.0), np.append(values, values[0])
    return angle, values


def plot_pv_overlay(cycles: Mapping[str, pd.DataFrame]) -> Figure | None:
    """Indicator diagrams, linear and log-log, one closed curve per case.

    Tables without ``cylinder_volume [m3]`` and ``cylinder_pressure [Pa]`` are skipped;
    a tabulated case draws its applied curve against the kinematic volume.

    Returns
    -------
    matplotlib.figure.Figure or None
        None when no table has both columns.
    """
    tables = {k: t for k, t in cycles.items() if PRESSURE_COLUMN in t and VOLUME_COLUMN in t}
    if not tables:
        return None
    fig = new_figure(figsize=(11.0, 4.6), layout="constrained")
    linear, loglog = fig.subplots(1, 2)
    for k, label in enumerate(cycles):
        if label not in tables:
            continue
        table = tables[label]
        v = table[VOLUME_COLUMN].to_numpy(dtype=float) * 1e6
        p = table[PRESSURE_COLUMN].to_numpy(dtype=float) / 1e5
        for ax in (linear, loglog):
            ax.plot(*_closed(v, p), label=label, **_style(k))
    loglog.set_xscale("log")
    loglog.set_yscale("log")
    for axis in (loglog.xaxis, loglog.yaxis):  # plain numbers, no crowded minor labels
        from matplotlib.ticker import NullFormatter, ScalarFormatter

        axis.set_major_formatter(ScalarFormatter())
        axis.set_minor_formatter(NullFormatter())
    for ax, title in ((linear, "p-V diagram"), (loglog, "p-V diagram (log-log)")):
        ax.set_xlabel("cylinder volume [cm3]")
        ax.set_ylabel("cylinder pressure [bar]")
        ax.set_title(title)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize="small")
    return fig


def plot_torque_overlay(cycles: Mapping[str, pd.DataFrame]) -> Figure | None:
    """Driving torque on the crank [N m] against crank angle, one curve per case.

    Uses ``shaft_torque [N m]`` of each cycle table (the legend gives each mean);
    tables without it are skipped.

    Returns
    -------
    matplotlib.figure.Figure or None
    """
    tables = {
        label: t.rename(columns={SHAFT_TORQUE_COLUMN: TORQUE_COLUMN})
        for label, t in cycles.items()
        if SHAFT_TORQUE_COLUMN in t and ANGLE_COLUMN in t
    }
    if not tables:
        return None
    return plot_drive_torque(tables, title="driving torque on the crank")


def common_bearings(cycles: Mapping[str, pd.DataFrame], names: Sequence[str]) -> list[str]:
    """The bearings of ``names`` whose force every table has (magnitude or components)."""
    out = []
    for name in names:
        try:
            for table in cycles.values():
                force_magnitude(table.head(1), name)
        except KeyError:
            continue
        out.append(name)
    return out


def plot_bearing_overlay(cycles: Mapping[str, pd.DataFrame]) -> Figure | None:
    """Force magnitude [N] of every bearing against crank angle, a panel per bearing.

    Only bearings present in every table are drawn.

    Returns
    -------
    matplotlib.figure.Figure or None
    """
    bearings = common_bearings(cycles, BEARING_NAMES)
    if not cycles or not bearings:
        return None
    return plot_bearing_loads(cycles, bearings, title="bearing loads (force magnitude)")


def plot_orbit_overlay(
    cycles: Mapping[str, pd.DataFrame], bearings: Sequence[str] = ORBIT_BEARINGS
) -> Figure | None:
    """Journal orbits (Y against X displacement [um]), a panel per bearing, one curve
    per case; a dot marks top dead centre.

    Tables with no displacement for a bearing (pinned runs) are left out of its panel.

    Returns
    -------
    matplotlib.figure.Figure or None
        None when no table has a non-zero displacement of any of ``bearings``.
    """
    if not any(has_orbits(t, bearings) for t in cycles.values()):
        return None
    fig = new_figure(figsize=(4.4 * len(bearings) + 0.4, 4.6), layout="constrained")
    axes = np.atleast_1d(fig.subplots(1, len(bearings), squeeze=False)).ravel()
    for ax, bearing in zip(axes, bearings, strict=True):
        for k, (label, table) in enumerate(cycles.items()):
            xy = displacement(table, bearing)
            if xy is None:
                continue
            um = 1e6 * xy
            (line,) = ax.plot(*_closed(um[:, 0], um[:, 1]), label=label, **_style(k))
            ax.plot(um[0, 0], um[0, 1], "o", color=line.get_color(), ms=3.5)
        ax.axhline(0.0, color="0.6", lw=0.5)
        ax.axvline(0.0, color="0.6", lw=0.5)
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("displacement X [um]")
        ax.set_ylabel("displacement Y [um]")
        ax.set_title(bearing)
        ax.grid(True, alpha=0.3)
        if ax.lines:
            ax.legend(fontsize="small")
    title = "journal orbits relative to the bushing (dot: TDC)"
    rigid = [label for label, t in cycles.items() if not has_orbits(t, bearings)]
    if rigid:
        title += f"\nno displacement (pinned): {', '.join(rigid)}"
    fig.suptitle(title)
    return fig


#: The builder of each overlay figure of ``recipsim compare``
#: (:data:`recipsim.report.figure_names.OVERLAY_NAMES`), from the tables and the plenum.
OVERLAY_FIGURES: dict[str, Any] = {
    "overlay_pressure": lambda cycles, plenum: plot_pressure_overlay(cycles, plenum),
    "overlay_pv": lambda cycles, plenum: plot_pv_overlay(cycles),
    "overlay_torque": lambda cycles, plenum: plot_torque_overlay(cycles),
    "overlay_bearing_loads": lambda cycles, plenum: plot_bearing_overlay(cycles),
    "overlay_orbits": lambda cycles, plenum: plot_orbit_overlay(cycles),
}
assert tuple(OVERLAY_FIGURES) == OVERLAY_NAMES


def save_overlay_figures(
    cycles: Mapping[str, pd.DataFrame],
    out_dir: str | Path,
    plenum: Mapping[str, tuple[float, float]] | None = None,
    names: Sequence[str] | None = None,
) -> list[Path]:
    """Write the overlay figures of labelled cycle tables as PNG files.

    Files (each only when some table has its columns): ``overlay_pressure.png``,
    ``overlay_pv.png``, ``overlay_torque.png``, ``overlay_bearing_loads.png``,
    ``overlay_orbits.png`` (only when a case has flexible bearings).

    Parameters
    ----------
    cycles : mapping of str to pandas.DataFrame
        Cycle tables by case label.
    out_dir : str or pathlib.Path
        Existing directory.
    plenum : mapping of str to (float, float), optional
        Suction and discharge pressure [Pa] per label (:func:`plot_pressure_overlay`).
    names : sequence of str, optional
        Only these of :data:`~recipsim.report.figure_names.OVERLAY_NAMES`; default all.

    Returns
    -------
    list of pathlib.Path
        The files written.
    """
    out = Path(out_dir)
    tables = dict(cycles)
    written = []
    for name, build in OVERLAY_FIGURES.items():
        if names is not None and name not in names:
            continue
        fig = build(tables, plenum)
        if fig is not None:
            written.append(save_figure(fig, out / f"{name}.png"))
    return written
