"""Start pose and state scales of the flexible mechanism (not compiled).

:func:`initial_state` puts the bodies at their pinned positions deflected by the pinned
reactions (the quasi-static pose, which shortens the start-up transient);
:func:`state_scales` sizes each state for the absolute tolerances and the convergence
test; :func:`effective_stiffness` gives both a stiffness for every bearing law. The
state layout is :mod:`.layout`'s; the right-hand side is :mod:`.flexible`.
"""

from __future__ import annotations

import math

import numpy as np

from recipsim.physics.kinematics import piston_displacement, rod_angle, rod_centre_of_mass
from recipsim.physics.mechanics import layout as lay
from recipsim.physics.mechanics.bearing_laws.registry import law_in_row
from recipsim.physics.mechanics.bodies import rotor_marker
from recipsim.physics.mechanics.pinned import N_PIN_OUT, pinned_reactions

_ROW = lay.P_BEARINGS
_NB = lay.N_BEARING_PAR


# ------------------------------------------------------------ initial state


def initial_state(
    par: np.ndarray,
    theta: float,
    omega: float,
    gas_pressure: float | None = None,
    *,
    static_deflection: bool = True,
) -> np.ndarray:
    """State with the bodies at their pinned positions at crank angle ``theta``.

    With ``static_deflection`` each bearing is deflected by its pinned reaction at
    ``theta`` over its stiffness (the quasi-static pose, which shortens the start-up
    transient); velocities are the rigid ones (deflection rates zero).

    Parameters
    ----------
    par : numpy.ndarray
        Parameter array.
    theta : float
        Crank angle [rad].
    omega : float
        Crank speed [rad/s].
    gas_pressure : float, optional
        Cylinder pressure for the static deflection [Pa]; default the shell pressure.
    static_deflection : bool

    Returns
    -------
    numpy.ndarray
        Shape ``(N_STATE,)``.
    """
    y = np.zeros(lay.N_STATE)
    y[lay.Y_CRANK_ANGLE] = theta
    y[lay.Y_CRANK_SPEED] = omega
    if not static_deflection:
        return y
    if gas_pressure is None:
        gas_pressure = float(par[lay.P_SHELL_PRESSURE])
    out = np.zeros(N_PIN_OUT)
    pinned_reactions(theta, omega, 0.0, gas_pressure, par, out)
    big_end = _place_rotor(par, out, y, theta)
    _place_rod_and_piston(par, out, y, theta, big_end)
    return y


def _deflection(par: np.ndarray, out: np.ndarray, i: int) -> np.ndarray:
    """Bearing ``i``'s deflection (x, y) under its pinned reaction in ``out`` [m]."""
    k = effective_stiffness(par, i)
    f = out[3 * i : 3 * i + 2]
    if k <= 0.0:
        return np.zeros(2)
    e = -f / k
    clearance = par[_ROW + i * _NB + lay.BP_CLEARANCE]
    size = float(np.hypot(e[0], e[1]))
    if clearance > 0.0 and size > 0.5 * clearance:  # a film law: stay inside it
        e *= 0.5 * clearance / size
    return e


def _place_rotor(par: np.ndarray, out: np.ndarray, y: np.ndarray, theta: float) -> np.ndarray:
    """Rotor offset and tilts from the two main bearings' deflections, written into ``y``;
    returns the big end's position (x, y) [m], the eccentric bearing's deflection off."""
    r = par[lay.P_CRANK_RADIUS]
    zg = par[lay.P_ROTOR_COM_Z]
    h1, h2 = par[lay.P_PRIMARY_Z] - zg, par[lay.P_SECONDARY_Z] - zg
    e1, e2 = _deflection(par, out, lay.B_PRIMARY), _deflection(par, out, lay.B_SECONDARY)
    # marker at height h: (x_g + h sin(beta), y_g - h sin(alpha) cos(beta)), small tilts
    beta = (e1[0] - e2[0]) / (h1 - h2)
    alpha = -(e1[1] - e2[1]) / (h1 - h2)
    y[lay.Y_ROTOR_TILT_X] = alpha
    y[lay.Y_ROTOR_TILT_Y] = beta
    y[lay.Y_ROTOR_X] = e1[0] - h1 * math.sin(beta)
    y[lay.Y_ROTOR_Y] = e1[1] + h1 * math.sin(alpha) * math.cos(beta)
    ca, sa, cb, sb = math.cos(alpha), math.sin(alpha), math.cos(beta), math.sin(beta)
    pex, pey, _, _ = rotor_marker(
        y[0], y[1], 0.0, 0.0, ca, sa, cb, sb, 0.0, 0.0, 0.0,
        r * math.cos(theta), r * math.sin(theta), -zg,
    )  # fmt: skip
    e3 = _deflection(par, out, lay.B_ECCENTRIC)
    big_end: np.ndarray = np.array([pex, pey]) - e3
    return big_end


