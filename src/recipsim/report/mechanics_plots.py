"""Figures of the crank-train report tables: bearing loads, bearing orbits, drive torque.

Every function takes report tables (pandas DataFrames with the columns of a case's cycle
table or the paper study's: ``crank_angle [deg]`` from TDC,
``bearing_force_<name> [N]`` or its ``_x``/``_y``/``_z`` components,
``bearing_displacement_<name>_x|_y [m]``, ``drive_torque [N m]``) keyed by a label
("pinned", "flexible", ...) and returns a :class:`matplotlib.figure.Figure`.

Figures are built with the object-oriented API (no :mod:`matplotlib.pyplot`, no global
figure registry, no ``show``): they work under any backend, including none, and need
no closing. :func:`save_figure` writes one as PNG.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

from recipsim.physics.mechanics.layout import BEARING_NAMES
from recipsim.report.figure_kit import PNG_OPTIONS, angle_axis, new_figure
from recipsim.report.figure_names import TITLE_Y

if TYPE_CHECKING:
    from matplotlib.figure import Figure

ANGLE_COLUMN = "crank_angle [deg]"
TORQUE_COLUMN = "drive_torque [N m]"
#: Line styles cycled over the labelled tables (colours follow the default cycle).
LINE_STYLES: tuple[Any, ...] = ("-", "--", "-.", ":", (0, (5, 1, 1, 1, 1, 1)), (0, (1, 3)))
#: Orbit colours per bearing: primary red and secondary blue, as in the paper's Fig. 11.
ORBIT_COLOURS = {
    "primary": "tab:red",
    "secondary": "tab:blue",
    "eccentric": "tab:green",
    "pin": "tab:purple",
    "piston_top": "tab:orange",
    "piston_skirt": "tab:brown",
}
#: Resolution of the written PNG files [dots per inch].
DPI = 110


def force_magnitude(table: pd.DataFrame, bearing: str) -> np.ndarray:
    """Force magnitude of one bearing over the table rows [N].

    Parameters
    ----------
    table : pd.DataFrame
        Report table with ``bearing_force_<bearing> [N]``, or with its ``_x``, ``_y``
        (and optionally ``_z``) components [N].
    bearing : str
        Bearing name (one of ``BEARING_NAMES``).

    Returns
    -------
    numpy.ndarray
        (n,) [N].

    Raises
    ------
    KeyError
        If the table has neither the magnitude nor the X and Y components.
    """
    column = f"bearing_force_{bearing} [N]"
    if column in table:
        return table[column].to_numpy(dtype=float)
    parts = [f"bearing_force_{bearing}_{ax} [N]" for ax in "xyz"]
    present = [c for c in parts if c in table]
    if parts[0] not in present or parts[1] not in present:
        raise KeyError(f"no force columns for bearing {bearing!r} ({column} or its components)")
    comps = np.column_stack([table[c].to_numpy(dtype=float) for c in present])
    return np.linalg.norm(comps, axis=1)


def displacement(table: pd.DataFrame, bearing: str) -> np.ndarray | None:
    """Journal displacement of one bearing in its plane, (n, 2) [m], or None.

    Parameters
    ----------
    table : pd.DataFrame
        Report table.
    bearing : str
        Bearing name.

    Returns
    -------
    numpy.ndarray or None
        X and Y displacement columns [m]; None when the table has no displacement
        columns for this bearing or they are all zero (a pinned table).
    """
    cols = [f"bearing_displacement_{bearing}_{ax} [m]" for ax in "xy"]
    if not all(c in table for c in cols):
        return None
    xy = np.column_stack([table[c].to_numpy(dtype=float) for c in cols])
    if xy.size == 0 or not np.any(xy != 0.0):
        return None
    return xy


def film_clearance(table: pd.DataFrame, bearing: str) -> float | None:
    """Radial clearance of a bearing on an oil film, from its cycle columns [m], or None.

    The report's ``film_thickness_<bearing> [m]`` is the clearance less the journal's
    displacement from the sleeve centre, so their sum is the clearance at every sample
    (the median is taken against round-off).

    Parameters
    ----------
    table : pd.DataFrame
        Report table.
    bearing : str
        Bearing name.

    Returns
    -------
    float or None
        [m]; None when the bearing has no film columns (a linear or pinned bearing).
    """
    column = f"film_thickness_{bearing} [m]"
    xy = displacement(table, bearing)
    if column not in table or xy is None:
        return None
    film = table[column].to_numpy(dtype=float)
    return float(np.median(film + np.hypot(xy[:, 0], xy[:, 1])))


def film_bearings(table: pd.DataFrame) -> tuple[str, ...]:
    """The bearings of a report table that run on an oil film, ``BEARING_NAMES`` order."""
    return tuple(b for b in BEARING_NAMES if f"film_thickness_{b} [m]" in table)


def has_orbits(table: pd.DataFrame, bearings: Sequence[str] = ("primary", "secondary")) -> bool:
    """Whether a table has a non-zero displacement for at least one of ``bearings``."""
    return any(displacement(table, b) is not None for b in bearings)


def _closed(angle: np.ndarray, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Append the first sample at +360 deg when the samples cover one revolution."""
    if angle.size > 1 and angle[-1] - angle[0] < 360.0 and angle[-1] - angle[0] > 300.0:
        return np.append(angle, angle[0] + 360.0), np.append(values, values[0])
    return angle, values


