"""Coefficient files: what ``recipsim rate`` writes reads back to the same polynomials; a
maker's file (another standard, other units, a range of validity) is read and evaluated
only inside its range; a malformed file is refused naming the row or column."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from recipsim.errors import CaseError
from recipsim.studies.rate.coefficients import coefficient_row, read_coefficients
from recipsim.studies.rate.polynomial import evaluate, to_kelvin

#: A maker's file as North American makers publish one: degF, Btu/h, lb/h, a range.
MAKER = """quantity,unit,standard,temperature_unit,C1,C2,C3,C4,C5,C6,C7,C8,C9,C10,\
S_min,S_max,D_min,D_max
cooling_capacity,Btu/h,AHRI_540,degF,1000,10,-2,0,0,0,0,0,0,0.001,-10,40,80,140
power_input,W,AHRI_540,degF,20,0.1,0.5,0,0,0,0,0,0,0,-10,40,80,140
mass_flow,lb/h,AHRI_540,degF,3,0.05,-0.01,0,0,0,0,0,0,0,-10,40,80,140
"""


def test_the_written_table_reads_back_to_the_same_polynomials(tmp_path):
    rng = np.random.default_rng(3)
    rows = []
    written = {}
    for quantity, unit in (("cooling_capacity", "W"), ("power_input", "W"), ("current", "A")):
        c = rng.normal(size=10) * 10.0 ** -np.arange(10)
        written[quantity] = c
        extra = {"S_min": -35.0, "S_max": -10.0, "D_min": 35.0, "D_max": 65.0, "note": "x, y"}
        rows.append(coefficient_row(quantity, unit, "EN12900", "degC", c, extra))
    # a quantity left out: empty coefficients and why
    rows.append(coefficient_row("mass_flow", "kg/h", "EN12900", "degC", None, {"note": "why"}))
    path = tmp_path / "coefficients.csv"
    pd.DataFrame(rows).to_csv(path, index=False)

    read = read_coefficients(path)
    assert sorted(read) == ["cooling_capacity", "current", "power_input"]
    for quantity, c in written.items():
        # to_csv writes floats with repr: the coefficients come back bit for bit
        assert np.array_equal(read[quantity].coefficients, c)
        assert read[quantity].temperature_unit == "degC"
        assert read[quantity].bounds == (-35.0, -10.0, 35.0, 65.0)
        assert read[quantity].standard == "EN12900"
    s, d = np.array([-30.0, -12.5]), np.array([40.0, 60.0])
    expected = evaluate(written["power_input"], s, d)
    got = read["power_input"].si(to_kelvin(s, "degC"), to_kelvin(d, "degC"))
    assert got == pytest.approx(expected, rel=1e-12)


def test_a_makers_file_in_fahrenheit_and_btu_is_evaluated_in_si(tmp_path):
    path = tmp_path / "maker.csv"
    path.write_text(MAKER)
    makers = read_coefficients(path)
    # 20 F / 100 F: capacity 1000 + 200 - 200 + 1000 = 2000 Btu/h; power 20 + 2 + 50 = 72 W;
    # mass flow 3 + 1 - 1 = 3 lb/h = 3 * 0.45359237 / 3600 kg/s
    s, d = to_kelvin(np.array([20.0]), "degF"), to_kelvin(np.array([100.0]), "degF")
    assert makers["cooling_capacity"].si(s, d)[0] == pytest.approx(2000 * 0.29307107, rel=1e-6)
    assert makers["power_input"].si(s, d)[0] == pytest.approx(72.0, rel=1e-12)
    assert makers["mass_flow"].si(s, d)[0] == pytest.approx(3 * 0.45359237 / 3600, rel=1e-9)


def test_a_makers_polynomial_is_not_extrapolated(tmp_path):
    path = tmp_path / "maker.csv"
    path.write_text(MAKER)
    capacity = read_coefficients(path)["cooling_capacity"]
    s = to_kelvin(np.array([-10.0, 40.0, 41.0, 20.0]), "degF")
    d = to_kelvin(np.array([80.0, 140.0, 100.0, 150.0]), "degF")
    values = capacity.si(s, d)
    assert np.isfinite(values[:2]).all()  # on the bounds: inside
    assert math.isnan(values[2]) and math.isnan(values[3])  # S above, D above


@pytest.mark.parametrize(
    ("change", "where"),
    [
        (lambda t: t.replace("temperature_unit", "t_unit"), "temperature_unit"),
        (lambda t: t.replace("power_input,W", "power,W"), "row 2, quantity"),
        (lambda t: t.replace("power_input,W", "power_input,kg/h"), "row 2, unit"),
        (lambda t: t.replace(",degF,20,", ",K,20,"), "row 2, temperature_unit"),
        (lambda t: t.replace(",1000,10,", ",1000,,"), "row 1"),
        (lambda t: t.replace(",1000,10,", ",1000,ten,"), "row 1, C2"),
        (lambda t: t + "power_input,W,AHRI_540,degF,1,1,1,1,1,1,1,1,1,1,,,,\n", "row 4"),
    ],
    ids=["no column", "quantity", "unit", "temperature unit", "a gap", "text", "twice"],
)
def test_a_malformed_file_is_refused_naming_where(tmp_path, change, where):
    path = tmp_path / "maker.csv"
    path.write_text(change(MAKER))
    with pytest.raises(CaseError) as info:
        read_coefficients(path)
    assert info.value.key.startswith(where) or where in str(info.value)


def test_a_shipped_catalogue_is_found_by_its_file_name():
    """``--catalogue danfoss_tles5.7kk.3_r600a.csv`` from any directory: the shipped file,
    as calibrate finds it (its seven points, capacity at every one, COP at two)."""
    from recipsim.studies.rate.compare import read_catalogue

    points = read_catalogue("danfoss_tles5.7kk.3_r600a.csv")
    assert len(points) == 7
    assert all("cooling_capacity [W]" in p.targets for p in points)
    assert sum("COP [-]" in p.targets for p in points) == 2
