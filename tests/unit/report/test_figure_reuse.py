"""Figures drawn in turn on one Axes (the report's one-panel figures, the map plots) are
the figures drawn each on a fresh Axes, pixel for pixel: nothing of one (lines, legend
entries, title, scales, ticks, limits, colours) leaks into the next."""

from __future__ import annotations

import numpy as np
import pytest

from helpers import REFERENCE


@pytest.fixture(scope="module")
def cycle():
    from recipsim.case.load import load_case
    from recipsim.pipeline import simulate_case

    return simulate_case(load_case(REFERENCE), []).cycle


def _pixels(fig) -> np.ndarray:
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    return np.asarray(canvas.buffer_rgba()).copy()


def _one_panel_makers(cycle):
    from recipsim.report.plotting import _figure_makers

    return {
        name: make for name, kind, make in _figure_makers(cycle, (1.2e5, 1.5e6)) if kind == "single"
    }


def _shared_and_fresh(makers, order):
    """Each figure of ``order`` drawn in turn on one shared Axes, and on its own."""
    from recipsim.report.figure_kit import clear_axes
    from recipsim.report.plotting import single_axes

    shared = single_axes()
    for index, name in enumerate(order):
        if index:
            clear_axes(shared)
        fig = makers[name](shared)
        yield name, shared, _pixels(fig), _pixels(makers[name](single_axes()))


@pytest.mark.parametrize("order", [("p_V", "p_V_loglog", "p_theta", "torque"),
                                   ("torque", "p_theta", "p_V_loglog", "p_V")])  # fmt: skip
def test_one_panel_figures_on_a_shared_axes_are_the_fresh_figures(cycle, order) -> None:
    makers = _one_panel_makers(cycle)
    assert set(order) == set(makers)
    shared = None
    for name, axes, reused, fresh in _shared_and_fresh(makers, order):
        assert reused.shape == fresh.shape
        assert np.array_equal(reused, fresh), name
        shared = axes
    assert shared is not None
    # the last figure's artists are its own: p_V has a single line and no legend,
    # the torques three lines, the zero line and their legend
    if name == "p_V":
        assert len(shared.get_lines()) == 1 and shared.get_legend() is None
    else:
        labels = [t.get_text() for t in shared.get_legend().get_texts()]
        assert labels == ["driving torque", "gas torque", "inertia torque"]
        assert len(shared.get_lines()) == 4


def test_report_figures_read_at_a_glance(cycle) -> None:
    """The crank angle every 90 deg, at most six labelled ticks on a linear axis."""
    from recipsim.report.plotting import plot_pressure, plot_pv, plot_torque, plot_valves

    for fig in (plot_pressure(cycle), plot_torque(cycle), plot_valves(cycle)):
        _pixels(fig)
        angle = fig.axes[0].xaxis
        assert list(angle.get_majorticklocs()) == [0.0, 90.0, 180.0, 270.0, 360.0]
        for ax in fig.axes:
            visible = [
                t for t in ax.yaxis.get_majorticklocs() if ax.get_ylim()[0] <= t <= ax.get_ylim()[1]
            ]
            assert 3 <= len(visible) <= 6
    fig = plot_pv(cycle)
    _pixels(fig)
    assert 3 <= len(fig.axes[0].get_xticks()) <= 7
