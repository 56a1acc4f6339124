"""Map plots of a sweep: performance against evaporating temperature, a line per group.

The x axis is the evaporating temperature (in degrees Celsius on the plot) when it
varies, otherwise the first numeric axis that varies. Every other axis that varies
(refrigerant, condensing temperature, speed, ...) splits the points into lines:
colour follows the first such axis, line style the others. Only ``ok`` points are
drawn. Peak bearing loads are drawn when the summary has ``bearing_max_<name> [N]``
columns (flexible mechanics).
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Collection, Iterable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pandas as pd
from pandas.api.types import is_numeric_dtype

from recipsim.atomic import atomic_write
from recipsim.errors import CaseError
from recipsim.report.figure_kit import fewer_ticks, lines_as_collections, new_figure
from recipsim.report.figure_names import TITLE_Y
from recipsim.report.plotting import PNG_OPTIONS, single_axes

if TYPE_CHECKING:
    from matplotlib.figure import Figure

MAP_QUANTITIES: tuple[tuple[str, str, str], ...] = (
    ("cooling_capacity [W]", "cooling capacity [W]", "map_cooling_capacity.png"),
    ("shaft_power [W]", "shaft power [W]", "map_shaft_power.png"),
    ("COP [-]", "COP [-]", "map_COP.png"),
    ("volumetric_efficiency [-]", "volumetric efficiency [-]", "map_volumetric_efficiency.png"),
    ("isentropic_efficiency [-]", "isentropic efficiency [-]", "map_isentropic_efficiency.png"),
)
BEARING_COLUMN = re.compile(r"^bearing_max_(\w+) \[N\]$")
EVAPORATING = "evaporating_temperature [K]"
_STYLES = ("-", "--", ":", "-.")
_MARKERS = ("o", "s", "^", "D", "v", "P", "X", "*")


def _split(column: str) -> tuple[str, str]:
    """``"name [unit]"`` to (name, unit); no unit gives ``""``."""
    match = re.match(r"^(.*) \[(.*)\]$", column)
    return (match.group(1), match.group(2)) if match else (column, "")


def _numeric(table: pd.DataFrame, column: str) -> bool:
    return bool(is_numeric_dtype(table[column]))


def x_column(table: pd.DataFrame, axes: Sequence[str]) -> str | None:
    """Column for the x axis: the evaporating temperature, else the first numeric axis."""
    varying = [c for c in axes if c in table and table[c].nunique(dropna=True) > 1]
    if EVAPORATING in varying:
        return EVAPORATING
    for column in varying:
        if _numeric(table, column):
            return column
    if EVAPORATING in table and table[EVAPORATING].nunique(dropna=True) > 1:
        return EVAPORATING
    return None


def group_columns(table: pd.DataFrame, axes: Sequence[str], x: str) -> list[str]:
    """Axis columns other than ``x`` that vary: one line per combination of their values."""
    return [c for c in axes if c != x and c in table and table[c].nunique(dropna=True) > 1]


def _display(column: str, values: Any) -> tuple[Any, str]:
    """Values and axis label for plotting (K as degC, rad/s as rpm)."""
    name, unit = _split(column)
    label = name.replace("_", " ")
    if unit == "K":
        return values - 273.15, f"{label} [°C]"
    if unit == "rad/s":
        return values * 60.0 / (2.0 * math.pi), f"{label} [rpm]"
    return values, f"{label} [{unit}]" if unit else label


def _value_label(column: str, value: Any) -> str:
    name, unit = _split(column)
    name = name.replace("_temperature", "").replace("_", " ")
    if isinstance(value, str):
        return value if column == "refrigerant" else f"{name} {value}"
    if unit == "K":
        return f"{name} {value - 273.15:g} °C"
    if unit == "rad/s":
        return f"{name} {value * 60.0 / (2.0 * math.pi):.0f} rpm"
    return f"{name} {value:g}" + (f" {unit}" if unit and unit != "-" else "")


def map_lines(
    table: pd.DataFrame, x: str, groups: list[str]
) -> list[tuple[str, dict[str, Any], Any]]:
    """(label, style, row positions sorted by ``x``) of each line of a map of ``table``:
    one line per combination of the ``groups`` columns, colour after the first, line
    style and marker after the others. The same for every quantity of one table: pass it
    to :func:`plot_map` to draw several."""
    # positions, not labels: only the columns that split and sort the lines
    keys = table[list(dict.fromkeys([*groups, x]))].reset_index(drop=True)
    if not groups:
        order = keys.sort_values(x).index.to_numpy()
        return [("", {"color": "C0", "ls": "-", "marker": "o"}, order)]
    first = list(dict.fromkeys(keys[groups[0]]))
    rest: list[tuple[Any, ...]] = []
    out = []
    for key, rows in keys.groupby(groups, sort=False, dropna=False):
        key = key if isinstance(key, tuple) else (key,)
        if key[1:] not in rest:
            rest.append(key[1:])
        colour = first.index(key[0]) % 10
        style = {"color": f"C{colour}", **_style(rest.index(key[1:]))}
        label = ", ".join(_value_label(c, v) for c, v in zip(groups, key, strict=True))
        out.append((label, style, rows.sort_values(x).index.to_numpy()))
    return out


def _style(index: int) -> dict[str, Any]:
    """Line style and marker of the ``index``-th combination of the other group axes:
    distinct pairs for the first 32 (the marker shifts by one every 8)."""
    return {
        "ls": _STYLES[index % len(_STYLES)],
        "marker": _MARKERS[(index + index // len(_MARKERS)) % len(_MARKERS)],
    }


#: More lines than this get a key (a colour per value of the first group axis, a style per
#: combination of the others) instead of a legend entry per line.
MAX_LEGEND_LINES = 12


def legend_entries(table: pd.DataFrame, groups: list[str]) -> tuple[list[Any], list[str]]:
    """Handles and labels of a map's key: a colour per value of the first group axis and
    a line style per combination of the others (used above :data:`MAX_LEGEND_LINES`)."""
    from matplotlib.lines import Line2D

    handles: list[Any] = []
    labels: list[str] = []
    for i, value in enumerate(dict.fromkeys(table[groups[0]])):
        handles.append(Line2D([], [], color=f"C{i % 10}", ls="-"))
        labels.append(_value_label(groups[0], value))
    if len(groups) > 1:
        combos = list(dict.fromkeys(zip(*(table[c] for c in groups[1:]), strict=True)))
        for i, combo in enumerate(combos):
            handles.append(Line2D([], [], color="0.3", ms=4, **_style(i)))
            labels.append(
                ", ".join(_value_label(c, v) for c, v in zip(groups[1:], combo, strict=True))
            )
    return handles, labels


def plot_map(
    table: pd.DataFrame,
    y: str,
    x: str,
    groups: list[str],
    ylabel: str = "",
    ax: Any = None,
    legend: bool = True,
    lines: list[tuple[str, dict[str, Any], Any]] | None = None,
) -> Figure:
    """One quantity against ``x``, a line per combination of the ``groups`` columns
    (their legend in the axes with ``legend``), about five ticks a side; ``lines``:
    :func:`map_lines` of ``table``, found here if not given."""
    if ax is None:
        fig = new_figure(figsize=(7.0, 4.8), layout="constrained")
        ax = fig.add_subplot()
    else:
        fig = ax.figure
    xv = table[x].to_numpy(dtype=float)
    yv = table[y].to_numpy(dtype=float)
    drawn = [
        (label, style, *_display(x, xv[rows]), yv[rows])
        for label, style, rows in (map_lines(table, x, groups) if lines is None else lines)
    ]
    xlabel = drawn[-1][3] if drawn else ""
    if len(drawn) > MAX_LEGEND_LINES:  # a key, no entry per line: no Line2D per line
        lines_as_collections(ax, [(style, xs, ys) for _, style, xs, _, ys in drawn])
    else:
        for label, style, xs, _, ys in drawn:
            ax.plot(xs, ys, label=label or None, ms=4, lw=1.2, **style)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel or y)
    ax.grid(True, alpha=0.3)
    fewer_ticks(ax)
    if groups and legend and len(drawn) > MAX_LEGEND_LINES:
        ax.legend(*legend_entries(table, groups), fontsize=6, ncol=2)
    elif groups and legend:
        ax.legend(fontsize=7, ncol=2 if len(drawn) > 6 else 1)
    return fig


def bearing_columns(table: pd.DataFrame) -> list[str]:
    """The ``bearing_max_<name> [N]`` columns of a summary table that hold a value."""
    return [c for c in table.columns if BEARING_COLUMN.match(str(c)) and table[c].notna().any()]


def plot_bearing_loads(
    table: pd.DataFrame,
    x: str,
    groups: list[str],
    lines: list[tuple[str, dict[str, Any], Any]] | None = None,
) -> Figure | None:
    """Peak load of every bearing against ``x``, a panel per bearing (``None`` if none);
    ``lines`` as in :func:`plot_map`."""
    columns = bearing_columns(table)
    if not columns:
        return None
    ncols = min(3, len(columns))
    nrows = math.ceil(len(columns) / ncols)
    lines = map_lines(table, x, groups) if lines is None else lines
    if len(lines) > MAX_LEGEND_LINES:
        handles, labels = legend_entries(table, groups)
    else:
        handles, labels = [], [label for label, _, _ in lines if label]
    legend_rows = math.ceil(len(labels) / 3) if labels else 0
    legend_height = 0.19 * legend_rows + (0.15 if legend_rows else 0.0)
    # a legend that would take over 40 % of the panels' height gets height of its own
    height = 3.4 * nrows
    height += max(0.0, 0.6 + legend_height - 0.4 * height)
    fig = new_figure(figsize=(4.2 * ncols, height))
    axes = fig.subplots(nrows, ncols, squeeze=False)
    for ax, column in zip(axes.flat, columns, strict=False):
        name = BEARING_COLUMN.match(column).group(1)  # type: ignore[union-attr]
        plot_map(table, column, x, groups, "peak load [N]", ax, legend=False, lines=lines)
        ax.set_title(name.replace("_", " "), y=TITLE_Y)
    for ax in list(axes.flat)[len(columns) :]:
        ax.set_visible(False)
    fig.suptitle("peak bearing loads")
    # one legend for all panels, below them, in fixed margins [inch]: inside a panel it
    # would hide the data, and the constrained layout engine measures every label at
    # every draw
    if not handles:
        handles, labels = axes.flat[0].get_legend_handles_labels()
    width, height = fig.get_size_inches()
    bottom = 0.6 + legend_height
    fig.subplots_adjust(
        left=0.75 / width,
        right=1.0 - 0.2 / width,
        bottom=bottom / height,
        top=1.0 - 0.6 / height,
        wspace=0.3,
        hspace=0.45,
    )
    if labels:
        fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=7, frameon=False)
    return fig


#: Names of the map plots (file ``map_<name>.png``), for :func:`save_map_plots`'s ``only``.
MAP_NAMES = tuple(name[4:-4] for _, _, name in MAP_QUANTITIES) + ("bearing_loads",)


def check_map_names(names: Iterable[str], where: str = "--plots") -> tuple[str, ...]:
    """``names`` checked against :data:`MAP_NAMES`.

    Raises
    ------
    CaseError
        Naming an unknown map plot and the allowed ones.
    """
    names = tuple(names)
    for name in names:
        if name not in MAP_NAMES:
            raise CaseError(where, name, f"unknown map plot; allowed: {', '.join(MAP_NAMES)}")
    return names


def save_map_plots(
    table: pd.DataFrame,
    axes: Sequence[str],
    out_dir: Path,
    only: Collection[str] | None = None,
    progress: Callable[[int], Any] | None = None,
) -> list[Path]:
    """Draw the map plots of a summary table into ``out_dir`` (atomically).

    Parameters
    ----------
    table : pandas.DataFrame
        The sweep's summary table (all points; only ``ok`` ones are drawn).
    axes : sequence of str
        Its axis columns.
    out_dir : Path
        Where the PNG files go.
    only : collection of str, optional
        Draw just these plots (names of :data:`MAP_NAMES`); default all.
    progress : callable, optional
        Given the number of plots to draw, a progress bar (``update()``, ``close()``):
        drawing them takes seconds.

    Returns
    -------
    list of Path
        The files written (none when no point is ``ok`` or nothing numeric varies).
    """
    wanted = set(MAP_NAMES if only is None else check_map_names(only))
    ok = table[table["status"] == "ok"] if "status" in table else table
    if ok.empty:
        return []
    x = x_column(ok, axes)
    if x is None:
        return []
    groups = group_columns(ok, axes, x)
    lines = map_lines(ok, x, groups)  # the same lines in every plot
    written = []
    drawn = [
        (column, label, name)
        for column, label, name in (*MAP_QUANTITIES, ("", "", "map_bearing_loads.png"))
        if name[4:-4] in wanted and (not column or column in ok)
    ]
    bar = progress(len(drawn)) if progress is not None else None
    try:
        for column, label, name in drawn:
            path = _save_map(ok, (x, groups, lines), (column, label), Path(out_dir) / name)
            if path is not None:
                written.append(path)
            if bar is not None:
                bar.update(1)
    finally:
        if bar is not None:
            bar.close()
    return written


def _save_map(
    ok: pd.DataFrame,
    layout: tuple[str, list[str], Any],
    quantity: tuple[str, str],
    path: Path,
) -> Path | None:
    """Draw one map plot (``quantity``: its column and label; the bearing loads' panels
    for an empty column) into ``path``; None where there is nothing to draw."""
    x, groups, lines = layout
    column, label = quantity
    if column:
        ax = single_axes(figsize=(7.0, 4.8))
        fig = plot_map(ok, column, x, groups, ylabel=label, ax=ax, lines=lines)
        ax.set_title(label.rsplit(" [", 1)[0], y=TITLE_Y)
    else:  # panels and a legend below them, in fixed margins
        panels = plot_bearing_loads(ok, x, groups, lines)
        if panels is None:
            return None
        fig = panels
    atomic_write(path, lambda tmp: fig.savefig(tmp, dpi=110, format="png", pil_kwargs=PNG_OPTIONS))
    return path
