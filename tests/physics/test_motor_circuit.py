"""Single-phase induction motor circuit: a textbook example, an independent complex
solution, power balance, field symmetry, the PSC balance, and the torque inverse."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from recipsim.physics.motor_circuit import (
    MotorCircuit,
    motor_breakdown,
    motor_loss_columns,
    motor_operating_point,
    motor_operating_point_at_slip,
    motor_operating_point_at_torque,
)

#: Chapman, Electric Machinery Fundamentals (5th ed.), problem 9-1: a 120 V 1/4 hp
#: 60 Hz four-pole split-phase motor, R1 = 2.00, X1 = 2.56, XM = 60.5, R2 = 2.80,
#: X2 = 2.56 ohm, rotational losses 51 W at s = 0.05. Chapman lumps core, friction,
#: windage and stray losses into those 51 W taken from the converted power, so here
#: they are all put on the windage term (51 W at 0.95 synchronous speed).
CHAPMAN = MotorCircuit(
    voltage=120.0,
    frequency=60.0,
    poles=4,
    main_resistance=2.00,
    main_leakage_reactance=2.56,
    magnetising_reactance=60.5,
    rotor_resistance=2.80,
    rotor_leakage_reactance=2.56,
    friction_windage_loss=51.0 / 0.95**2,
)

#: Chapman's main winding with every loss kind switched on and a run capacitor.
LOSSY = dataclasses.replace(
    CHAPMAN, core_conductance=35.0 / 120.0**2, stray_loss_fraction=0.03, friction_windage_loss=9.0
)
PSC = dataclasses.replace(
    LOSSY,
    variant="PSC",
    aux_turns_ratio=1.3,
    aux_resistance=4.5,
    aux_leakage_reactance=3.9,
    run_capacitance=25e-6,
)


def test_chapman_problem_9_1_printed_values():
    # Printed in the solutions manual (page 277): I1 = 4.862 A at -46.2 deg,
    # P_in = 403.8 W, P_AG,F = 340.6 W, P_AG,B = 15.6 W, P_AG = 325 W, P_conv = 308 W,
    # P_out = 257 W, tau_ind = 1.72 N m, tau_load = 1.44 N m, efficiency 63.6 %.
    # Tolerances: half a unit of the last printed digit, except where the book carries
    # rounded intermediates: P_in = 120 * 4.862 * cos(46.2 deg) (angle rounded to 0.1
    # deg: 0.1 %), P_conv = 323 - 14.8 and P_out = 308 - 51 (rounded to 1 W before
    # subtracting: 1 W), efficiency = 257 / 403.8 (0.3 percentage points).
    p = motor_operating_point_at_slip(CHAPMAN, 0.05)
    assert p.main_current == pytest.approx(4.862, abs=5e-4)
    assert math.degrees(math.acos(p.power_factor)) == pytest.approx(46.2, abs=0.05)
    assert p.electrical_power == pytest.approx(403.8, rel=1e-3)
    assert p.forward_air_gap_power == pytest.approx(340.6, abs=0.05)
    assert p.backward_air_gap_power == pytest.approx(15.6, abs=0.05)
    assert p.forward_air_gap_power - p.backward_air_gap_power == pytest.approx(325.0, abs=0.5)
    assert p.electromagnetic_torque * p.speed == pytest.approx(308.0, abs=1.0)
    assert p.shaft_power == pytest.approx(257.0, abs=1.0)
    assert p.electromagnetic_torque == pytest.approx(1.72, abs=5e-3)
    assert p.shaft_torque == pytest.approx(1.44, abs=5e-3)
    assert p.efficiency == pytest.approx(0.636, abs=3e-3)
    assert p.speed == pytest.approx(0.95 * 1800 * math.pi / 30, rel=1e-14)


def _hand_solution(c: MotorCircuit, s: float) -> tuple[complex, float, float]:
    """Main current and rotor-branch air-gap powers by plain impedance algebra: each
    half circuit's rotor-branch current from the current divider, P = |I2|^2 R2/(2 s)."""
    rotor_f = 0.5 * (c.rotor_resistance / s + 1j * c.rotor_leakage_reactance)
    rotor_b = 0.5 * (c.rotor_resistance / (2 - s) + 1j * c.rotor_leakage_reactance)
    mag = 0.5j * c.magnetising_reactance
    z_f = rotor_f * mag / (rotor_f + mag)
    z_b = rotor_b * mag / (rotor_b + mag)
    i1 = c.voltage / (c.main_resistance + 1j * c.main_leakage_reactance + z_f + z_b)
    i2f = i1 * mag / (rotor_f + mag)
    i2b = i1 * mag / (rotor_b + mag)
    return i1, abs(i2f) ** 2 * rotor_f.real, abs(i2b) ** 2 * rotor_b.real


