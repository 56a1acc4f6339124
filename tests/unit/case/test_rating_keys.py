"""Rating standards, superheat/subcooling and ambient keys, the motor circuit's keys and
options.friction: what each sets, and the conflicts refused with a CaseError."""

from __future__ import annotations

import math

import pytest

from helpers import CASES, REFERENCE
from recipsim.case.load import load_case
from recipsim.errors import CaseError
from recipsim.physics.motor_circuit import MotorCircuit, motor_breakdown, motor_operating_point

R600A = CASES / "r600a_lbp.toml"


def test_en12900_sets_its_point_and_liquid_at_the_bubble_point():
    op = load_case(R600A, {"operating_point.standard": "EN12900"}).operating_point
    assert op.evaporating_temperature == pytest.approx(248.15, abs=1e-9)
    assert op.condensing_temperature == pytest.approx(328.15, abs=1e-9)
    assert op.suction_temperature == pytest.approx(305.15, abs=1e-9)
    assert op.liquid_temperature == pytest.approx(328.15, abs=1e-6)  # no subcooling
    assert (op.ambient_temperature, op.standard) == (pytest.approx(305.15), "EN12900")


def test_the_rating_point_with_liquid_at_condensing_now_loads():
    """The refrigerant file's en12900_lbp point (liquid 55 C at 55 C condensing) was
    refused by a rounding-level excess over the bubble point; 1 uK is now saturated."""
    op = load_case(R600A, {"operating_point.rating_point": "en12900_lbp"}).operating_point
    assert op.liquid_temperature == pytest.approx(328.15)


def test_a_standard_keeps_a_given_evaporating_temperature():
    """A map point rated the standard's way: its own evaporating temperature, the
    standard's suction gas and (zero) subcooling at its condensing temperature."""
    op = load_case(
        R600A,
        {
            "operating_point.standard": "EN12900",
            "operating_point.evaporating_temperature": "-35 degC",
            "operating_point.condensing_temperature": "45 degC",
        },
    ).operating_point
    assert op.evaporating_temperature == pytest.approx(238.15)
    assert op.suction_temperature == pytest.approx(305.15)
    assert op.liquid_temperature == pytest.approx(318.15, abs=1e-6)


def test_ahri_540_sets_superheat_and_subcooling():
    op = load_case(CASES / "r32_ac.toml", {"operating_point.standard": "AHRI_540"}).operating_point
    assert op.suction_temperature == pytest.approx(280.35 + 11.1, abs=1e-6)
    assert op.liquid_temperature == pytest.approx(327.55 - 8.3, abs=1e-6)
    assert op.ambient_temperature == pytest.approx(308.15)


def test_superheat_and_subcooling_keys():
    case = load_case(
        REFERENCE,
        {"operating_point.superheat": "10 K", "operating_point.subcooling": "5 K"},
    )
    op = case.operating_point
    assert op.suction_temperature == pytest.approx(op.evaporating_temperature + 10.0, abs=1e-6)
    assert op.liquid_temperature == pytest.approx(op.condensing_temperature - 5.0, abs=1e-6)
    assert op.ambient_temperature == pytest.approx(305.35)  # the agreed default


@pytest.mark.parametrize(
    ("overrides", "key"),
    [
        ({"standard": "ASHRAE_LBP", "suction_temperature": "30 degC"}, "suction_temperature"),
        ({"standard": "EN12900", "subcooling": "2 K"}, "subcooling"),
        ({"standard": "EN12900", "ambient_temperature": "25 degC"}, "ambient_temperature"),
        ({"suction_temperature": "30 degC", "superheat": "5 K"}, "superheat"),
        ({"superheat": "5 degC"}, "superheat"),  # 278 K: a temperature, not a difference
    ],
)
def test_conflicting_rating_keys_are_refused(overrides, key):
    with pytest.raises(CaseError, match=rf"operating_point\.{key}"):
        load_case(R600A, {f"operating_point.{k}": v for k, v in overrides.items()})


def test_keys_that_agree_with_the_standard_are_accepted():
    op = load_case(
        R600A,
        {"operating_point.standard": "ASHRAE_LBP", "operating_point.ambient_temperature": 305.35},
    ).operating_point
    assert op.suction_temperature == pytest.approx(305.35)


def test_friction_option_defaults_and_refusals():
    assert load_case(REFERENCE).options.friction == "off"
    assert load_case(CASES / "reference_r134a_lbp_lubricated.toml").options.friction == "films"
    with pytest.raises(CaseError, match=r"options\.friction.*'films' needs"):
        load_case(REFERENCE, {"options.friction": "films"})
    with pytest.raises(CaseError, match=r"options\.friction.*oil films"):
        load_case(CASES / "reference_r134a_lbp_lubricated.toml", {"options.friction": "mean"})


