"""Map plots on synthetic summary tables: lines per group, bearing loads when present."""

from __future__ import annotations

import numpy as np
import pandas as pd

from recipsim.studies.sweep.plots import (
    bearing_columns,
    group_columns,
    plot_map,
    save_map_plots,
    x_column,
)

AXES = ["refrigerant", "condensing_temperature [K]", "evaporating_temperature [K]"]
BEARINGS = ("primary", "secondary", "eccentric", "pin", "piston_top", "piston_skirt")


def synthetic(bearings: bool) -> pd.DataFrame:
    rows = []
    for refrigerant, scale in (("R134a", 1.0), ("R600a", 0.6)):
        for condensing in (318.15, 328.15):
            for evaporating in (238.15, 243.15, 248.15):
                capacity = scale * 10.0 * (evaporating - 200.0) - (condensing - 300.0)
                row = {
                    "point": len(rows),
                    "refrigerant": refrigerant,
                    "condensing_temperature [K]": condensing,
                    "evaporating_temperature [K]": evaporating,
                    "status": "ok",
                    "cooling_capacity [W]": capacity,
                    "shaft_power [W]": capacity / 2.0,
                    "COP [-]": 2.0,
                    "volumetric_efficiency [-]": 0.8,
                    "isentropic_efficiency [-]": 0.7,
                }
                if bearings:
                    for i, name in enumerate(BEARINGS):
                        row[f"bearing_max_{name} [N]"] = 100.0 * (i + 1) + capacity
                rows.append(row)
    table = pd.DataFrame(rows)
    table.loc[3, "status"] = "failed"
    table.loc[3, "cooling_capacity [W]"] = np.nan
    return table


def test_lines_per_refrigerant_and_condensing_temperature():
    table = synthetic(bearings=False)
    ok = table[table["status"] == "ok"]
    x = x_column(ok, AXES)
    assert x == "evaporating_temperature [K]"
    groups = group_columns(ok, AXES, x)
    assert groups == ["refrigerant", "condensing_temperature [K]"]
    fig = plot_map(ok, "cooling_capacity [W]", x, groups)
    lines = fig.axes[0].get_lines()
    assert len(lines) == 4
    labels = [line.get_label() for line in lines]
    assert labels == [
        "R134a, condensing 45 °C",
        "R134a, condensing 55 °C",
        "R600a, condensing 45 °C",
        "R600a, condensing 55 °C",
    ]
    # x in degrees Celsius, sorted; the failed point is not drawn
    np.testing.assert_allclose(lines[0].get_xdata(), [-35.0, -30.0, -25.0])
    assert len(lines[1].get_xdata()) == 2
    # colour per refrigerant, line style per condensing temperature
    assert lines[0].get_color() == lines[1].get_color() != lines[2].get_color()
    assert lines[0].get_linestyle() != lines[1].get_linestyle()
    assert lines[0].get_linestyle() == lines[2].get_linestyle()


def test_bearing_load_plot_only_with_bearing_columns(tmp_path):
    plain = save_map_plots(synthetic(bearings=False), AXES, tmp_path / "plain")
    assert sorted(p.name for p in plain) == [
        "map_COP.png",
        "map_cooling_capacity.png",
        "map_isentropic_efficiency.png",
        "map_shaft_power.png",
        "map_volumetric_efficiency.png",
    ]
    table = synthetic(bearings=True)
    assert bearing_columns(table) == [f"bearing_max_{n} [N]" for n in BEARINGS]
    flexible = save_map_plots(table, AXES, tmp_path / "flexible")
    bearing = tmp_path / "flexible" / "map_bearing_loads.png"
    assert bearing in flexible and bearing.stat().st_size > 20_000
    assert not list((tmp_path / "flexible").glob(".*"))  # no temporary files left
    # columns without a value (a rigid-crank sweep that does not fill them) are skipped
    empty = synthetic(bearings=False)
    empty["bearing_max_primary [N]"] = np.nan
    assert bearing_columns(empty) == []


def test_no_plots_without_a_converged_point(tmp_path):
    table = synthetic(bearings=False)
    table["status"] = "invalid"
    assert save_map_plots(table, AXES, tmp_path) == []
    assert not list(tmp_path.iterdir())


def large_map(bearings: bool) -> tuple[pd.DataFrame, list[str]]:
    """10 condensing temperatures x 10 speeds x 3 evaporating temperatures: 100 lines
    (the layout of ``throughput_1000``, whose bearing-load plot once failed with
    "bottom cannot be >= top": a legend entry per line took more than the figure)."""
    rows = []
    for condensing in np.linspace(308.15, 330.65, 10):
        for speed in np.linspace(209.4, 586.4, 10):
            for evaporating in (238.15, 243.15, 248.15):
                row = {
                    "condensing_temperature [K]": condensing,
                    "shaft_speed [rad/s]": speed,
                    "evaporating_temperature [K]": evaporating,
                    "status": "ok",
                    "cooling_capacity [W]": speed * (evaporating - 200.0) / (condensing - 250.0),
                }
                if bearings:
                    for i, name in enumerate(BEARINGS):
                        row[f"bearing_max_{name} [N]"] = 100.0 * (i + 1) + speed
                rows.append(row)
    return pd.DataFrame(rows), [
        "condensing_temperature [K]",
        "shaft_speed [rad/s]",
        "evaporating_temperature [K]",
    ]


def test_many_lines_get_a_key_instead_of_a_legend_entry_each(tmp_path):
    table, axes = large_map(bearings=True)
    x = x_column(table, axes)
    groups = group_columns(table, axes, x)
    fig = plot_map(table, "cooling_capacity [W]", x, groups)
    # drawn as collections: the 100 lines in one, the markers in one per marker shape
    ax = fig.axes[0]
    assert not ax.get_lines()
    lines, *markers = ax.collections
    assert len(lines.get_segments()) == 100
    assert sum(len(m.get_offsets()) for m in markers) == len(table)
    assert len(markers) == 8  # the ten speeds' markers: eight shapes
    by_line = table.sort_values(x).groupby(groups, sort=False)
    first = next(iter(by_line))[1]  # the first line's points, in degrees Celsius
    np.testing.assert_allclose(lines.get_segments()[0][:, 0], first[x] - 273.15)
    np.testing.assert_allclose(lines.get_segments()[0][:, 1], first["cooling_capacity [W]"])
    # each line in its colour (a colour per condensing temperature), its markers too
    from matplotlib.colors import to_rgba

    colours = lines.get_colors()
    assert len(colours) == 100 and tuple(colours[0]) == to_rgba("C0")
    assert {tuple(c) for m in markers for c in m.get_facecolors()} == {
        to_rgba(f"C{i}") for i in range(10)
    }
    texts = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    # a colour per condensing temperature, a style per speed: 20 entries, not 100
    assert len(texts) == 20
    assert texts[0] == "condensing 35 °C" and texts[10] == "shaft speed 2000 rpm"
    # the ten speeds' styles are all different (line style and marker together)
    handles = fig.axes[0].get_legend().legend_handles
    styles = {(h.get_linestyle(), h.get_marker()) for h in handles[10:]}
    assert len(styles) == 10
    written = save_map_plots(table, axes, tmp_path)
    assert tmp_path / "map_bearing_loads.png" in written


def _pixels(fig) -> np.ndarray:
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    return np.asarray(canvas.buffer_rgba()).copy()