def _place_rod_and_piston(
    par: np.ndarray, out: np.ndarray, y: np.ndarray, theta: float, big_end: np.ndarray
) -> None:
    """Piston tilt and offset from its two guide films, the rod between the big end and
    the pin, written into ``y`` as departures from the rigid pose."""
    r, big_l = par[lay.P_CRANK_RADIUS], par[lay.P_ROD_LENGTH]
    u_pin = par[lay.P_PISTON_PIN_U]
    u_top, u_skirt = par[lay.P_PISTON_TOP_U], par[lay.P_PISTON_SKIRT_U]
    e5 = _deflection(par, out, lay.B_PISTON_TOP)[1]
    e6 = _deflection(par, out, lay.B_PISTON_SKIRT)[1]
    gam = math.asin((e5 - e6) / (u_top - u_skirt))
    yp = e5 - u_top * math.sin(gam)
    e4 = _deflection(par, out, lay.B_PIN)
    small_y = yp + u_pin * math.sin(gam) - e4[1]
    sphi = (small_y - big_end[1]) / big_l
    phi = math.asin(sphi)
    small_x = big_end[0] + big_l * math.cos(phi)
    pin_x = small_x + e4[0]
    xp = pin_x - u_pin * math.cos(gam)

    a = par[lay.P_ROD_COM_FRACTION]
    phi0, _, _ = rod_angle(theta, r, big_l)
    gx, gy, _, _, _, _ = rod_centre_of_mass(theta, r, big_l, a)
    xd, _, _ = piston_displacement(theta, r, big_l)
    y[lay.Y_ROD_DX] = big_end[0] + a * big_l * math.cos(phi) - gx
    y[lay.Y_ROD_DY] = big_end[1] + a * big_l * math.sin(phi) - gy
    y[lay.Y_ROD_DANGLE] = phi - phi0
    y[lay.Y_PISTON_DX] = xp - (r + big_l - xd - u_pin)
    y[lay.Y_PISTON_Y] = yp
    y[lay.Y_PISTON_TILT] = gam


def effective_stiffness(par: np.ndarray, i: int) -> float:
    """A stiffness of bearing ``i`` for start poses and tolerances [N/m]: its law's
    ``start_stiffness`` (the linear law's own, a journal film's secant stiffness at
    eccentricity ratio 0.5 at the shaft speed), 0 for a law without one (the body starts
    centred)."""
    row = _ROW + i * _NB
    law = law_in_row(par, row)
    if law.start_stiffness is None:
        return 0.0
    return law.start_stiffness(par, row, float(par[lay.P_SPEED]))


def state_scales(par: np.ndarray) -> np.ndarray:
    """Characteristic size of each state, for absolute tolerances and convergence checks.

    Deflections: ``d = 100 N / k_max``; tilts: ``d`` over the shortest lever; rates:
    those times ``sqrt(k_max / m_piston)`` (the highest bearing frequency); crank angle
    1 rad; crank speed ``max(|speed|, 1)`` rad/s.

    Returns
    -------
    numpy.ndarray
        Shape ``(N_STATE,)``, positive.
    """
    ks = [effective_stiffness(par, i) for i in range(lay.N_BEARINGS)]
    k_max = max(ks)
    d = 100.0 / k_max
    zg = par[lay.P_ROTOR_COM_Z]
    lever_rotor = min(abs(par[lay.P_PRIMARY_Z] - zg), abs(par[lay.P_SECONDARY_Z] - zg), abs(zg))
    lever_rotor = max(lever_rotor, 1e-3)
    lever_piston = max(abs(par[lay.P_PISTON_TOP_U] - par[lay.P_PISTON_SKIRT_U]), 1e-3)
    w = math.sqrt(k_max / par[lay.P_PISTON_MASS])
    q = np.full(lay.N_COORD, d)
    q[[lay.Y_ROTOR_TILT_X, lay.Y_ROTOR_TILT_Y]] = d / lever_rotor
    q[lay.Y_ROD_DANGLE] = d / par[lay.P_ROD_LENGTH]
    q[lay.Y_PISTON_TILT] = d / lever_piston
    q[lay.Y_CRANK_ANGLE] = 1.0
    v = q * w
    v[lay.Y_CRANK_ANGLE] = max(abs(par[lay.P_SPEED]), 1.0)
    return np.concatenate([q, v])
