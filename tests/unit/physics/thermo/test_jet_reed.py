"""The jet reed (``options.valves = "jet_reed"``): its force is the momentum balance of the
port's jet, A_p (dp + q_p); its force coefficient 1 + (A_e/A_p)^2 in the incompressible
limit, 1 at small lift (the static reed law) and 2 for a free jet on a disk."""

import math

import numpy as np
import pytest

from helpers import REFERENCE
from recipsim.case.load import load_case
from recipsim.model.build import build_model, scenes
from recipsim.physics.thermo import cylinder as cyl
from recipsim.physics.thermo.flow import regularised_mass_flux
from recipsim.physics.thermo.jet_reed import JET_REED, force_coefficient, jet_reed_force
from recipsim.physics.thermo.properties import STATUS_OK
from recipsim.physics.thermo.valve_models import VALVE_MODELS, moves_reeds

JET = ["options.valves=jet_reed"]


def _discharge_rhs(overrides: list[str], lift: float) -> np.ndarray:
    """Outputs of the rigid-crank right-hand side with the discharge reed free at
    ``lift`` and the gas at 370 K, 75 kg/m3 (about 17 bar, above the 14.7 bar plenum)."""
    model = build_model(load_case(REFERENCE, overrides)).for_solve()
    y = model.y0.copy()
    y[cyl.Y_T], y[cyl.Y_RHO], y[cyl.Y_XD] = 370.0, 75.0, lift
    mode = np.array([0, 1], dtype=np.int64)
    aux = np.zeros(scenes.N_AUX)
    status = scenes.scene_rhs(
        0.0, y, mode, model.par, model.ipar, model.props, model.props.buffer, np.zeros_like(y), aux
    )
    assert status == STATUS_OK
    return aux


def test_the_registry_lists_the_jet_reed_as_a_moving_reed():
    assert VALVE_MODELS[JET_REED.name] is JET_REED
    assert JET_REED.moves_reeds and moves_reeds(JET_REED.code)
    assert load_case(REFERENCE, JET).options.valves == JET_REED.name


@pytest.mark.parametrize("lift", [0.05e-3, 0.3e-3, 1.0e-3])
def test_rhs_force_is_the_momentum_balance_and_the_flow_is_the_reeds(lift):
    """Against the reed model at the same state: the same mass flow (same flow area),
    and the opening force A_p (dp + mdot^2/(2 rho A_p^2)) - preload, to rounding."""
    reed = _discharge_rhs([], lift)
    jet = _discharge_rhs(JET, lift)
    assert jet[cyl.A_MDOT_DIS] == reed[cyl.A_MDOT_DIS] > 0.0
    case = load_case(REFERENCE, JET)
    valve = case.valves.discharge
    p, rho, mdot = jet[cyl.A_PRESSURE], jet[cyl.A_DENSITY], jet[cyl.A_MDOT_DIS]
    dp = p - case.operating_point.discharge_pressure
    area = valve.port_area
    expected = area * (dp + mdot**2 / (2.0 * rho * area**2)) - valve.preload
    assert jet[cyl.A_FORCE_REED_D] == pytest.approx(expected, rel=1e-12)


def test_without_flow_the_force_is_the_static_reed_law_over_the_port():
    """Seated (no flow), the opening force is dp A_p - preload: the reed law with a
    force coefficient of 1."""
    area = 0.25 * math.pi * 4e-3**2
    assert jet_reed_force(2e5, 0.0, 60.0, 4e-3, 0.5) == pytest.approx(2e5 * area - 0.5, rel=1e-15)


@pytest.mark.parametrize("lift", [0.1e-3, 0.5e-3, 0.8e-3, 2e-3])
@pytest.mark.parametrize("flow_coefficient", [0.8, 1.0])
def test_incompressible_force_coefficient_is_one_plus_the_area_ratio_squared(
    lift, flow_coefficient
):
    """With the compiled nozzle flux at dp/p = 1e-4 (laminar branch off),
    F/(dp A_p) = 1 + (A_e/A_p)^2; 2 for a loss-free port wide open, the momentum balance
    of a free jet on a disk (rho V^2 A = 2 dp A). Tolerance 1e-3: the compressible flux
    differs from the incompressible one by O(dp/p) = 1e-4."""
    d_port, d_curtain, p_up, rho = 4e-3, 4e-3, 2e6, 80.0
    dp = 1e-4 * p_up
    port = 0.25 * math.pi * d_port**2
    effective = flow_coefficient * min(math.pi * d_curtain * lift, port)
    mdot = effective * regularised_mass_flux(p_up, rho, p_up - dp, 1.1, 0.0)
    force = jet_reed_force(dp, mdot, rho, d_port, 0.0)
    closed = force_coefficient(lift, d_port, d_curtain, flow_coefficient)
    assert closed == pytest.approx(1.0 + (effective / port) ** 2, rel=1e-15)
    assert force / (dp * port) == pytest.approx(closed, rel=1e-3)
    if flow_coefficient == 1.0 and lift >= d_port / 4.0:
        assert force / (dp * port) == pytest.approx(2.0, rel=1e-3)


def test_back_flow_pushes_the_reed_shut():
    """Flow against the opening direction adds its dynamic head to the closing side."""
    area = 0.25 * math.pi * 4e-3**2
    closing = jet_reed_force(-1e4, -2e-3, 60.0, 4e-3, 0.0)
    assert closing < -1e4 * area < 0.0
