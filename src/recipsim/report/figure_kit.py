"""What makes the report's figures and map plots cheap to draw: fewer tick objects, and
one Axes drawn on in turn by figures of the same layout, many lines drawn as a few
collections.

Drawing a figure is mostly its axes: every tick is three lines and two texts, created
anew for every new Axes, and every tick label is laid out and rendered glyph by glyph.
Explicit locators keep the ticks an engineer reads (about five a side instead of up to
ten; the crank angle every 90 deg), and :func:`clear_axes` lets figures of one layout
share an Axes, its tick objects and its canvas's text cache instead of building them
for each figure.
"""

from __future__ import annotations

from typing import Any

import numpy as np

#: PNG compression of the report's figures: zlib level 1 writes a figure in a third of
#: the default level's time (6) for files about 20 % larger.
PNG_OPTIONS = {"compress_level": 1}

#: Most intervals between the major ticks of a linear axis.
NBINS = 5

#: Tick steps allowed, times a power of ten: round numbers, no 1.5, 3, 6 or 8.
STEPS = (1.0, 2.0, 2.5, 4.0, 5.0, 10.0)

#: Ticks of a crank angle axis [deg]: every 90 deg from TDC over one revolution.
ANGLE_TICKS = np.arange(0.0, 361.0, 90.0)


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


def clear_axes(ax: Any) -> None:
    """Make ``ax`` as it was when created, keeping its tick objects, for the next figure
    of the same layout: its data artists, legend, title, axis labels, scales (and so
    locators and formatters), limits, grid and colour cycle are reset.

    Cheaper than ``Axes.clear``, which rebuilds the axes and their ticks. The plotting
    functions drawn in turn on one Axes must set what they use (title position and
    size, ticks) themselves; the tests compare such figures with fresh ones pixel by
    pixel.
    """
    from matplotlib import rcParams
    from matplotlib.transforms import Bbox

    for artist in (*ax.lines, *ax.patches, *ax.texts, *ax.collections, *ax.images):
        artist.remove()
    if ax.get_legend() is not None:
        ax.get_legend().remove()
    ax.set_xscale("linear")
    ax.set_yscale("linear")
    ax.dataLim.set(Bbox.null())
    ax.ignore_existing_data_limits = True
    ax.set_autoscale_on(True)
    ax.set_prop_cycle(None)
    ax.set_title("")
    ax.set_xlabel("")
    ax.set_ylabel("")
    ax.grid(False, which="both")
    ax.tick_params(which="both", grid_alpha=rcParams["grid.alpha"])


def lines_as_collections(ax: Any, lines: list[tuple[dict[str, Any], Any, Any]]) -> None:
    """Lines of ``(style, x, y)`` (style: ``color``, ``ls``, ``marker``) drawn as one
    line collection and a marker collection per marker shape, as
    :meth:`~matplotlib.axes.Axes.plot` would draw each (width 1.2, markers of size 4 in
    the line's colour), the markers over the lines; no legend entries.

    A map of 1000 points has 100 lines a panel: a Line2D each cost about 2 ms to make
    and draw, 0.2 s a one-panel map plot and 0.7 s the six panels of its bearing loads.
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