@pytest.mark.parametrize("slip", [0.01, 0.05, 0.2, 0.7, 1.0])
def test_rsir_against_an_independent_complex_solution(slip):
    # Same circuit, different algebra (impedance form and rotor-branch currents against
    # the admittance form and 4 Re(Z) |I_f|^2): agreement to rounding, 1e-12.
    i1, p_f, p_b = _hand_solution(CHAPMAN, slip)
    p = motor_operating_point_at_slip(CHAPMAN, slip)
    assert p.main_current == pytest.approx(abs(i1), rel=1e-12)
    assert p.forward_air_gap_power == pytest.approx(p_f, rel=1e-12)
    assert p.backward_air_gap_power == pytest.approx(p_b, rel=1e-12)


def _loss_sum(p) -> float:
    return (
        p.shaft_power
        + p.stator_copper_loss
        + p.rotor_copper_loss
        + p.core_loss
        + p.stray_loss
        + p.windage_loss
    )


@pytest.mark.parametrize("circuit", [LOSSY, PSC], ids=["RSIR", "PSC"])
@pytest.mark.parametrize("slip", [-0.3, -0.01, 0.0, 1e-6, 0.03, 0.1, 0.4, 0.9, 1.0])
def test_power_balance_closes(circuit, slip):
    # Input from the terminals Re(V I*), losses from the branch currents and air-gap
    # powers: they close only if the stator equations are solved consistently. 1e-10
    # relative to the input (rounding is about 1e-14).
    p = motor_operating_point_at_slip(circuit, slip)
    assert _loss_sum(p) == pytest.approx(p.electrical_power, rel=1e-10)
    assert p.stator_copper_loss == pytest.approx(p.main_copper_loss + p.auxiliary_copper_loss)
    assert min(p.core_loss, p.stray_loss, p.rotor_copper_loss, p.main_copper_loss) >= 0.0


def test_rsir_field_symmetry_at_standstill_and_synchronism():
    # s = 1: both fields see the same rotor, so the main winding alone has no starting
    # torque, exactly. s = 0: only the backward field pulls, T = -P_b / w_s < 0.
    start = motor_operating_point_at_slip(CHAPMAN, 1.0)
    assert start.electromagnetic_torque == 0.0
    sync = motor_operating_point_at_slip(CHAPMAN, 0.0)
    assert sync.forward_air_gap_power == pytest.approx(0.0, abs=1e-12)
    assert sync.electromagnetic_torque < 0.0
    expected = -sync.backward_air_gap_power / CHAPMAN.synchronous_speed
    assert sync.electromagnetic_torque == pytest.approx(expected, rel=1e-14)


def test_psc_starts_forward_and_reduces_to_rsir_without_its_capacitor():
    # The capacitor makes the auxiliary current lead: positive starting torque.
    assert motor_operating_point_at_slip(PSC, 1.0).electromagnetic_torque > 0.1
    # A vanishing capacitor (1 pF: X_C ~ 2.7e9 ohm) opens the auxiliary branch; the
    # remaining coupling is of order |Z|/X_C ~ 1e-8.
    nearly_open = dataclasses.replace(PSC, run_capacitance=1e-12)
    for slip in (0.05, 0.5):
        p, q = (motor_operating_point_at_slip(c, slip) for c in (nearly_open, LOSSY))
        assert p.main_current == pytest.approx(q.main_current, rel=1e-7)
        assert p.electromagnetic_torque == pytest.approx(q.electromagnetic_torque, rel=1e-6)


def test_psc_balanced_capacitor_cancels_the_backward_field():
    # For a chosen turns ratio, balance (I_aux' = j I_main) needs, with Z = Z1m + 2 Z_f,
    # R1a = a Im(Z) - 2 a^2 Re(Z_f) and X_C = X1a + a Re(Z) + 2 a^2 Im(Z_f): derived by
    # hand from the two stator equations, evaluated here with their own complex algebra.
    slip, a, x1a = 0.04, 1.25, 3.0
    c = CHAPMAN
    rotor = c.rotor_resistance / slip + 1j * c.rotor_leakage_reactance
    z_f = 0.5 * rotor * 1j * c.magnetising_reactance / (rotor + 1j * c.magnetising_reactance)
    z = complex(c.main_resistance, c.main_leakage_reactance) + 2 * z_f
    r1a = a * z.imag - 2 * a * a * z_f.real
    x_c = x1a + a * z.real + 2 * a * a * z_f.imag
    assert r1a > 0.0
    balanced = dataclasses.replace(
        c,
        variant="PSC",
        aux_turns_ratio=a,
        aux_resistance=r1a,
        aux_leakage_reactance=x1a,
        run_capacitance=1.0 / (2 * math.pi * c.frequency * x_c),
    )
    p = motor_operating_point_at_slip(balanced, slip)
    assert p.backward_current / p.forward_current < 1e-9
    assert p.backward_air_gap_power / p.forward_air_gap_power < 1e-17
    off = motor_operating_point_at_slip(balanced, 0.2)
    assert off.backward_current / off.forward_current > 1e-2  # only at the design slip


