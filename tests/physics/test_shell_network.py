"""Shell thermal network: closed forms, limits, balances, the coupled cycle, trends."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq, fsolve

import recipsim
from recipsim.errors import CaseError
from recipsim.physics.thermo.fluid import Fluid
from recipsim.physics.thermo.shell_network import (
    DM,
    LINK_NAMES,
    NODES,
    OIL,
    SH,
    SM,
    NetworkLoads,
    NetworkParameters,
    NetworkPressures,
    node_residuals,
    solve_network,
)
from recipsim.pipeline import simulate_case

T_AMB = 305.35
#: The reference compressor with R600a as the ideal machine (what ``r600a_lbp`` was before
#: it became the real compressor): each test switches on only the parts it studies.
R600A_IDEAL = "reference_r134a_lbp_ideal"
R600A = {"refrigerant": "R600a"}
P_SUC, P_DIS = 62938.6, 762002.4  # R600a at -23.3 C / 54.4 C [Pa]
PRESSURES = NetworkPressures(P_SUC, 305.35, (P_SUC, P_SUC, P_DIS, P_DIS))


@pytest.fixture(scope="module")
def isobutane() -> Fluid:
    return Fluid("IsoButane")


def _parameters(ua: dict[str, float], shell_ambient: float, direct: float = 1.0, phi: float = 0.0):
    return NetworkParameters(
        conductances=tuple(ua.get(name, 0.0) for name in LINK_NAMES),
        shell_ambient=shell_ambient,
        ambient_temperature=T_AMB,
        direct_suction_fraction=direct,
        friction_wall_fraction=phi,
    )


def _loads(m=0.0, h_dis=0.0, friction=0.0, motor=0.0, back=(0.0, 0.0), leak=(0.0, 0.0)):
    return NetworkLoads(m, leak[0], back[0], back[1], m * h_dis, leak[1], 0.0, motor, friction)


def test_two_solid_nodes_against_their_closed_form(isobutane):
    """Friction F in the oil, oil -> shell (U1), shell -> ambient (U2), everything else
    unlinked: T_shell = T_amb + F / U2, T_oil = T_shell + F / U1. The unlinked nodes keep
    1e-9 W/K floor links, which move the answer by ~1e-9 K: 1e-6 K asserted."""
    u1, u2, friction = 3.0, 1.5, 12.0
    par = _parameters({"oil_shell": u1}, u2)
    sol = solve_network(par, _loads(friction=friction), PRESSURES, isobutane.enthalpy_pt)
    t_shell = T_AMB + friction / u2
    assert sol.temperature[SH] == pytest.approx(t_shell, abs=1e-6)
    assert sol.temperature[OIL] == pytest.approx(t_shell + friction / u1, abs=1e-6)
    assert sol.shell_heat_rejection == pytest.approx(friction, rel=1e-9)


def test_suction_muffler_heated_by_the_shell_against_a_real_gas_root(isobutane):
    """Suction muffler (flow M from the inlet) joined by UA to a shell gas tied to the
    ambient through very large conductances: h(p, T_sm) = h_in + UA (T_amb' - T_sm) / M,
    solved independently by brentq on the HEOS enthalpy. Newton stops at 1e-6 K and the
    shell gas sits 2e-6 K from the ambient with these links: 1e-4 K asserted."""
    m, ua, t_in = 4.3e-4, 0.8, 260.0
    par = _parameters({"suction_muffler_shell_gas": ua, "shell_gas_shell": 1e6}, 1e6)
    pressures = NetworkPressures(P_SUC, t_in, PRESSURES.node)
    sol = solve_network(par, _loads(m=m, h_dis=8e5), pressures, isobutane.enthalpy_pt)
    h_in = isobutane.enthalpy_pt(P_SUC, t_in)[0]

    def balance(t: float) -> float:
        return m * (h_in - isobutane.enthalpy_pt(P_SUC, t)[0]) + ua * (T_AMB - t)

    assert sol.temperature[SM] == pytest.approx(brentq(balance, t_in, T_AMB), abs=1e-4)


def test_discharge_line_heats_the_suction_muffler_against_a_real_gas_root(isobutane):
    """The discharge muffler joined to the suction muffler alone (the line routed along
    it), direct suction: ``M (h_in - h_sm) + UA (T_dm - T_sm) = 0`` at the suction
    pressure and ``M (h_dis - h_dm) + UA (T_sm - T_dm) = 0`` at the discharge pressure,
    solved independently by fsolve on the HEOS enthalpies. The 1e-9 W/K floor links and
    Newton's 1e-6 K: 1e-4 K asserted."""
    m, ua, t_in, t_dis = 4.3e-4, 0.3, 260.0, 360.0
    par = _parameters({"discharge_muffler_suction_muffler": ua}, 1.5)
    pressures = NetworkPressures(P_SUC, t_in, PRESSURES.node)
    h_dis = isobutane.enthalpy_pt(P_DIS, t_dis)[0]
    sol = solve_network(par, _loads(m=m, h_dis=h_dis), pressures, isobutane.enthalpy_pt)
    h_in = isobutane.enthalpy_pt(P_SUC, t_in)[0]

    def balances(t: np.ndarray) -> list[float]:
        t_sm, t_dm = t
        heat = ua * (t_dm - t_sm)
        return [
            m * (h_in - isobutane.enthalpy_pt(P_SUC, t_sm)[0]) + heat,
            m * (h_dis - isobutane.enthalpy_pt(P_DIS, t_dm)[0]) - heat,
        ]

    t_sm, t_dm = fsolve(balances, [t_in + 10.0, t_dis - 10.0], xtol=1e-12)
    assert sol.temperature[SM] == pytest.approx(t_sm, abs=1e-4)
    assert sol.temperature[DM] == pytest.approx(t_dm, abs=1e-4)
    assert sol.temperature[SM] > t_in + 1.0  # the link carries heat (not a no-op)


def test_no_internal_conductance_is_the_adiabatic_limit(isobutane):
    """All UA -> 0 but the shell's: the muffler gas is the inlet gas mixed with the
    suction back-flow, the outlet carries exactly the discharged enthalpy, the shell
    rejects nothing and the compressor closes on the gas alone. Tolerances: the 1e-9 W/K
    floors over ~100 K (1e-7 W) and Newton's 1e-6 K."""
    m, h_dis, m_back, h_back = 4.3e-4, 7.7e5, 4e-6, 4e-6 * 6.9e5
    par = _parameters({}, 1.5, direct=0.5)
    loads = _loads(m=m, h_dis=h_dis, back=(m_back, h_back))
    sol = solve_network(par, loads, PRESSURES, isobutane.enthalpy_pt)
    h_in = sol.inlet_enthalpy
    h_mixed = (m * h_in + h_back) / (m + m_back)
    assert sol.enthalpy[SM] == pytest.approx(h_mixed, abs=0.01)
    assert sol.outlet_enthalpy == pytest.approx(h_dis, abs=0.01)
    assert abs(sol.shell_heat_rejection) < 1e-6
    assert sol.temperature[SH] == pytest.approx(T_AMB, abs=1e-6)


@pytest.fixture(scope="module")
def network_run():
    case = recipsim.load_case(
        R600A_IDEAL,
        {
            **R600A,
            "options.thermal": "network",
            "thermal.motor_loss_power": "20 W",
            "thermal.friction_power": "8 W",
        },
    )
    return simulate_case(case)


def test_every_node_balances_against_the_converged_revolution(network_run):
    """Each node's balance, term by term (independent of the Newton that solved it),
    with the converged revolution's own flows: the brief asks 1e-3 of the largest flow
    through the node (measured 1e-4: the network moves by less than the cycle
    tolerance between the last two revolutions)."""
    assert network_run.row["converged [-]"]
    coupling = network_run.solution.model.thermal
    res = node_residuals(coupling.parameters, coupling.last_loads, coupling.applied.solution)
    assert res.shape == (len(NODES),)
    assert float(np.max(res)) < 1e-3
    assert network_run.row["thermal_balance_residual [-]"] == pytest.approx(float(np.max(res)))


def test_whole_compressor_energy_closes(network_run):
    """Input (indicated + friction + motor loss, set by hand: 28 W) = delivered flow x
    (h_outlet - h_inlet) + shell heat, within the issue's 0.5 % (measured ~3e-4: the
    cycle's own energy residual and the last revolution's change)."""
    row = network_run.row
    coupling = network_run.solution.model.thermal
    net = coupling.applied.solution
    m = row["discharge_mass_flow [kg/s]"]
    p_in = row["indicated_power [W]"] + 28.0
    out = m * (net.outlet_enthalpy - net.inlet_enthalpy) + row["shell_heat_rejection [W]"]
    assert abs(p_in - out) / p_in < 5e-3
    assert abs(row["thermal_energy_balance_residual [-]"]) < 5e-3
    # the sources went where the table says: the motor is the hottest solid
    assert row["node_temperature_motor [K]"] > row["node_temperature_shell [K]"]
    assert row["shell_heat_rejection [W]"] > 28.0  # the losses leave through the shell


def test_fixed_wall_ignores_the_network_table_bit_for_bit():
    """``fixed_wall`` (the default) reproduces today's results: a [thermal] table with
    every value changed changes nothing; the cylinder inlet is the line state."""
    base = recipsim.load_case(R600A_IDEAL, R600A)
    other = base.with_(
        {
            "options.thermal": "fixed_wall",
            "thermal.ua_shell_ambient": "5 W/K",
            "thermal.suction_muffler_loss_coefficient": 3.0,
            "thermal.motor_loss_power": "40 W",
        }
    )
    a, b = simulate_case(base).row, simulate_case(other).row
    for key, value in a.items():
        if key == "wall_time [s]":
            continue
        same = value == b[key] or (
            isinstance(value, float) and math.isnan(value) and math.isnan(b[key])
        )
        assert same, key
    assert a["cylinder_inlet_temperature [K]"] == base.operating_point.suction_temperature
    assert math.isnan(a["shell_heat_rejection [W]"])


def test_suction_heating_rises_as_evaporation_falls():
    """R600a household point, condensing 54.4 C, motor and friction losses set by hand
    (20 W, 8 W): less flow carries the shell's heat at lower evaporating temperature, so
    the gas is heated more on its way to the cylinder (the trend issue 16 asks). -35 C is
    left out: the reference compressor delivers almost nothing there (volumetric
    efficiency 0.02 with the fixed wall already) and the coupled run does not converge."""
    heating = []
    for t_evap in ("-30 degC", "-25 degC", "-10 degC"):
        case = recipsim.load_case(
            R600A_IDEAL,
            {
                **R600A,
                "options.thermal": "network",
                "operating_point.evaporating_temperature": t_evap,
                "thermal.motor_loss_power": "20 W",
                "thermal.friction_power": "8 W",
            },
        )
        row = simulate_case(case).row
        assert row["converged [-]"]
        heating.append(row["cylinder_inlet_temperature [K]"] - row["suction_temperature [K]"])
    assert heating[0] > heating[1] > heating[2] > 0.0


def test_muffler_pressure_drops_move_the_plenums():
    """K rho v^2 / 2 with the mean flows: the suction plenum sits below the line by
    K M^2 / (2 rho A^2) at the muffler gas density, the discharge plenum above it at the
    discharge chamber's. The drops use the previous revolution's density and flow:
    1e-3 of the drop asserted."""
    k_s, k_d = 2.0, 2.0
    case = recipsim.load_case(
        R600A_IDEAL,
        {
            **R600A,
            "options.thermal": "network",
            "thermal.suction_muffler_loss_coefficient": k_s,
            "thermal.discharge_muffler_loss_coefficient": k_d,
        },
    )
    run = simulate_case(case)
    row, th, op = run.row, case.thermal, case.operating_point
    fluid = run.solution.model.fluid
    m = row["discharge_mass_flow [kg/s]"]
    rho_s = fluid.enthalpy_pt(
        row["suction_plenum_pressure [Pa]"], row["cylinder_inlet_temperature [K]"]
    )[2]
    rho_d = run.solution.model.discharge.density
    dp_s = k_s * m * m / (2.0 * rho_s * th.suction_muffler_flow_area**2)
    dp_d = k_d * m * m / (2.0 * rho_d * th.discharge_muffler_flow_area**2)
    assert dp_s > 50.0 and dp_d > 50.0  # the check below is not vacuous
    assert op.suction_pressure - row["suction_plenum_pressure [Pa]"] == pytest.approx(
        dp_s, rel=1e-3
    )
    assert row["discharge_plenum_pressure [Pa]"] - op.discharge_pressure == pytest.approx(
        dp_d, rel=1e-3
    )


def test_thermal_table_errors_name_file_key_and_range():
    with pytest.raises(CaseError, match=r"thermal\.ua_motor_shell.*unknown key"):
        recipsim.load_case(R600A_IDEAL, {**R600A, "thermal.ua_motor_shell": 1.0})
    with pytest.raises(
        CaseError, match=r"thermal\.direct_suction_fraction.*out of range.*\[0, 1\]"
    ):
        recipsim.load_case(R600A_IDEAL, {**R600A, "thermal.direct_suction_fraction": 1.5})
    with pytest.raises(CaseError, match=r"shell_pressure.*low-side shell"):
        recipsim.load_case(
            R600A_IDEAL,
            {**R600A, "options.thermal": "network", "operating_point.shell_pressure": "5 bar"},
        )


def test_the_next_start_follows_the_plenum_without_moving_the_periodic_state(monkeypatch):
    """Revolution iteration moves the cylinder's start state with the network's suction
    plenum (``WorkingModel.update_thermal(..., y_next)``). The periodic state is the same as
    with the start left where the last revolution ended (the plenum does not move once
    converged): capacity, COP and the cylinder inlet within 3e-4 (each run converged to
    the 1e-4 cycle tolerance; measured 5e-5). It must also pay: fewer revolutions
    (measured here 6 instead of 7; over 24 map points of the reference case 5.0 instead
    of 6.5 on average)."""
    from recipsim.model.build import WorkingModel

    case = recipsim.load_case(
        "reference_r134a_lbp",
        {
            "options.thermal": "network",
            "options.motor": "equivalent_circuit",
            "options.friction": "mean",
            "operating_point.evaporating_temperature": "-25 degC",
        },
    )
    following = simulate_case(case).row
    original = WorkingModel.update_thermal

    def lagging(self, y_end, duration, y_next=None):  # the start stays where it ended
        return original(self, y_end, duration)

    monkeypatch.setattr(WorkingModel, "update_thermal", lagging)
    lag = simulate_case(case).row
    assert following["converged [-]"] and lag["converged [-]"]
    for column in ("cooling_capacity [W]", "COP [-]", "cylinder_inlet_temperature [K]"):
        assert following[column] == pytest.approx(lag[column], rel=3e-4), column
    assert following["revolutions [-]"] < lag["revolutions [-]"]
