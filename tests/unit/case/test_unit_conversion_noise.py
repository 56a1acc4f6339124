"""A value written in another unit is stored as the float nearest its exact SI value
where that is a round number (no float noise of the conversion), and as the float
conversion gives it elsewhere (an irrational factor)."""

from __future__ import annotations

import math

import pytest

from recipsim.case.rating import STANDARDS
from recipsim.units import correctly_rounded, to_si


@pytest.mark.parametrize(
    ("written", "unit", "exact"),
    [
        ("-23.3 degC", "K", "249.85"),  # the float sum -23.3 + 273.15 is 249.84999999999997
        ("54.4 degC", "K", "327.55"),
        ("32.2 degC", "K", "305.35"),
        ("22 mm", "m", "0.022"),
        ("0.153 mm", "m", "0.000153"),
        ("7 cm**3", "m**3", "7e-6"),
        ("1.2 bar", "Pa", "120000"),
    ],
)
def test_a_round_number_converts_to_the_float_nearest_its_exact_value(written, unit, exact):
    assert to_si(written, unit, "case.toml", "key") == float(exact)


def test_an_irrational_factor_keeps_the_float_conversion():
    """rpm to rad/s (pi/30): no short decimal to go to; the value is pint's float,
    within a unit in the last place of the float product."""
    speed = to_si("3500 rpm", "rad/s", "case.toml", "operating_point.shaft_speed")
    assert abs(speed - 3500.0 * math.pi / 30.0) <= math.ulp(speed)
    # an input with more digits than the rounding would keep is left alone
    third = to_si("0.3333333333333333 m", "m", "case.toml", "key")
    assert third == 0.3333333333333333


def test_no_value_moves_by_more_than_two_units_in_the_last_place():
    computed = 1.0 / 3.0 + 273.15  # a value with no short decimal near it
    assert correctly_rounded(1.0 / 3.0, 273.15, 274.15, computed) == computed
    assert correctly_rounded(-23.3, 273.15, 274.15, -23.3 + 273.15) == 249.85


def test_the_rating_standards_hold_their_temperatures_without_noise():
    lbp = STANDARDS["ASHRAE_LBP"]
    assert (lbp.evaporating_temperature, lbp.condensing_temperature) == (249.85, 327.55)
    assert lbp.suction_temperature == lbp.liquid_temperature == 305.35