@pytest.mark.parametrize("circuit", [CHAPMAN, LOSSY, PSC], ids=["chapman", "lossy", "PSC"])
def test_torque_inverse_hits_the_load_on_the_stable_branch(circuit):
    s_k, t_k = motor_breakdown(circuit)
    # the breakdown is a maximum: neighbours lower, to 1e-12 of the torque
    for ds in (1e-4, -1e-4):
        assert motor_operating_point_at_slip(circuit, s_k + ds).shaft_torque < t_k
    for fraction in (0.0, 0.1, 0.5, 0.9, 0.999):
        load = fraction * t_k
        p = motor_operating_point_at_torque(circuit, load)
        assert p.shaft_torque == pytest.approx(load, abs=1e-10)
        assert 0.0 < p.slip < s_k
        slope = motor_operating_point_at_slip(circuit, p.slip * (1 + 1e-6)).shaft_torque
        assert slope > p.shaft_torque  # rising with slip: the stable branch
    with pytest.raises(ValueError, match="exceeds the breakdown torque"):
        motor_operating_point_at_torque(circuit, 1.001 * t_k)


def test_torque_inverse_below_the_no_load_torque_generates():
    no_load = motor_operating_point_at_slip(LOSSY, 0.0).shaft_torque
    p = motor_operating_point_at_torque(LOSSY, no_load - 0.2)
    assert p.slip < 0.0
    assert p.shaft_torque == pytest.approx(no_load - 0.2, abs=1e-10)


def test_speed_and_slip_agree():
    p = motor_operating_point(LOSSY, 170.0)
    q = motor_operating_point_at_slip(LOSSY, 1 - 170.0 / LOSSY.synchronous_speed)
    assert p.speed == pytest.approx(170.0, rel=1e-14)
    # the two slips differ only by rounding (1e-16); the results by no more than 1e-12
    assert dataclasses.astuple(p) == pytest.approx(dataclasses.astuple(q), rel=1e-12)


@pytest.mark.parametrize(
    ("change", "text"),
    [
        ({"main_resistance": -1.0}, "main_resistance"),
        ({"rotor_resistance": 0.0}, "rotor_resistance"),
        ({"magnetising_reactance": math.nan}, "magnetising_reactance"),
        ({"stray_loss_fraction": 1.0}, "stray_loss_fraction"),
        ({"poles": 3}, "poles"),
        ({"variant": "CSCR"}, "RSIR or PSC"),
        ({"variant": "PSC"}, "aux_turns_ratio"),
    ],
)
def test_bad_parameters_are_refused(change, text):
    with pytest.raises(ValueError, match=text):
        dataclasses.replace(CHAPMAN, **change)


def test_bad_operating_requests_are_refused():
    with pytest.raises(ValueError, match="speed"):
        motor_operating_point(CHAPMAN, -1.0)
    with pytest.raises(ValueError, match="slip"):
        motor_operating_point_at_slip(CHAPMAN, 1.5)
    with pytest.raises(ValueError, match="finite"):
        motor_operating_point_at_torque(CHAPMAN, math.inf)


def test_loss_columns_name_units_and_add_up():
    p = motor_operating_point_at_slip(PSC, 0.05)
    cols = motor_loss_columns(p)
    for key in (
        "motor_electrical_power [W]",
        "motor_efficiency [-]",
        "motor_power_factor [-]",
        "motor_current [A]",
        "motor_stator_copper_loss [W]",
        "motor_main_copper_loss [W]",
        "motor_auxiliary_copper_loss [W]",
        "motor_rotor_copper_loss [W]",
        "motor_core_loss [W]",
        "motor_stray_loss [W]",
        "motor_windage_loss [W]",
        "motor_slip [-]",
        "motor_speed [rad/s]",
    ):
        assert np.isfinite(cols[key]), key
    kinds = ("stator_copper", "rotor_copper", "core", "stray", "windage")
    losses = sum(cols[f"motor_{kind}_loss [W]"] for kind in kinds)
    assert losses + cols["motor_shaft_power [W]"] == pytest.approx(
        cols["motor_electrical_power [W]"], rel=1e-10
    )
