"""From indicated to electrical: the "today" settings reproduce the indicated summary,
the motor circuit at its nameplate, the power chain, mean friction against Petroff's law
and the skirt formula by hand, mean friction against the oil films, and the rating
standards' enthalpies against CoolProp."""

from __future__ import annotations

import math

import numpy as np
import pytest

from helpers import CASES, REFERENCE, solve_case
from recipsim.case.load import load_case
from recipsim.physics.lubricant import DEFAULT_OIL
from recipsim.results.electrical import (
    MOTOR_LOSSES,
    loss_columns,
    mean_friction_columns,
    motor_columns,
    rating_enthalpies,
)
from recipsim.results.tables import cycle_table, summary

RPM = math.pi / 30.0


@pytest.fixture(scope="module")
def reference_run():
    """The reference case with today's settings (lossless motor, friction off)."""
    solution = solve_case(REFERENCE)
    cycle = cycle_table(solution)
    return solution, cycle, summary(solution, cycle)


def test_lossless_motor_and_no_friction_reproduce_the_indicated_summary(reference_run):
    """Exact equality (not a tolerance): with the default options every quantity is
    computed as before: capacity with the suction plenum's enthalpy and the liquid line's,
    COP = capacity / shaft power (the drive's integrated work)."""
    solution, cycle, row = reference_run
    model = solution.model
    op = model.case.operating_point
    assert (model.case.options.motor, model.case.options.friction) == ("lossless", "off")
    h_liquid = model.fluid.liquid_enthalpy(op.discharge_pressure, op.liquid_temperature)
    capacity = row["discharge_mass_flow [kg/s]"] * (model.suction.enthalpy - h_liquid)
    assert row["cooling_capacity [W]"] == capacity
    assert row["motor_electrical_power [W]"] == row["shaft_power [W]"]
    assert row["COP [-]"] == capacity / row["shaft_power [W]"]
    assert row["indicated_COP [-]"] == capacity / row["indicated_power [W]"]
    assert row["friction_power [W]"] == 0.0 and row["motor_loss_power [W]"] == 0.0
    explicit = model.case.with_({"options.motor": "lossless", "options.friction": "off"})
    again = loss_columns(explicit, cycle, row["shaft_power [W]"], op.shaft_speed / (2 * math.pi))
    assert again["shaft_power [W]"] == row["shaft_power [W]"]


def test_circuit_at_rated_load_gives_the_nameplate():
    """The nameplate fit reproduces its rated point to ~1e-12; through the summary's
    motor columns at rated torque and speed: efficiency, power factor, speed to 1e-9."""
    case = load_case(REFERENCE, {"options.motor": "equivalent_circuit"})
    rated_speed = 3500.0 * RPM
    shaft = 0.30 * rated_speed
    row = motor_columns(case, shaft, rated_speed)
    assert row["motor_efficiency [-]"] == pytest.approx(0.75, rel=1e-9)
    assert row["motor_power_factor [-]"] == pytest.approx(0.90, rel=1e-9)
    assert row["motor_speed_at_load [rpm]"] == pytest.approx(3500.0, rel=1e-9)
    assert row["motor_auxiliary_copper_loss_power [W]"] > 0.0  # PSC: both windings carry


def test_electrical_power_is_shaft_power_plus_the_losses(reference_run):
    """The circuit's input V Re(I) against the shaft power plus its six loss columns, at
    the reference cycle's load with mean friction: equal to rounding (1e-9 relative)."""
    solution, cycle, row = reference_run
    case = solution.model.case.with_(
        {"options.motor": "equivalent_circuit", "options.friction": "mean"}
    )
    freq = case.operating_point.shaft_speed / (2.0 * math.pi)
    cols = loss_columns(case, cycle, row["shaft_power [W]"], freq)
    losses = sum(cols[name] for name in MOTOR_LOSSES)
    shaft = cols["shaft_power [W]"]
    assert shaft == pytest.approx(row["shaft_power [W]"] + cols["friction_power [W]"], rel=1e-15)
    assert cols["motor_electrical_power [W]"] == pytest.approx(shaft + losses, rel=1e-9)
    assert cols["motor_loss_power [W]"] == pytest.approx(losses, rel=1e-9)
    # a household motor at 0.3 N m: efficiency a little off the rated 0.75
    assert 0.65 < cols["motor_efficiency [-]"] < 0.80


