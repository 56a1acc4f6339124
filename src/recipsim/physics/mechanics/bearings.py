"""Bearing laws: force on the journal from the relative motion of two markers.

A bearing joins a marker on a journal-side body A to a marker on a bushing-side body
B (or ground). Its law sees only the relative displacement ``e = r_A - r_B``, its rate
and the spin rates of both sides about the bearing axis, and returns the force on A;
B receives the opposite force. Laws are chosen per bearing by an integer code in the
bearing's parameter row, dispatched in :func:`bearing_force`; adding a law (e.g. the
hydrodynamic ``short_journal``) means a new branch here, nothing in the bodies.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from recipsim.physics.mechanics.layout import BP_AXIS, BP_DAMPING, BP_LAW, BP_STIFFNESS, LAW_LINEAR


@njit(cache=True)
def linear_bearing_force(
    k: float, c: float, ex: float, ey: float, ez: float, vx: float, vy: float, vz: float
) -> tuple[float, float, float]:
    """Isotropic spring and dashpot, ``F = -k e - c de/dt`` (the paper's law).

    Parameters
    ----------
    k : float
        Stiffness [N/m].
    c : float
        Damping [N s/m].
    ex, ey, ez : float
        Relative displacement journal minus bushing, normal to the axis [m].
    vx, vy, vz : float
        Its time derivative [m/s].

    Returns
    -------
    fx, fy, fz : float
        Force on the journal [N].
    """
    return -k * ex - c * vx, -k * ey - c * vy, -k * ez - c * vz


@njit(cache=True)
def bearing_force(
    par: np.ndarray,
    row: int,
    ex: float,
    ey: float,
    ez: float,
    vx: float,
    vy: float,
    vz: float,
    spin_journal: float,
    spin_bushing: float,
) -> tuple[float, float, float]:
    """Force on the journal of bearing row ``row`` of ``par`` (dispatch on the law code).

    Parameters
    ----------
    par : numpy.ndarray
        Parameter array; the bearing's row starts at ``row``.
    ex, ey, ez, vx, vy, vz : float
        Relative displacement [m] and velocity [m/s], journal minus bushing, inertial.
        Components along the bearing axis are ignored.
    spin_journal, spin_bushing : float
        Angular speeds of the two sides about the bearing axis [rad/s] (used by
        hydrodynamic laws; the linear law ignores them).

    Returns
    -------
    fx, fy, fz : float
        Force on the journal [N], normal to the bearing axis.
    """
    axis = int(par[row + BP_AXIS])
    if axis == 0:
        ex = 0.0
        vx = 0.0
    elif axis == 1:
        ey = 0.0
        vy = 0.0
    else:
        ez = 0.0
        vz = 0.0
    law = int(par[row + BP_LAW])
    if law == LAW_LINEAR:
        return linear_bearing_force(
            par[row + BP_STIFFNESS], par[row + BP_DAMPING], ex, ey, ez, vx, vy, vz
        )
    raise ValueError("unknown bearing law code")


@njit(cache=True)
def bearing_spring_energy(par: np.ndarray, row: int, ex: float, ey: float, ez: float) -> float:
    """Elastic energy stored in bearing row ``row`` [J] (0 for laws without one)."""
    if int(par[row + BP_LAW]) == LAW_LINEAR:
        return 0.5 * par[row + BP_STIFFNESS] * (ex * ex + ey * ey + ez * ez)
    return 0.0
