"""The piston's pose in the flexible crank train's state: crown displacement from its
rigid TDC position, lateral offset of its axis from the bore axis, tilt (state layout
:mod:`.layout`)."""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from recipsim.physics.kinematics import piston_displacement
from recipsim.physics.mechanics import layout as lay


@njit(cache=True)
def piston_axial_displacement(y: np.ndarray, par: np.ndarray) -> tuple[float, float]:
    """Crown displacement from its rigid TDC position and its rate.

    The cylinder volume is ``V_clearance + A_p * x`` with this ``x``; it equals the
    slider-crank displacement when the bearings are rigid.

    Returns
    -------
    x, dx_dt : float
        [m], [m/s].
    """
    r = par[lay.P_CRANK_RADIUS]
    big_l = par[lay.P_ROD_LENGTH]
    th = y[lay.Y_CRANK_ANGLE]
    xd, dxd, _ = piston_displacement(th, r, big_l)
    u_crown = par[lay.P_PISTON_CROWN_U]
    gam = y[lay.Y_PISTON_TILT]
    # crown X = (r + L - x_kin - u_pin + dX) + u_crown cos(gam); u_crown - u_pin = pin offset
    x = xd - y[lay.Y_PISTON_DX] + u_crown * (1.0 - math.cos(gam))
    dx = dxd * y[lay.Y_CRANK_SPEED] - y[lay.Y_PISTON_DVX]
    dx += u_crown * math.sin(gam) * y[lay.Y_PISTON_TILT_RATE]
    return x, dx


@njit(cache=True)
def piston_lateral_offset(y: np.ndarray, par: np.ndarray, from_crown: float) -> float:
    """Lateral (Y) offset of the piston axis from the bore axis [m].

    Parameters
    ----------
    y : numpy.ndarray
        State.
    par : numpy.ndarray
        Parameters.
    from_crown : float
        Axial station below the crown [m] (0: crown, piston length: skirt end).
    """
    u = par[lay.P_PISTON_CROWN_U] - from_crown
    return y[lay.Y_PISTON_Y] + u * math.sin(y[lay.Y_PISTON_TILT])


@njit(cache=True)
def piston_tilt(y: np.ndarray) -> float:
    """Piston tilt about the pin axis Z [rad] (positive: crown towards +Y)."""
    return y[lay.Y_PISTON_TILT]
