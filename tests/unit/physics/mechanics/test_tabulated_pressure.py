"""Tabulated pressure: CSV contract, validation errors, periodic interpolation, test curve."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from recipsim.case.pressure_curve import read_pressure_curve
from recipsim.errors import CaseError
from recipsim.physics.kinematics import piston_displacement_array
from recipsim.physics.mechanics.tabulated import (
    ideal_cycle_indicated_work,
    ideal_cycle_pressure_curve,
    tabulated_pressure,
    tabulated_pressure_curve_from_arrays,
)

HEADER = "crank_angle [deg],cylinder_pressure [Pa],note\n"


def write(tmp_path: Path, body: str, header: str = HEADER) -> Path:
    path = tmp_path / "p.csv"
    path.write_text(header + body)
    return path


def test_read_csv_converts_degrees_and_ignores_other_columns(tmp_path: Path) -> None:
    path = write(tmp_path, "0,15e5,a\n90,2e5,b\n180,1.2e5,c\n270,3e5,d\n")
    curve = read_pressure_curve(path)
    np.testing.assert_allclose(curve.crank_angle, np.radians([0, 90, 180, 270]))
    np.testing.assert_allclose(curve.pressure, [15e5, 2e5, 1.2e5, 3e5])


def test_closing_row_at_360_is_dropped(tmp_path: Path) -> None:
    curve = read_pressure_curve(write(tmp_path, "0,15e5,\n120,2e5,\n240,3e5,\n360,15e5,\n"))
    assert curve.crank_angle.size == 3


@pytest.mark.parametrize(
    ("body", "key_part"),
    [
        ("0,15e5,\n120,2e5,\n240,3e5,\n360,14e5,\n", "crank_angle"),  # open 360 deg span
        ("0,15e5,\n200,2e5,\n400,3e5,\n", "crank_angle"),  # more than a revolution
        ("0,15e5,\n120,2e5,\n100,3e5,\n", "row 3"),  # not increasing
        ("0,15e5,\n120,2e5,\n120,3e5,\n", "row 3"),  # repeated angle
        ("0,15e5,\n120,0,\n240,3e5,\n", "row 2"),  # zero pressure
        ("0,15e5,\n120,-2e5,\n240,3e5,\n", "row 2"),  # negative pressure
        ("0,15e5,\n120,two bar,\n240,3e5,\n", "row 2"),  # not a number
        ("0,15e5,\n120,nan,\n240,3e5,\n", "row 2"),  # not finite
        ("0,15e5,\n120,2e5,\n", "crank_angle"),  # too few rows
    ],
)
def test_invalid_tables_raise_case_error(tmp_path: Path, body: str, key_part: str) -> None:
    path = write(tmp_path, body)
    with pytest.raises(CaseError) as err:
        read_pressure_curve(path)
    assert err.value.file == str(path)
    assert key_part in err.value.key


def test_missing_column_and_missing_file(tmp_path: Path) -> None:
    path = write(tmp_path, "0,1\n", header="crank_angle [deg],pressure [bar]\n")
    with pytest.raises(CaseError, match="missing column"):
        read_pressure_curve(path)
    with pytest.raises(CaseError, match="no such pressure curve file"):
        read_pressure_curve(tmp_path / "none.csv")


def test_negative_start_angle_is_allowed() -> None:
    curve = tabulated_pressure_curve_from_arrays(np.array([-180.0, -90.0, 0.0, 90.0]), np.ones(4))
    assert curve.crank_angle[0] == pytest.approx(-math.pi)


def test_periodic_interpolation() -> None:
    angles = np.radians([10.0, 100.0, 200.0, 300.0])
    values = np.array([1.0, 3.0, 2.0, 5.0])
    # inside the table: same as np.interp, also at the nodes
    for th in np.radians([10.0, 55.0, 100.0, 150.0, 299.9, 300.0]):
        assert tabulated_pressure(th, angles, values) == pytest.approx(
            np.interp(th, angles, values), rel=1e-14
        )
    # wrap segment: linear from 300 deg (5.0) to 370 deg (1.0)
    for deg, expected in [(335.0, 3.0), (0.0, 5.0 - 4.0 * 60 / 70), (5.0, 5.0 - 4.0 * 65 / 70)]:
        assert tabulated_pressure(math.radians(deg), angles, values) == pytest.approx(expected)
    # periodic in any number of revolutions, both signs
    for th in (0.3, 2.0, 5.9):
        ref = tabulated_pressure(th, angles, values)
        for k in (-3, -1, 1, 7):
            assert tabulated_pressure(th + 2 * math.pi * k, angles, values) == pytest.approx(
                ref, abs=1e-12
            )


def test_ideal_cycle_limits_and_closed_form_work() -> None:
    r, big_l, area = 0.0092, 0.036, math.pi * 0.022**2 / 4
    curve = ideal_cycle_pressure_curve(r, big_l, n_points=720)
    assert curve.pressure.min() == pytest.approx(1.15e5)
    assert curve.pressure.max() == pytest.approx(15e5)
    assert curve.pressure[0] == pytest.approx(15e5)  # TDC: discharge pressure
    assert curve.pressure[360] == pytest.approx(1.15e5)  # BDC: suction pressure
    # closed form against a fine quadrature of -closed integral p dV on the exact curve
    fine = ideal_cycle_pressure_curve(r, big_l, n_points=400_000)
    v = area * (0.02 * 2 * r + piston_displacement_array(fine.crank_angle, r, big_l))
    p = fine.pressure
    work = -np.sum(0.5 * (p + np.roll(p, -1)) * (np.roll(v, -1) - v))
    assert ideal_cycle_indicated_work(r, area) == pytest.approx(work, rel=1e-6)
    # order of magnitude: p_s V_s n/(n-1) ((p_d/p_s)^((n-1)/n) - 1) = 2.3 J per cycle
    # for 7 cm3 before the volumetric efficiency; about 110 W at 3500 rpm
    assert 1.0 < work < 2.5


def test_smoothing_keeps_the_mean_and_lowers_the_corners() -> None:
    sharp = ideal_cycle_pressure_curve(0.0092, 0.036)
    smooth = ideal_cycle_pressure_curve(0.0092, 0.036, smoothing=math.radians(5.0))
    assert smooth.pressure.mean() == pytest.approx(sharp.pressure.mean(), rel=1e-12)
    assert smooth.pressure.max() < sharp.pressure.max()
    assert smooth.pressure.min() > 0.0
    jump = np.abs(np.diff(np.diff(smooth.pressure))).max()
    assert jump < 0.2 * np.abs(np.diff(np.diff(sharp.pressure))).max()
