"""The suction path's tube laws against their closed forms.

- The half-sine pulse factors: for a film law ``Re^p`` the factor is 1 at ``p = 1`` (a
  linear law averages to its value at the mean flow) and ``pi^2 / 4`` at ``p = 2`` (the
  mean of ``v^2``), and at ``p = 0.8`` it equals a direct quadrature of the pulse to 1e-9
  (the quadrature's own error on 200,000 midpoints of a smooth integrand is below that).
- The laminar tube drop without minor losses is Hagen-Poiseuille's
  ``128 mu L Q / (pi D^4)`` to round-off; the turbulent one is Blasius' to round-off.
- A film in series with a wall never exceeds either.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from recipsim.physics.thermo.suction_path import (
    HALF_SINE_VELOCITY_SQUARE_FACTOR,
    darcy_friction_factor,
    half_sine_film_factor,
    reynolds_number,
    series_conductance,
    tube_film_coefficient,
    tube_pressure_drop,
)


def _pulse_mean(power: float) -> float:
    """mean(q^power) / mean(q)^power of a half-sine draw over half a period, by quadrature."""
    n = 200_000
    t = (np.arange(n) + 0.5) / n  # one period
    q = np.where(t < 0.5, np.sin(2.0 * math.pi * t), 0.0)
    return float(np.mean(q**power) / np.mean(q) ** power)


@pytest.mark.parametrize("power", [0.8, 1.0, 2.0])
def test_half_sine_factor_matches_quadrature(power):
    assert half_sine_film_factor(power) == pytest.approx(_pulse_mean(power), rel=1e-9)


def test_half_sine_limits():
    assert half_sine_film_factor(1.0) == pytest.approx(1.0, rel=1e-14)
    assert half_sine_film_factor(2.0) == pytest.approx(HALF_SINE_VELOCITY_SQUARE_FACTOR, rel=1e-14)
    assert 0.84 < half_sine_film_factor(0.8) < 0.86


def test_laminar_drop_is_hagen_poiseuille():
    mu, rho, d, length = 1.0e-5, 1.5, 4.0e-3, 0.2
    mdot = 1.0e-5  # Re = 318
    assert reynolds_number(mdot, d, mu) < 2300.0
    dp = tube_pressure_drop(mdot, rho, mu, d, length, 0.0, 1.0)
    q = mdot / rho
    assert dp == pytest.approx(128.0 * mu * length * q / (math.pi * d**4), rel=1e-12)


def test_turbulent_drop_is_blasius_with_minor_losses_and_pulsation():
    mu, rho, d, length = 8.3e-6, 1.4, 6.2e-3, 0.03
    mdot = 3.0e-4
    re = reynolds_number(mdot, d, mu)
    assert re > 2300.0
    area = math.pi * d * d / 4.0
    v = mdot / (rho * area)
    k = 1.5 + 0.316 * re**-0.25 * length / d
    expected = 2.0 * k * 0.5 * rho * v * v
    assert tube_pressure_drop(mdot, rho, mu, d, length, 1.5, 2.0) == pytest.approx(expected, 1e-12)
    assert darcy_friction_factor(0.0) == 0.0


def test_film_goes_as_flow_to_the_power_0p8_when_turbulent():
    args = (6.2e-3, 8.3e-6, 0.02, 0.8, 1.0)
    h1 = tube_film_coefficient(3.0e-4, *args)
    h2 = tube_film_coefficient(6.0e-4, *args)
    assert h2 / h1 == pytest.approx(2.0**0.8, rel=1e-12)
    # no flow: the laminar floor Nu = 3.66
    assert tube_film_coefficient(0.0, *args) == pytest.approx(3.66 * 0.02 / 6.2e-3)


def test_series_conductance_is_below_both():
    assert series_conductance(0.2, 0.3) == pytest.approx(0.12)
    assert series_conductance(0.0, 0.3) == 0.0
