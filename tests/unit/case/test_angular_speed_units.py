"""A shaft speed in any unit an engineer writes means the same speed: rpm, rev/s, rad/s,
and a frequency without an angle (Hz, 1/s, 1/min) read as revolutions per time, never
as radians per second (pint alone takes 1 Hz for 1 rad/s, the radian being
dimensionless)."""

from __future__ import annotations

import math

import pytest

from helpers import REFERENCE
from recipsim.case.load import load_case
from recipsim.units import to_si

RPM_3000 = 3000.0 * 2.0 * math.pi / 60.0  # [rad/s]


@pytest.mark.parametrize(
    "text",
    [
        "3000 rpm",
        "50 rev/s",
        "50 revolution/s",
        f"{RPM_3000!r} rad/s",
        "50 Hz",
        "0.05 kHz",
        "50 1/s",
        "3000 1/min",
        "3000 revolution/minute",
    ],
)
def test_every_angular_speed_unit_gives_the_same_speed(text: str) -> None:
    assert to_si(text, "rad/s", "case.toml", "shaft_speed") == pytest.approx(RPM_3000, rel=1e-14)


def test_a_bare_number_is_rad_per_second() -> None:
    assert to_si(RPM_3000, "rad/s", "case.toml", "shaft_speed") == RPM_3000


def test_hertz_stays_hertz_where_the_key_is_a_frequency() -> None:
    assert to_si("60 Hz", "Hz", "motor.toml", "line_frequency") == 60.0


def test_a_case_at_50_hz_runs_at_3000_rpm() -> None:
    case = load_case(REFERENCE, {"operating_point.shaft_speed": "50 Hz"})
    assert case.operating_point.shaft_speed == pytest.approx(RPM_3000, rel=1e-14)
