"""The report's figures read at a glance: the crank angle every 90 deg and a handful of
labelled ticks on every linear axis."""

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