def _angle_axis(ax: Any) -> None:
    angle_axis(ax)
    ax.grid(True, alpha=0.3)


def plot_bearing_loads(
    tables: Mapping[str, pd.DataFrame],
    bearings: Sequence[str] = BEARING_NAMES,
    title: str = "",
) -> Figure:
    """Bearing force magnitude against crank angle, one subplot per bearing.

    Parameters
    ----------
    tables : mapping of str to pd.DataFrame
        Report tables by label (e.g. ``{"pinned": ..., "flexible": ...}``); one line per
        table in every subplot, crank angle [deg] from TDC against force [N].
    bearings : sequence of str
        Bearings to plot, one subplot each (default all six).
    title : str
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure
    """
    if not tables:
        raise ValueError("no tables to plot")
    n = len(bearings)
    ncols = 2 if n > 1 else 1
    nrows = -(-n // ncols)
    fig = new_figure(figsize=(10.0, 2.6 * nrows + 0.8), layout="constrained")
    axes = np.atleast_1d(fig.subplots(nrows, ncols, sharex=True, squeeze=False)).ravel()
    for ax, bearing in zip(axes, bearings, strict=False):
        for k, (label, table) in enumerate(tables.items()):
            angle = table[ANGLE_COLUMN].to_numpy(dtype=float)
            a, f = _closed(angle, force_magnitude(table, bearing))
            ax.plot(a, f, ls=LINE_STYLES[k % len(LINE_STYLES)], lw=1.2, label=label)
        ax.set_title(bearing, y=TITLE_Y)
        ax.set_ylabel("force [N]")
        ax.grid(True, alpha=0.3)
    # the panels share their angle axis: its limits and ticks set once (set on each
    # panel, every setting would make the ticks of all six anew)
    angle_axis(axes[0])
    for ax in axes[n:]:
        ax.set_visible(False)
    for ax in axes[max(0, n - ncols) : n]:
        ax.set_xlabel("crank angle from TDC [deg]")
    axes[0].legend()
    fig.suptitle(title or "bearing loads")
    return fig


def plot_orbits(
    tables: Mapping[str, pd.DataFrame],
    bearings: Sequence[str] = ("primary", "secondary"),
    title: str = "",
) -> Figure:
    """Bearing orbits: journal displacement Y against X [um], one panel per table.

    Tables without displacement columns, or with all-zero displacements (pinned
    tables), are skipped. In each panel every bearing has its own colour (primary
    red, secondary blue, as in the paper's Fig. 11), equal aspect, and a dot at the
    first sample (TDC). A bearing on an oil film (``film_thickness_<name> [m]`` in the
    table) is drawn inside its clearance circle (dashed, radius the radial clearance,
    :func:`film_clearance`) with a cross at its smallest film, and the panel is
    framed on the largest circle; a linear bearing is drawn as its orbit alone.

    Parameters
    ----------
    tables : mapping of str to pd.DataFrame
        Report tables by label.
    bearings : sequence of str
        Bearings drawn together in each panel.
    title : str
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ValueError
        If no table has a non-zero displacement for any of ``bearings``.
    """
    panels = {label: t for label, t in tables.items() if has_orbits(t, bearings)}
    if not panels:
        raise ValueError(f"no table has displacements of {', '.join(bearings)}")
    n = len(panels)
    fig = new_figure(figsize=(3.9 * n + 0.4, 4.3), layout="constrained")
    axes = np.atleast_1d(fig.subplots(1, n, squeeze=False)).ravel()
    for ax, (label, table) in zip(axes, panels.items(), strict=True):
        largest = 0.0
        for bearing in bearings:
            xy = displacement(table, bearing)
            if xy is None:
                continue
            um = 1e6 * np.vstack([xy, xy[:1]])
            colour = ORBIT_COLOURS.get(bearing)
            ax.plot(um[:, 0], um[:, 1], color=colour, lw=1.0, label=bearing)
            ax.plot(um[0, 0], um[0, 1], "o", color=colour, ms=3.5)
            clearance = film_clearance(table, bearing)
            if clearance is not None:
                largest = max(largest, _clearance_circle(ax, table, bearing, clearance, um))
        ax.axhline(0.0, color="0.6", lw=0.5)
        ax.axvline(0.0, color="0.6", lw=0.5)
        if largest > 0.0:
            ax.set_xlim(-1.08 * largest, 1.08 * largest)
            ax.set_ylim(-1.08 * largest, 1.08 * largest)
            ax.set_aspect("equal", adjustable="box")
        else:
            ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("displacement X [um]")
        ax.set_ylabel("displacement Y [um]")
        ax.set_title(label)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize="small")
    fig.suptitle(title or "bearing orbits (journal relative to bushing; dot: TDC)")
    return fig