def test_motor_circuit_from_nameplate_and_refusals():
    case = load_case(REFERENCE, {"options.motor": "equivalent_circuit"})
    assert case.motor_circuit is not None and case.motor_circuit.variant == "PSC"
    assert case.motor is not None  # the drive's torque curve is still built
    with pytest.raises(CaseError, match=r"shaft_speed.*synchronous"):
        load_case(
            REFERENCE,
            {"options.motor": "equivalent_circuit", "operating_point.shaft_speed": "3700 rpm"},
        )
    with pytest.raises(CaseError, match=r"motor\.rated_efficiency: .*not both"):
        load_case(REFERENCE, {"options.motor": "equivalent_circuit", "motor.main_resistance": 2.0})
    with pytest.raises(CaseError, match=r"motor\.rated_power.*exactly one"):
        load_case(REFERENCE, {"options.motor": "equivalent_circuit", "motor.rated_power": 100.0})


def test_a_nameplate_is_fitted_once_per_process_and_reproduced():
    """The catalogue case's motor, given by nameplate: the fitted circuit reproduces the
    rated shaft power, efficiency, power factor and breakdown torque; cases that share
    the nameplate (the points of a sweep) share one fit, another nameplate has its own."""
    from recipsim.case import motor_losses

    catalogue = CASES / "tles5.7kk3_r600a.toml"
    motor_losses._fitted_circuit.cache_clear()
    first = load_case(catalogue).motor_circuit
    again = load_case(catalogue, {"operating_point.standard": "ASHRAE_LBP"}).motor_circuit
    assert first is not None and again is first
    assert motor_losses._fitted_circuit.cache_info().misses == 1
    case = load_case(catalogue)
    speed = 2900.0 * math.pi / 30.0  # the case's rated speed [rad/s]
    # the torques as the case applies them (matched to its displacement: 0.247 and 0.54
    # N m within the 5-digit displacement it is written with)
    rated_torque, breakdown = case.motor.rated_torque, case.motor.breakdown_torque
    assert rated_torque == pytest.approx(0.247, rel=1e-5)
    point = motor_operating_point(first, speed)
    assert point.shaft_power == pytest.approx(rated_torque * speed, rel=1e-8)
    assert point.efficiency == pytest.approx(case.raw["motor"]["rated_efficiency"], rel=1e-8)
    assert point.power_factor == pytest.approx(0.60, rel=1e-8)
    assert motor_breakdown(first)[1] == pytest.approx(breakdown, rel=1e-8)
    other = load_case(catalogue, {"motor.rated_power_factor": 0.62}).motor_circuit
    assert other != first
    assert motor_losses._fitted_circuit.cache_info().misses == 2


def test_motor_circuit_from_its_values(tmp_path):
    """Chapman's problem 9-1 motor given by its circuit values, on a constant-speed case."""
    head, rest = REFERENCE.read_text().split("[motor]\n")
    tail = rest[rest.index("\n# recipsim bench") :]
    values = (
        '[motor]\nline_frequency = "60 Hz"\npoles = 4\nvoltage = "120 V"\n'
        "main_resistance = 2.0\nmain_leakage_reactance = 2.56\nmagnetising_reactance = 60.5\n"
        "rotor_resistance = 2.8\nrotor_leakage_reactance = 2.56\n"
    )
    path = tmp_path / "chapman.toml"
    path.write_text(head + values + tail)
    case = load_case(
        path,
        {"options.motor": "equivalent_circuit", "operating_point.shaft_speed": "1700 rpm"},
    )
    expected = MotorCircuit(
        voltage=120.0, frequency=60.0, poles=4, main_resistance=2.0,
        main_leakage_reactance=2.56, magnetising_reactance=60.5, rotor_resistance=2.8,
        rotor_leakage_reactance=2.56,
    )  # fmt: skip
    assert case.motor_circuit == expected
    assert case.motor is None  # no torque curve keys: none built
    assert math.isclose(case.motor_circuit.synchronous_speed, 1800 * math.pi / 30)


@pytest.mark.parametrize(
    ("path", "overrides"),
    [
        (R600A, {"operating_point.standard": "EN12900"}),
        (R600A, {"operating_point.standard": "ASHRAE_LBP"}),
        (REFERENCE, {"operating_point.superheat": "10 K", "options.motor": "equivalent_circuit"}),
    ],
)
def test_the_resolved_case_reloads_to_the_same_point(path, overrides, tmp_path):
    """The report's case.toml (standard, rating point, defaults written out) loads back to
    the same operating point, options and motor circuit, with no conflict refused."""
    from recipsim.report.resolved_case import resolved_case

    case = load_case(path, overrides)
    text, files = resolved_case(case)
    (tmp_path / "case.toml").write_text(text)
    for rel, data in files.items():
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / rel).write_bytes(data)
    again = load_case(tmp_path / "case.toml")
    assert again.operating_point == case.operating_point
    assert again.options == case.options and again.motor_circuit == case.motor_circuit
