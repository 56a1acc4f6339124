"""The mobility law (Booker's short-bearing mobility, inverted for the force) against the
short law it approximates, the closed forms it must meet exactly, and its own inversion.

Tolerances: where both laws are exact (the centred squeeze damper) to 1e-12; the
inversion (the force put back into the forward mobility gives the velocity) to 1e-9,
ten times the Newton tolerance on the direction times the mobility's slope; against the
short law, the map measured over 48 film directions per eccentricity ratio, plus 0.2
points: Booker's closed forms are an approximation whose error grows with eps.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from recipsim.physics.mechanics.bearing_laws.mobility import (
    mobility_journal_film,
    mobility_vector,
)
from recipsim.physics.mechanics.bearing_laws.registry import BEARING_LAWS, JOURNAL_LAWS
from recipsim.physics.mechanics.journal import short_journal_film

R, L, C, MU = 0.007, 0.012, 10e-6, 0.01  # the reference eccentric journal's order
DIRECTIONS = np.linspace(-math.pi, math.pi, 49)[:-1]


def _film_state(eps: float, direction: float) -> tuple[float, ...]:
    """A journal at ``eps`` on +x, not spinning, moving so that its film velocities are
    ``(A, B) = (cos direction, sin direction)`` [1/s]."""
    a, b = math.cos(direction), math.sin(direction)
    return (eps * C, 0.0, b * C, -a * C, 0.0, 0.0, R, L, C, MU)


def _relative_difference(eps: float, direction: float) -> float:
    state = _film_state(eps, direction)
    fx, fy, _ = short_journal_film(*state)
    mx, my, _ = mobility_journal_film(*state)
    return math.hypot(mx - fx, my - fy) / math.hypot(fx, fy)


def test_centred_squeeze_is_the_short_bearing_damper_exactly():
    for direction in DIRECTIONS:
        vx, vy = 0.3 * math.cos(direction), 0.3 * math.sin(direction)
        fx, fy, _ = mobility_journal_film(0.0, 0.0, vx, vy, 0.0, 0.0, R, L, C, MU)
        damper = -math.pi * MU * R * L**3 / (2.0 * C**3)
        assert fx == pytest.approx(damper * vx, rel=1e-12)
        assert fy == pytest.approx(damper * vy, rel=1e-12, abs=1e-12 * abs(damper))


@pytest.mark.parametrize(
    ("eps", "largest"),
    [(0.1, 0.005), (0.3, 0.016), (0.5, 0.037), (0.7, 0.071), (0.9, 0.125), (0.95, 0.145)],
)
def test_force_follows_the_short_law_within_bookers_approximation(eps, largest):
    worst = max(_relative_difference(eps, d) for d in DIRECTIONS)
    assert worst <= largest + 0.002
    assert worst > 0.0 or eps == 0.0  # a different law, not the short one renamed


@pytest.mark.parametrize("eps", [0.05, 0.4, 0.8, 0.97, 0.999])
def test_the_force_reproduces_the_velocity_through_the_forward_mobility(eps):
    """Booker's forward method: the load ``W u = -F`` moves the journal, relative to the
    frame at the mean spin, at ``W (c/R)^2/(mu L D) M`` times ``c``."""
    scale = (C / R) ** 2 / (MU * L * 2 * R)
    for direction in DIRECTIONS:
        state = _film_state(eps, direction)
        fx, fy, _ = mobility_journal_film(*state)
        load = math.hypot(fx, fy)
        ux, uy = -fx / load, -fy / load  # the journal frame is (x, y) here (e on +x)
        mr, mt = mobility_vector(eps, ux, uy, (L / (2 * R)) ** 2)
        b, minus_a = load * scale * mr, load * scale * mt
        assert b == pytest.approx(math.sin(direction), abs=1e-9)
        assert -minus_a == pytest.approx(math.cos(direction), abs=1e-9)


def test_the_film_only_dissipates():
    for eps in (0.0, 0.3, 0.9):
        for direction in DIRECTIONS:
            state = _film_state(eps, direction)
            fx, fy, _ = mobility_journal_film(*state)
            assert -(fx * state[2] + fy * state[3]) >= 0.0


def test_steady_load_is_ocvirks_within_the_approximation():
    """A journal turning at a fixed eccentricity (no squeeze): Ocvirk's load
    ``mu omega R L^3/(4 c^2) eps sqrt(pi^2 (1 - eps^2) + 16 eps^2)/(1 - eps^2)^2``."""
    omega = 300.0
    for eps, tolerance in ((0.2, 0.004), (0.5, 0.015), (0.8, 0.025)):
        fx, fy, _ = mobility_journal_film(eps * C, 0.0, 0.0, 0.0, omega, 0.0, R, L, C, MU)
        shape = eps * math.sqrt(math.pi**2 * (1 - eps**2) + 16 * eps**2) / (1 - eps**2) ** 2
        ocvirk = MU * omega * R * L**3 / (4 * C * C) * shape
        assert math.hypot(fx, fy) == pytest.approx(ocvirk, rel=tolerance)


def test_it_is_a_journal_law_a_case_can_name():
    law = BEARING_LAWS["mobility"]
    assert law.name in JOURNAL_LAWS
    assert law.film and not law.spring and law.table is None
