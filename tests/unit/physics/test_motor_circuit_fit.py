"""Motor circuit from nameplate data: the rated point comes back exactly, the default
household compressor motor lands in its efficiency band, bad data are refused."""

from __future__ import annotations

import dataclasses
import math

import pytest

from recipsim.physics.motor_circuit import (
    motor_breakdown,
    motor_operating_point,
    motor_operating_point_at_torque,
)
from recipsim.physics.motor_nameplate import (
    HOUSEHOLD_COMPRESSOR_NAMEPLATE,
    MotorNameplate,
    household_compressor_motor,
    motor_circuit_from_nameplate,
)

RPM = math.pi / 30.0

PLATES = {
    "default": HOUSEHOLD_COMPRESSOR_NAMEPLATE,
    # the same class of motor given by input power and current instead
    "input_and_current": MotorNameplate(
        voltage=220.0,
        frequency=50.0,
        poles=2,
        rated_output=75.0,
        rated_speed=2920.0 * RPM,
        breakdown_torque_ratio=2.3,
        rated_input_power=97.0,
        rated_current=0.70,
    ),
    # a 60 Hz four-pole motor with an unequal leakage split and given stray fraction
    "four_pole": MotorNameplate(
        voltage=115.0,
        frequency=60.0,
        poles=4,
        rated_output=186.0,
        rated_speed=1725.0 * RPM,
        breakdown_torque_ratio=2.5,
        rated_efficiency=0.70,
        rated_power_factor=0.62,
        stray_loss_fraction=0.018,
        leakage_reactance_ratio=0.8,
    ),
    "psc": dataclasses.replace(
        HOUSEHOLD_COMPRESSOR_NAMEPLATE,
        variant="PSC",
        rated_efficiency=0.85,
        rated_power_factor=0.95,
    ),
}


@pytest.mark.parametrize("name", list(PLATES))
def test_nameplate_rated_point_is_reproduced(name):
    # The fit solves four equations to ~1e-14; 1e-8 relative is the requirement.
    plate = PLATES[name]
    circuit = motor_circuit_from_nameplate(plate)
    rated_torque = plate.rated_output / plate.rated_speed
    point = motor_operating_point(circuit, plate.rated_speed)
    assert point.shaft_power == pytest.approx(plate.rated_output, rel=1e-8)
    assert point.electrical_power == pytest.approx(plate.input_power, rel=1e-8)
    assert point.efficiency == pytest.approx(plate.rated_output / plate.input_power, rel=1e-8)
    assert point.power_factor == pytest.approx(plate.power_factor, rel=1e-8)
    if plate.rated_current is not None:
        assert point.line_current == pytest.approx(plate.rated_current, rel=1e-8)
    # the inverse at rated torque gives back the rated speed
    again = motor_operating_point_at_torque(circuit, rated_torque)
    assert again.speed == pytest.approx(plate.rated_speed, rel=1e-8)
    assert motor_breakdown(circuit)[1] / rated_torque == pytest.approx(
        plate.breakdown_torque_ratio, rel=1e-8
    )
    # the per-unit assumptions hold at the rated point
    assert point.core_loss == pytest.approx(plate.core_loss_fraction * plate.input_power)
    assert point.windage_loss == pytest.approx(plate.friction_windage_fraction * plate.rated_output)
    stray = plate.stray_loss_fraction
    expected_stray = 0.025 * plate.input_power if stray is None else stray * plate.rated_output
    assert point.stray_loss == pytest.approx(expected_stray)
    assert circuit.main_leakage_reactance == pytest.approx(
        plate.leakage_reactance_ratio * circuit.rotor_leakage_reactance
    )
    if plate.variant == "PSC":
        # capacitor and turns ratio chosen for a balanced rated point
        assert point.backward_current / point.forward_current < 1e-9


def test_default_motor_efficiency_band_over_the_compressor_load_range():
    # TLES5.7KK.3 at its rating points draws about 70-100 W; the shaft power of a
    # household compressor motor of this class runs about 55-100 W. The band 0.75-0.85
    # is the expected efficiency range for small hermetic-compressor RSIR motors (see the
    # report); a circuit that drops out of it at part load would be implausible.
    circuit = household_compressor_motor()
    assert circuit.variant == "RSIR"
    for output in (70.0, 85.0, 100.0):
        speed_guess = HOUSEHOLD_COMPRESSOR_NAMEPLATE.rated_speed
        point = motor_operating_point_at_torque(circuit, output / speed_guess)
        assert 0.75 < point.efficiency < 0.85, (output, point.efficiency)
        assert 2850 * RPM < point.speed < 2990 * RPM  # 2900-2950 rpm class under load
    # stator copper, rotor copper and fixed losses all present at the rated point
    point = motor_operating_point(circuit, HOUSEHOLD_COMPRESSOR_NAMEPLATE.rated_speed)
    assert point.stator_copper_loss > 0.1 * (point.electrical_power - point.shaft_power)
    assert point.rotor_copper_loss > 0.1 * (point.electrical_power - point.shaft_power)


@pytest.mark.parametrize(
    ("change", "text"),
    [
        ({"rated_input_power": 120.0}, "exactly one of rated_efficiency"),
        ({"rated_power_factor": None}, "exactly one of rated_power_factor"),
        ({"rated_efficiency": 1.2}, "efficiency"),
        ({"rated_speed": 3100.0 * RPM}, "synchronous"),
        ({"breakdown_torque_ratio": 0.9}, "breakdown"),
        # fixed losses alone (core 4 %, stray 2.5 %, windage 1 %) exceed 1 - 0.97
        ({"rated_efficiency": 0.97}, "no circuit reproduces"),
    ],
)
def test_inconsistent_nameplates_are_refused(change, text):
    plate = dataclasses.replace(HOUSEHOLD_COMPRESSOR_NAMEPLATE, **change)
    with pytest.raises(ValueError, match=text):
        motor_circuit_from_nameplate(plate)
