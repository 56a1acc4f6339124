"""One sign convention for torques in every report (reports/README.md, "Torques").

A torque on the crankshaft is positive along the rotation. The gas torque is the torque
of the gas force on the crank: negative while the piston compresses (crank angle 180 to
360 deg from top dead centre, the piston rising), positive while the clearance gas
re-expands; the driving torque is positive on average; inertia = driving + gas.

The pinned crank computes the gas torque as ``(p - p_shell) A dx/dtheta``; the flexible
crank train as the gas power on the piston over the crank speed. Under the same pressure
the two differ only by the bearing deflections (micrometres against a 9.2 mm crank
radius) and the speed ripple, so their curves must correlate almost perfectly: the
threshold 0.9 of the brief leaves room for the motor-driven speed ripple of the coupled
case; a flipped sign gives -1.
"""

from __future__ import annotations

import numpy as np
import pytest

import recipsim
from helpers import CASES, REFERENCE

PAPER = CASES / "paper_tabulated.toml"
PINNED = {"options.mechanics": "pinned", "options.drive": "constant_speed"}
GAS = "gas_torque [N m]"
SHAFT = "shaft_torque [N m]"
INERTIA = "inertia_torque [N m]"


@pytest.fixture(scope="module")
def cycles():
    """Cycle tables of one point four ways: the tabulated curve on the pinned and the
    flexible crank, the cylinder on the rigid crank and coupled to the flexible one."""
    runs = {
        "tabulated pinned": recipsim.load_case(PAPER, PINNED),
        "tabulated flexible": recipsim.load_case(PAPER),
        "cylinder pinned": recipsim.load_case(REFERENCE),
        "cylinder coupled": recipsim.load_case("reference_r134a_lbp_coupled"),
    }
    return {label: recipsim.simulate(case).cycle for label, case in runs.items()}


def _compressing(cycle):
    angle = cycle["crank_angle [deg]"].to_numpy()
    pressure = cycle["cylinder_pressure [Pa]"].to_numpy()
    rising = (angle > 200.0) & (angle < 340.0)  # the piston rises, the gas is compressed
    return rising & (pressure > 1.5 * pressure.min())


@pytest.mark.parametrize(
    "label", ["tabulated pinned", "tabulated flexible", "cylinder pinned", "cylinder coupled"]
)
def test_signs_of_every_report(cycles, label):
    cycle = cycles[label]
    gas = cycle[GAS].to_numpy()
    assert (gas[_compressing(cycle)] < 0.0).all()  # the gas resists compression
    assert cycle[SHAFT].mean() > 0.0  # the drive supplies the work
    # the gas takes energy from the crank over a revolution: mean gas torque < 0
    assert gas.mean() < 0.0
    # inertia = driving + gas, to round-off (1e-9 of the peak driving torque)
    scale = np.abs(cycle[SHAFT].to_numpy()).max()
    residual = cycle[INERTIA].to_numpy() - cycle[SHAFT].to_numpy() - gas
    assert np.abs(residual).max() < 1e-9 * scale


@pytest.mark.parametrize(
    ("pinned", "flexible"),
    [("tabulated pinned", "tabulated flexible"), ("cylinder pinned", "cylinder coupled")],
)
def test_pinned_and_flexible_gas_torques_agree_in_shape(cycles, pinned, flexible):
    a = cycles[pinned][GAS].to_numpy()
    b = cycles[flexible][GAS].to_numpy()
    assert len(a) == len(b)
    assert np.corrcoef(a, b)[0, 1] > 0.9


def test_plot_titles_say_what_was_run(tmp_path):
    """Every report figure is headed by the case, the crank, the drive and the pressure."""
    from recipsim.report.case_report import run_title
    from recipsim.report.plotting import save_cycle_figures

    case = recipsim.load_case(PAPER, PINNED)
    result = recipsim.simulate(case)
    title = run_title(result.summary.to_dict())
    assert title == "paper_tabulated: pinned crank, constant_speed, tabulated pressure"
    names = save_cycle_figures(result.cycle, tmp_path, title=title)
    assert "torque.png" in names and (tmp_path / "torque.png").stat().st_size > 0