def _clearance_circle(
    ax: Any, table: pd.DataFrame, bearing: str, clearance: float, um: np.ndarray
) -> float:
    """Draw a film bearing's clearance circle and mark its smallest film; returns the
    circle's radius [um]."""
    from matplotlib.patches import Circle

    colour = ORBIT_COLOURS.get(bearing)
    radius = 1e6 * clearance
    circle = Circle((0.0, 0.0), radius, fill=False, ls="--", lw=0.8, color=colour)
    circle.set_gid(f"clearance_{bearing}")
    ax.add_patch(circle)
    film = table[f"film_thickness_{bearing} [m]"].to_numpy(dtype=float)
    k = int(np.argmin(film))
    ax.plot(
        um[k, 0],
        um[k, 1],
        "x",
        color=colour,
        ms=6.0,
        label=f"{bearing}: smallest film {1e6 * film[k]:.2f} um of {radius:.3g}",
    )
    return radius


def plot_drive_torque(tables: Mapping[str, pd.DataFrame], title: str = "") -> Figure:
    """Driving torque on the crank against crank angle, one line per table.

    Parameters
    ----------
    tables : mapping of str to pd.DataFrame
        Report tables by label with ``drive_torque [N m]``; the legend gives each mean
        [N m].
    title : str
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure
    """
    if not tables:
        raise ValueError("no tables to plot")
    fig = new_figure(figsize=(7.0, 4.4), layout="constrained")
    ax = fig.subplots()
    for k, (label, table) in enumerate(tables.items()):
        angle = table[ANGLE_COLUMN].to_numpy(dtype=float)
        torque = table[TORQUE_COLUMN].to_numpy(dtype=float)
        a, q = _closed(angle, torque)
        mean = float(np.mean(torque))
        if abs(mean) < 1e-9 * float(np.max(np.abs(torque), initial=0.0)):
            mean = 0.0  # round-off of a zero mean (inertia load only)
        ls = LINE_STYLES[k % len(LINE_STYLES)]
        lw = max(2.4 - 0.4 * k, 0.9)  # later lines thinner: coinciding curves stay visible
        ax.plot(a, q, ls=ls, lw=lw, label=f"{label} (mean {mean:.3g} N m)")
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.set_xlabel("crank angle from TDC [deg]")
    ax.set_ylabel("drive torque [N m]")
    _angle_axis(ax)
    ax.legend(fontsize="small")
    ax.set_title(title or "driving torque")
    return fig


def save_figure(fig: Figure, path: str | Path, dpi: int = DPI) -> Path:
    """Write a figure as PNG and return its path.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    path : str or pathlib.Path
        File to write (its directory must exist).
    dpi : int
        Resolution [dots per inch].

    Returns
    -------
    pathlib.Path
    """
    path = Path(path)
    fig.savefig(path, dpi=dpi, format="png", pil_kwargs=PNG_OPTIONS)
    return path


def save_mechanism_figures(
    tables: Mapping[str, pd.DataFrame], out_dir: str | Path, prefix: str = ""
) -> list[Path]:
    """Write the standard mechanism figures of labelled report tables as PNG files.

    Files: ``<prefix>bearing_loads.png``, ``<prefix>orbits.png`` (primary and
    secondary; only when some table has displacements) and
    ``<prefix>drive_torque.png``.

    Parameters
    ----------
    tables : mapping of str to pd.DataFrame
        Report tables by label.
    out_dir : str or pathlib.Path
        Directory, created if missing.
    prefix : str
        Prepended to every file name.

    Returns
    -------
    list of pathlib.Path
        The files written.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = [save_figure(plot_bearing_loads(tables), out / f"{prefix}bearing_loads.png")]
    if any(has_orbits(t) for t in tables.values()):
        written.append(save_figure(plot_orbits(tables), out / f"{prefix}orbits.png"))
    written.append(save_figure(plot_drive_torque(tables), out / f"{prefix}drive_torque.png"))
    return written