def test_mean_friction_against_petroff_and_the_skirt_by_hand(reference_run):
    """Petroff P = 2 pi mu R^3 L w^2 / c for the primary journal (constant speed), the
    eccentric with the rod's swing (rod angle by finite differences of asin), and the skirt
    mu pi D L v^2 / delta with the closed-form piston velocity: 1e-9 relative (the same
    formulas evaluated independently; the finite differences are central, 1e-6 rad)."""
    solution, cycle, _ = reference_run
    case = solution.model.case
    cols = mean_friction_columns(case, cycle)
    mu = DEFAULT_OIL.viscosity(333.15)
    w = case.operating_point.shaft_speed
    primary = 2 * math.pi * mu * 0.008**3 * 0.020 * w**2 / 10e-6
    assert cols["friction_power_primary [W]"] == pytest.approx(primary, rel=1e-9)
    theta = np.radians(cycle["crank_angle [deg]"].to_numpy())
    lam = case.geometry.crank_radius / case.geometry.connecting_rod_length
    h = 1e-6
    dphi = (-np.arcsin(lam * np.sin(theta + h)) + np.arcsin(lam * np.sin(theta - h))) / (2 * h)
    eccentric = 2 * math.pi * mu * 0.007**3 * 0.012 * w**2 / 10e-6 * np.mean((1 - dphi) ** 2)
    assert cols["friction_power_eccentric [W]"] == pytest.approx(eccentric, rel=1e-8)
    r = case.geometry.crank_radius
    s, c = np.sin(theta), np.cos(theta)
    v = r * w * s * (1 + lam * c / np.sqrt(1 - lam**2 * s**2))
    skirt = mu * math.pi * 0.022 * 0.020 * np.mean(v**2) / 6e-6
    assert cols["piston_friction_power [W]"] == pytest.approx(skirt, rel=1e-9)
    total = sum(v for k, v in cols.items() if k != "friction_power [W]")
    assert cols["friction_power [W]"] == pytest.approx(total, rel=1e-15)


def test_mean_friction_against_the_films_of_the_lubricated_case():
    """Petroff at the lubricated case's own cycle (same journals, oil, speeds) against the
    finite-length films. Measured ratios 0.91 / 0.87 / 0.83 (primary, secondary,
    eccentric; 0.88 for the three together, 7.23 W against 8.23 W; the films run at
    eccentricity ratios up to 0.36-0.62, where the Couette torque alone is 1.07-1.27 times
    Petroff's): the same order of magnitude, and below 1 since Petroff is the centred
    film's lower bound. The same holds for the skirt: the mean law's concentric Couette
    force against the skirt film (0.89 measured, 3.67 W against 4.12 W; the film runs at
    eccentricity ratios up to 0.46)."""
    solution = solve_case(CASES / "reference_r134a_lbp_lubricated.toml")
    cycle = cycle_table(solution)
    row = summary(solution, cycle)
    mean = mean_friction_columns(solution.model.case, cycle)
    films = 0.0
    for name in ("primary", "secondary", "eccentric"):
        ratio = mean[f"friction_power_{name} [W]"] / row[f"friction_power_{name} [W]"]
        assert 0.7 < ratio < 1.0, (name, ratio)
        films += row[f"friction_power_{name} [W]"]
    assert row["friction"] == "films"
    skirt = row["piston_friction_power [W]"]
    assert 0.7 < mean["piston_friction_power [W]"] / skirt < 1.0
    # the skirt film's dissipation: its axial friction and its lateral (squeeze) power at
    # the two stations
    films += skirt + sum(row[f"friction_power_{s} [W]"] for s in ("piston_top", "piston_skirt"))
    assert row["friction_power [W]"] == pytest.approx(films, rel=1e-12)


@pytest.mark.parametrize(
    ("standard", "dh_printed"),
    [("ASHRAE_LBP", 334.8e3), ("EN12900", 276.2e3)],  # thermo-notes section 3, R600a
)
def test_standard_enthalpies_against_coolprop(standard, dh_printed):
    """h(p_evap, T_suction gas) - h(liquid) of the standard for R600a against CoolProp
    directly (1e-9: the same equation of state) and the printed value (half its last
    digit, 0.05 kJ/kg)."""
    import CoolProp.CoolProp as CP

    case = load_case(
        CASES / "r600a_lbp.toml",
        {"operating_point.standard": standard, "options.properties": "heos"},
    )
    op = case.operating_point
    h_gas, h_liquid = rating_enthalpies(case_fluid(case), op)
    t_evap = {"ASHRAE_LBP": 249.85, "EN12900": 248.15}[standard]
    p_evap = CP.PropsSI("P", "T", t_evap, "Q", 1, "Isobutane")
    if standard == "ASHRAE_LBP":
        t_cond, t_suc = 327.55, 305.35
        p_cond = CP.PropsSI("P", "T", t_cond, "Q", 0, "Isobutane")
        liquid = CP.PropsSI("H", "P", p_cond, "T", 305.35, "Isobutane")
    else:
        t_suc = 305.15
        liquid = CP.PropsSI("H", "T", 328.15, "Q", 0, "Isobutane")  # no subcooling
    gas = CP.PropsSI("H", "P", p_evap, "T", t_suc, "Isobutane")
    assert h_gas == pytest.approx(gas, rel=1e-9)
    assert h_liquid == pytest.approx(liquid, rel=1e-9)
    assert h_gas - h_liquid == pytest.approx(dh_printed, abs=50.0)
    assert op.ambient_temperature == pytest.approx(t_suc, abs=1e-9)  # both: ambient = gas


def case_fluid(case):
    from recipsim.case.refrigerant import case_fluid as make

    return make(case.refrigerant, case.options.properties)
