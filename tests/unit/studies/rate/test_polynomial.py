"""The ten-coefficient polynomial of EN 12900 / AHRI 540: its order, its units, its fit.

The hand-computed values are worked out in the comments; the fits are checked on data made
by a known polynomial, which a least-squares fit of the same ten terms must give back to
round-off.
"""

from __future__ import annotations

import numpy as np
import pytest

from recipsim.studies.rate.coefficients import Polynomial
from recipsim.studies.rate.polynomial import (
    MIN_POINTS,
    RatingError,
    evaluate,
    fit,
    from_kelvin,
    to_kelvin,
)

#: C1 .. C10 = 1 .. 10: every term has its own weight, so a swapped pair shows.
ONE_TO_TEN = np.arange(1.0, 11.0)


def test_the_terms_come_in_the_standards_order():
    # S = -2, D = 3:
    #   C1          1
    #   C2  S      2 * -2      = -4
    #   C3  D      3 * 3       =  9
    #   C4  S^2    4 * 4       = 16
    #   C5  S D    5 * -6      = -30
    #   C6  D^2    6 * 9       = 54
    #   C7  S^3    7 * -8      = -56
    #   C8  D S^2  8 * 12      = 96
    #   C9  S D^2  9 * -18     = -162
    #   C10 D^3    10 * 27     = 270          sum 194
    # (C8 and C9 swapped would give 164: the test tells the two mixed terms apart)
    assert evaluate(ONE_TO_TEN, -2.0, 3.0)[0] == pytest.approx(194.0, abs=1e-12)


def test_en12900_coefficients_take_celsius():
    # X = 100 + 2 S - 0.5 D + 0.01 S D in W, S and D in degC; at -25 C / 55 C:
    # 100 - 50 - 27.5 - 13.75 = 8.75 W
    c = np.array([100.0, 2.0, -0.5, 0.0, 0.01, 0.0, 0.0, 0.0, 0.0, 0.0])
    poly = Polynomial("cooling_capacity", "W", "degC", c, (np.nan,) * 4)
    value = poly.si(np.array([248.15]), np.array([328.15]))
    assert value[0] == pytest.approx(8.75, rel=1e-12)


def test_ahri_540_coefficients_take_fahrenheit_and_publish_btu_per_hour():
    # X = 1000 + 10 S - 2 D + 0.001 D^3 in Btu/h, S and D in degF; at 20 F / 100 F:
    # 1000 + 200 - 200 + 1000 = 2000 Btu/h = 2000 * 0.29307107 W = 586.142 W
    c = np.array([1000.0, 10.0, -2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.001])
    poly = Polynomial("cooling_capacity", "Btu/h", "degF", c, (np.nan,) * 4)
    s_k = (20.0 - 32.0) / 1.8 + 273.15
    d_k = (100.0 - 32.0) / 1.8 + 273.15
    # the IT Btu (1055.05585 J) per hour; pint's Btu agrees to 1e-6
    assert poly.si(np.array([s_k]), np.array([d_k]))[0] == pytest.approx(586.1421, rel=1e-6)


def test_temperature_units_go_there_and_back():
    kelvin = np.array([233.15, 273.15, 338.7])
    assert from_kelvin(kelvin, "degF") == pytest.approx([-40.0, 32.0, 149.99], abs=1e-9)
    for unit in ("degC", "degF"):
        assert to_kelvin(from_kelvin(kelvin, unit), unit) == pytest.approx(kelvin, abs=1e-12)


@pytest.mark.parametrize(
    ("s_axis", "d_axis"),
    [
        (np.arange(-35.0, -9.0, 5.0), np.arange(35.0, 66.0, 10.0)),  # EN 12900, degC
        (np.arange(-30.0, 21.0, 10.0), np.arange(90.0, 151.0, 20.0)),  # AHRI 540, degF
    ],
    ids=["degC", "degF"],
)
def test_a_fit_gives_back_the_polynomial_that_made_the_data(s_axis, d_axis):
    rng = np.random.default_rng(7)
    # coefficients of the size a household compressor's capacity has in each unit
    scale = 10.0 ** -np.array([-2, 0, 0, 2, 2, 2, 4, 4, 4, 4], dtype=float)
    truth = rng.uniform(-1.0, 1.0, 10) * scale
    s, d = (a.ravel() for a in np.meshgrid(s_axis, d_axis))
    values = evaluate(truth, s, d)
    result = fit(s, d, values)
    # round-off of a least-squares solve on columns up to 150^3: far below 1e-9 relative
    assert np.max(np.abs(result.residuals)) <= 1e-9 * np.max(np.abs(values))
    assert result.coefficients == pytest.approx(truth, rel=1e-6, abs=1e-12)


def test_fewer_than_ten_points_are_refused():
    s, d = (a.ravel() for a in np.meshgrid([-30.0, -20.0, -10.0], [35.0, 45.0, 55.0]))
    assert len(s) == MIN_POINTS - 1
    with pytest.raises(RatingError, match="9 good points.*at least 10"):
        fit(s, d, s + d, "cooling_capacity")


def test_a_grid_with_three_condensing_temperatures_cannot_fix_the_cubic():
    # 12 points, but D^3 is a combination of 1, D and D^2 on three values of D
    s, d = (a.ravel() for a in np.meshgrid([-35.0, -30.0, -25.0, -20.0], [35.0, 45.0, 55.0]))
    with pytest.raises(RatingError, match="determine only 9 of the ten"):
        fit(s, d, s * d, "power_input")
