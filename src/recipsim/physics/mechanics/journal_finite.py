"""Finite-length hydrodynamic journal bearing: the short-bearing law times a tabulated
impedance ratio from Reynolds solutions with Swift-Stieber cavitation.

For a film direction ``theta0 = atan2(B, A)`` and eccentricity ratio ``eps`` the finite
bearing's force is linear in ``V = |(A, B)|`` like the short one's (mechanics-notes 2.2),
so ``F_finite = Q(eps, theta0) F_short`` with ``F`` written as the complex number ``F_r + i
F_t`` in the frame ``(e_r, e_t)``. Q comes from the table of one L/D built by
:func:`~recipsim.physics.mechanics.journal_table.finite_journal_table` (layout there),
interpolated by bicubic Hermite on spline derivatives (C1) in ``u = -ln(1 - eps)`` and
``theta0``. The peak pressure uses the same interpolation of the tabulated ratio of the
peaks.

Range: the table spans ``0 <= eps <= EPS_MAX`` (0.99). Beyond it Q is held at its value at
``EPS_MAX`` while the short-bearing factor keeps growing (then is capped at
``FILM_ECCENTRICITY_CAP``, as in :mod:`.journal`): Q falls toward 0 as eps -> 1, so the
held value errs on the stiff side where :func:`~recipsim.physics.mechanics.journal.
journal_contact` is already carrying the load. Torques: the Couette shear of the full
film plus the pressure-gradient part ``-(|e|/2) F_t`` of this law's force; the bushing's
by :func:`~recipsim.physics.mechanics.journal.bushing_torque`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from recipsim.physics.mechanics.journal import (
    couette_torque,
    film_kinematics,
    short_film_unit_forces,
    short_journal_peak_pressure,
)
from recipsim.physics.mechanics.journal_table import (
    H_N_EPS,
    H_N_THETA0,
    H_THETA0_START,
    H_U_MAX,
    JQ_IMAG,
    JQ_PEAK,
    JQ_REAL,
    N_HEADER,
    N_NODE_VALUES,
    N_QUANTITIES,
)


@njit(cache=True)
def tabulated_ratio(
    table: np.ndarray, offset: int, eps: float, theta0: float, quantity: int
) -> float:
    """Bicubic Hermite interpolation of one tabulated quantity.

    Parameters
    ----------
    table : numpy.ndarray
        Array holding the flat table.
    offset : int
        Index where the table starts.
    eps : float
        Eccentricity ratio [-] (held at the last node beyond it).
    theta0 : float
        Film direction [rad] (any value; periodic).
    quantity : int
        0: Q_r, 1: Q_i, 2: peak-pressure ratio.

    Returns
    -------
    float
        The interpolated value [-].
    """
    n_eps = int(table[offset + H_N_EPS])
    n_theta0 = int(table[offset + H_N_THETA0])
    u_max = table[offset + H_U_MAX]
    du = u_max / (n_eps - 1)
    dtheta = 2.0 * math.pi / n_theta0
    u = min(-math.log1p(-min(eps, 1.0 - 1e-15)), u_max)
    x = u / du
    j = min(int(x), n_eps - 2)
    t = x - j
    y = (theta0 - table[offset + H_THETA0_START]) / dtheta
    m_float = math.floor(y)
    s = y - m_float
    m = int(m_float) % n_theta0
    m_next = m + 1 if m + 1 < n_theta0 else 0
    # Hermite basis: value at 0 and 1, slope at 0 and 1 (slopes scaled to the cell)
    t2 = t * t
    s2 = s * s
    hu0 = 2.0 * t2 * t - 3.0 * t2 + 1.0
    hu1 = 1.0 - hu0
    gu0 = (t2 * t - 2.0 * t2 + t) * du
    gu1 = (t2 * t - t2) * du
    ht0 = 2.0 * s2 * s - 3.0 * s2 + 1.0
    ht1 = 1.0 - ht0
    gt0 = (s2 * s - 2.0 * s2 + s) * dtheta
    gt1 = (s2 * s - s2) * dtheta
    value = 0.0
    for p in range(2):
        hu = hu0 if p == 0 else hu1
        gu = gu0 if p == 0 else gu1
        for q in range(2):
            ht = ht0 if q == 0 else ht1
            gt = gt0 if q == 0 else gt1
            node = (
                offset + N_HEADER + ((j + p) * n_theta0 + (m if q == 0 else m_next)) * N_NODE_VALUES
            )
            base = node + quantity
            value += (
                hu * ht * table[base]
                + gu * ht * table[base + N_QUANTITIES]
                + hu * gt * table[base + 2 * N_QUANTITIES]
                + gu * gt * table[base + 3 * N_QUANTITIES]
            )
    return value


@njit(cache=True)
def finite_journal_film(
    ex: float,
    ey: float,
    vx: float,
    vy: float,
    omega_journal: float,
    omega_bushing: float,
    radius: float,
    length: float,
    clearance: float,
    viscosity: float,
    table: np.ndarray,
    offset: int,
) -> tuple[float, float, float]:
    """Finite-length film force and journal torque (Swift-Stieber cavitation).

    Parameters
    ----------
    ex, ey, vx, vy, omega_journal, omega_bushing, radius, length, clearance, viscosity
        As in :func:`~recipsim.physics.mechanics.journal.short_journal_film` [SI].
    table : numpy.ndarray
        Array holding the table of this bearing's L/D (:func:`~recipsim.physics.
        mechanics.journal_table.finite_journal_table`).
    offset : int
        Index where that table starts in ``table``.

    Returns
    -------
    fx, fy : float
        Film force on the journal [N].
    torque_journal : float
        Film torque on the journal about its centre and the axis [N m].
    """
    ux, uy, eps, a, b, e_norm = film_kinematics(
        ex, ey, vx, vy, omega_journal, omega_bushing, clearance
    )
    torque = couette_torque(eps, omega_journal, omega_bushing, radius, length, clearance, viscosity)
    v = math.sqrt(a * a + b * b)
    if v == 0.0:
        return 0.0, 0.0, torque
    sr, st = short_film_unit_forces(eps, b / v, a / v)
    theta0 = math.atan2(b, a)
    qr = tabulated_ratio(table, offset, eps, theta0, JQ_REAL)
    qi = tabulated_ratio(table, offset, eps, theta0, JQ_IMAG)
    scale = viscosity * radius * length**3 * v / (clearance * clearance)
    fr = (qr * sr - qi * st) * scale
    ft = (qr * st + qi * sr) * scale
    return fr * ux - ft * uy, fr * uy + ft * ux, torque - 0.5 * e_norm * ft


@njit(cache=True)
def finite_journal_peak_pressure(
    ex: float,
    ey: float,
    vx: float,
    vy: float,
    omega_journal: float,
    omega_bushing: float,
    radius: float,
    length: float,
    clearance: float,
    viscosity: float,
    table: np.ndarray,
    offset: int,
) -> float:
    """Largest finite-bearing film pressure [Pa] (post-processing).

    The short bearing's peak times the tabulated ratio of the Reynolds solution's largest
    nodal pressure to it; arguments as in :func:`finite_journal_film`.
    """
    _, _, eps, a, b, _ = film_kinematics(ex, ey, vx, vy, omega_journal, omega_bushing, clearance)
    if a == 0.0 and b == 0.0:
        return 0.0
    ratio = tabulated_ratio(table, offset, eps, math.atan2(b, a), JQ_PEAK)
    short = short_journal_peak_pressure(
        ex, ey, vx, vy, omega_journal, omega_bushing, radius, length, clearance, viscosity
    )
    return short * max(ratio, 0.0)
