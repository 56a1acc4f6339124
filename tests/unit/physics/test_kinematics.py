"""Slider-crank kinematics and inertia torque against closed forms and finite differences."""

import math

import numpy as np
import pytest

from recipsim.physics.kinematics import (
    inertia_torque,
    piston_displacement,
    piston_displacement_array,
    piston_velocity_array,
    rod_angle,
    rod_centre_of_mass,
)

R, L = 9.2e-3, 36e-3


def test_dead_centres():
    assert piston_displacement(0.0, R, L)[0] == pytest.approx(0.0, abs=1e-15)
    assert piston_displacement(math.pi, R, L)[0] == pytest.approx(2 * R, rel=1e-14)
    # velocity vanishes at both dead centres
    assert piston_displacement(0.0, R, L)[1] == pytest.approx(0.0, abs=1e-15)
    assert piston_displacement(math.pi, R, L)[1] == pytest.approx(0.0, abs=1e-15)


def test_closed_form_at_quarter_turn():
    # at 90 deg: x = r + L (1 - sqrt(1 - l^2)), dx/dtheta = r, d2x = -r l / sqrt(1 - l^2)
    lam = R / L
    x, dx, d2x = piston_displacement(math.pi / 2, R, L)
    assert x == pytest.approx(R + L * (1 - math.sqrt(1 - lam**2)), rel=1e-14)
    assert dx == pytest.approx(R, rel=1e-14)
    assert d2x == pytest.approx(-R * lam / math.sqrt(1 - lam**2), rel=1e-12)


@pytest.mark.parametrize("theta", np.linspace(0.1, 6.2, 13))
def test_derivatives_match_finite_differences(theta):
    # central differences with h = 1e-5 are accurate to ~1e-10 relative here
    h = 1e-5
    for fun in (
        lambda t: piston_displacement(t, R, L),
        lambda t: rod_angle(t, R, L),
    ):
        f0, fp, fm = fun(theta), fun(theta + h), fun(theta - h)
        assert (fp[0] - fm[0]) / (2 * h) == pytest.approx(f0[1], rel=1e-7, abs=1e-12)
        assert (fp[1] - fm[1]) / (2 * h) == pytest.approx(f0[2], rel=1e-6, abs=1e-10)
    g0 = rod_centre_of_mass(theta, R, L, 0.35)
    gp = rod_centre_of_mass(theta + h, R, L, 0.35)
    gm = rod_centre_of_mass(theta - h, R, L, 0.35)
    assert (gp[0] - gm[0]) / (2 * h) == pytest.approx(g0[2], rel=1e-7, abs=1e-12)
    assert (gp[1] - gm[1]) / (2 * h) == pytest.approx(g0[3], rel=1e-7, abs=1e-12)
    assert (gp[2] - gm[2]) / (2 * h) == pytest.approx(g0[4], rel=1e-6, abs=1e-10)


def test_vectorised_matches_scalar():
    theta = np.linspace(0, 2 * np.pi, 37)
    xs = np.array([piston_displacement(t, R, L)[0] for t in theta])
    np.testing.assert_allclose(piston_displacement_array(theta, R, L), xs, rtol=1e-14, atol=1e-18)
    dxs = np.array([piston_displacement(t, R, L)[1] for t in theta])
    np.testing.assert_allclose(piston_velocity_array(theta, R, L), dxs, rtol=1e-14, atol=1e-18)


def test_inertia_torque_is_rate_of_kinetic_energy():
    # tau * omega = dKE/dt at constant omega; KE(theta) from the derivatives; over a
    # revolution the inertia torque does no net work
    omega = 366.5
    mp, mr, a, ir = 0.035, 0.030, 0.35, 4e-6

    def kinetic(t):
        _, dx, _ = piston_displacement(t, R, L)
        _, _, dgx, dgy, _, _ = rod_centre_of_mass(t, R, L, a)
        _, dphi, _ = rod_angle(t, R, L)
        return 0.5 * omega**2 * (mp * dx**2 + mr * (dgx**2 + dgy**2) + ir * dphi**2)

    h = 1e-6
    for t in np.linspace(0.2, 6.0, 7):
        dke_dtheta = (kinetic(t + h) - kinetic(t - h)) / (2 * h)
        assert inertia_torque(t, omega, R, L, mp, mr, a, ir) == pytest.approx(dke_dtheta, rel=1e-6)
    theta = np.linspace(0, 2 * np.pi, 2001)[:-1]
    tau = np.array([inertia_torque(t, omega, R, L, mp, mr, a, ir) for t in theta])
    assert abs(tau.mean()) < 1e-9 * np.abs(tau).max()
