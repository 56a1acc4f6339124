"""Exact slider-crank kinematics (no pin offset), crank angle from top dead centre.

Frame: crank centre at the origin, spin axis Z, cylinder axis X, head at +X.
The crank pin is at ``r (cos theta, sin theta)``; the piston pin at ``(X_p, 0)`` with
``X_p = r cos theta + L sqrt(1 - lambda^2 sin^2 theta)``; ``lambda = r / L``.
The piston displacement from top dead centre is ``x = r + L - X_p`` so that the
cylinder volume is ``V = V_c + A_p x``.

Every function here is compiled with numba and works on scalars; derivatives are
with respect to the crank angle (multiply by omega, omega^2 for time derivatives at
constant speed).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit


@njit(cache=True)
def piston_displacement(theta: float, r: float, L: float) -> tuple[float, float, float]:
    """Piston displacement from TDC and its first two crank-angle derivatives.

    Parameters
    ----------
    theta : float
        Crank angle from top dead centre [rad].
    r, L : float
        Crank radius and connecting-rod length [m].

    Returns
    -------
    x, dx_dtheta, d2x_dtheta2 : float
        Displacement [m], [m/rad], [m/rad^2].
    """
    lam = r / L
    s = math.sin(theta)
    c = math.cos(theta)
    d = math.sqrt(1.0 - lam * lam * s * s)
    x = r * (1.0 - c) + L * (1.0 - d)
    dx = r * s * (1.0 + lam * c / d)
    d2x = r * c + r * lam * ((c * c - s * s) / d + lam * lam * s * s * c * c / (d * d * d))
    return x, dx, d2x


@njit(cache=True)
def rod_angle(theta: float, r: float, L: float) -> tuple[float, float, float]:
    """Connecting-rod angle from the +X axis and its crank-angle derivatives.

    Returns
    -------
    phi, dphi_dtheta, d2phi_dtheta2 : float
        [rad], [-], [1/rad]. ``sin(phi) = -lambda sin(theta)``.
    """
    lam = r / L
    s = math.sin(theta)
    c = math.cos(theta)
    d = math.sqrt(1.0 - lam * lam * s * s)
    phi = math.atan2(-lam * s, d)
    dphi = -lam * c / d
    d2phi = lam * s * (1.0 - lam * lam) / (d * d * d)
    return phi, dphi, d2phi


@njit(cache=True)
def rod_centre_of_mass(
    theta: float, r: float, L: float, a: float
) -> tuple[float, float, float, float, float, float]:
    """Position of the rod's centre of mass and its crank-angle derivatives.

    Parameters
    ----------
    a : float
        Fraction of the rod length from the big end (crank pin) to the centre of mass.

    Returns
    -------
    gx, gy, dgx, dgy, d2gx, d2gy : float
        Position [m] and derivatives [m/rad], [m/rad^2] in the X-Y plane.
    """
    x, dx, d2x = piston_displacement(theta, r, L)
    xp = r + L - x
    s = math.sin(theta)
    c = math.cos(theta)
    gx = (1.0 - a) * r * c + a * xp
    gy = (1.0 - a) * r * s
    dgx = -(1.0 - a) * r * s - a * dx
    dgy = (1.0 - a) * r * c
    d2gx = -(1.0 - a) * r * c - a * d2x
    d2gy = -(1.0 - a) * r * s
    return gx, gy, dgx, dgy, d2gx, d2gy


@njit(cache=True)
def inertia_torque(
    theta: float,
    omega: float,
    r: float,
    L: float,
    piston_mass: float,
    rod_mass: float,
    rod_com_fraction: float,
    rod_inertia: float,
) -> float:
    """Shaft torque that accelerates piston and rod at constant crank speed [N m].

    From the power balance ``tau * omega = dKE/dt`` with
    ``KE = omega^2/2 (m_p x'^2 + m_r |G'|^2 + I_r phi'^2)``.
    """
    _, dx, d2x = piston_displacement(theta, r, L)
    _, _, dgx, dgy, d2gx, d2gy = rod_centre_of_mass(theta, r, L, rod_com_fraction)
    _, dphi, d2phi = rod_angle(theta, r, L)
    return (
        omega
        * omega
        * (
            piston_mass * dx * d2x
            + rod_mass * (dgx * d2gx + dgy * d2gy)
            + rod_inertia * dphi * d2phi
        )
    )


def piston_displacement_array(theta: np.ndarray, r: float, L: float) -> np.ndarray:
    """Vectorised :func:`piston_displacement` (displacement only) [m]."""
    lam = r / L
    s = np.sin(theta)
    return r * (1.0 - np.cos(theta)) + L * (1.0 - np.sqrt(1.0 - lam * lam * s * s))


def piston_velocity_array(theta: np.ndarray, r: float, L: float) -> np.ndarray:
    """Vectorised first derivative of :func:`piston_displacement`, dx/dtheta [m/rad]."""
    lam = r / L
    s = np.sin(theta)
    c = np.cos(theta)
    return r * s * (1.0 + lam * c / np.sqrt(1.0 - lam * lam * s * s))
