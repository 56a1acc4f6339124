"""Shared look of the report's figures and map plots: the ticks an engineer reads (about
five a side, the crank angle every 90 deg), PNG options, and many lines of a map drawn
as a few collections.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: PNG compression of the report's figures (zlib level 1: fast, files slightly larger).
PNG_OPTIONS = {"compress_level": 1}

#: Most intervals between the major ticks of a linear axis.
NBINS = 5

#: Tick steps allowed, times a power of ten: round numbers, no 1.5, 3, 6 or 8.
STEPS = (1.0, 2.0, 2.5, 4.0, 5.0, 10.0)

#: Ticks of a crank angle axis [deg]: every 90 deg from TDC over one revolution.
ANGLE_TICKS = np.arange(0.0, 361.0, 90.0)


def new_figure(**options: Any) -> Figure:
    """A new :class:`matplotlib.figure.Figure` (``options`` as it takes them), outside
    pyplot: no backend chosen, no global registry. matplotlib is imported here, when a
    figure is drawn, so that runs without figures never load it."""
    from matplotlib.figure import Figure

    return Figure(**options)


def fewer_ticks(ax: Any, x: bool = True, y: bool = True, nbins: int = NBINS) -> None:
    """At most ``nbins`` + 1 major ticks on the linear ``x`` / ``y`` axes of ``ax`` (log
    axes and axes with fixed ticks are left alone)."""
    from matplotlib.ticker import MaxNLocator

    for axis, wanted in ((ax.xaxis, x), (ax.yaxis, y)):
        if wanted and axis.get_scale() == "linear" and axis.isDefault_majloc:
            axis.set_major_locator(MaxNLocator(nbins=nbins, steps=STEPS))


def angle_axis(ax: Any) -> None:
    """Crank angle axis of ``ax``: 0-360 deg, a tick every 90 deg."""
    ax.set_xlim(0.0, 360.0)
    ax.set_xticks(ANGLE_TICKS)


def lines_as_collections(ax: Any, lines: list[tuple[dict[str, Any], Any, Any]]) -> None:
    """Lines of ``(style, x, y)`` (style: ``color``, ``ls``, ``marker``) drawn as one
    line collection and a marker collection per marker shape, as
    :meth:`~matplotlib.axes.Axes.plot` would draw each (width 1.2, markers of size 4 in
    the line's colour), the markers over the lines; no legend entries: a map of
    thousands of points draws its hundred lines a panel as one artist.
    """
    from matplotlib.collections import LineCollection
    from matplotlib.colors import to_rgba_array

    segments = [np.column_stack([xs, ys]) for _, xs, ys in lines]
    colours = to_rgba_array([style["color"] for style, _, _ in lines])  # once a line
    ax.add_collection(
        LineCollection(
            segments,
            colors=colours,
            linestyles=[style["ls"] for style, _, _ in lines],
            linewidths=1.2,
            zorder=2,
        )
    )
    by_marker: dict[str, list[int]] = {}
    for index, (style, _, _) in enumerate(lines):
        by_marker.setdefault(style["marker"], []).append(index)
    for marker, indices in by_marker.items():
        points = np.concatenate([segments[i] for i in indices])
        finite = np.isfinite(points).all(axis=1)
        colour_of_point = np.repeat(colours[indices], [len(segments[i]) for i in indices], axis=0)
        ax.scatter(
            points[finite, 0],
            points[finite, 1],
            s=16.0,  # points^2: a Line2D marker of size 4
            marker=marker,
            c=colour_of_point[finite],
            linewidths=1.0,
            zorder=2.01,
        )
    ax.autoscale_view()
