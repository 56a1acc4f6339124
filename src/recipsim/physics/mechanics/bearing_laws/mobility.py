"""The mobility law of a journal bearing: Booker's mobility method for the short bearing
in the closed form of its mobility vector, inverted for the film force.

Booker's mobility method (Booker 1965) gives the velocity of the journal centre,
relative to the frame turning at the mean spin ``omega_mean = (omega_journal +
omega_bushing)/2``, from the load ``W`` on the journal::

    (d e/dt - omega_mean z x e) / c = W (c/R)^2 / (mu L D) M(zeta, kappa)

with ``M = M_zeta u + M_kappa u_perp`` in the frame of the load's direction ``u``
(``u_perp = z x u``), ``zeta = e.u/c`` and ``kappa = e.u_perp/c``, and for the short bearing
with Guembel cavitation the closed forms (Booker's approximation, as given by Flores,
Ambrosio, Claro and Pimenta 2006, "Journal bearings subjected to dynamic loads: the
analytical mobility method", Mecanica Experimental 13, 115-127)::

    M_zeta  = (1 - zeta)^(5/2) / (pi (L/D)^2)
    M_kappa = -4 kappa (1 - zeta)^(3/2) / (pi^2 (L/D)^2)

A force law needs the inverse: the film's velocities ``A``, ``B``
(:func:`recipsim.physics.mechanics.journal.film_kinematics`) give the relative velocity
``c (B e_r - A e_t)``; the load direction ``u`` is the one whose ``M`` points along it.
Since ``M . u = M_zeta > 0``, ``u`` lies within 90 deg of the velocity, and the direction
of ``M`` turns monotonically with ``u``: one root on that half-circle. In the tangent of
half the angle from the velocity to ``u`` the condition is a quartic, solved by Newton's
method kept in a narrowing bracket, with no trigonometric call (:func:`load_direction`).
``W`` follows from the lengths; the film force on the
journal is ``-W u``. Centred (``e = 0``) this is exactly the short law's squeeze damper
``-pi mu R L^3 v/(2 c^3)``; elsewhere Booker's closed forms approximate the short
bearing: the force is within 1.6 % of :mod:`.short_journal`'s up to ``eps = 0.3``, 3.7 %
at 0.5, 7.1 % at 0.7 and 14.5 % at 0.95 over all film directions, and the steady load
within 2.2 % of Ocvirk's up to ``eps = 0.8`` (``tests/physics/test_journal_mobility.py``).

The journal's torque: the Couette shear of the full film plus the pressure-gradient part
``-(|e|/2) F_t``, as the short law's (:mod:`recipsim.physics.mechanics.journal`); the
asperity contact is added by the registry. The peak film pressure (a post-processing
output) is the short bearing's scaled to this law's load.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from recipsim.physics.mechanics.bearing_laws.law import (
    FILM_OUTPUTS,
    BearingLaw,
    journal_film_geometry,
)
from recipsim.physics.mechanics.bearing_laws.short_journal import film_secant_stiffness
from recipsim.physics.mechanics.journal import (
    couette_torque,
    film_kinematics,
    short_journal_film,
    short_journal_peak_pressure,
)
from recipsim.physics.mechanics.layout import (
    JOURNAL_NAMES,
)

CODE = 4

LAW = BearingLaw(
    name="mobility",
    code=CODE,
    summary="Booker's mobility method for the short bearing (closed-form mobility "
    "vector), inverted for the film force; asperity contact",
    source="Booker (1965), J. Basic Eng. 87, 537-546; the closed forms as given by "
    "Flores, Ambrosio, Claro & Pimenta (2006), Mecanica Experimental 13, 115-127",
    bearings=JOURNAL_NAMES,
    start_stiffness=film_secant_stiffness,
    outputs=FILM_OUTPUTS,
)

#: Newton's step on ``t = tan(delta/2)`` below which the next one is taken as the last:
#: the error after it is of order the square of this (quadratic convergence).
_LAST_STEP = 1e-8
_MAX_ITERATIONS = 60


@njit(cache=True)
def mobility_vector(
    eps: float, cos_u: float, sin_u: float, slenderness_squared: float
) -> tuple[float, float]:
    """Booker's short-bearing mobility ``M`` in the frame ``(e_r, e_t)`` [-].

    Parameters
    ----------
    eps : float
        Eccentricity ratio, ``0 <= eps < 1`` [-] (``e = eps c e_r``).
    cos_u, sin_u : float
        The load direction ``u`` in the frame ``(e_r, e_t)``.
    slenderness_squared : float
        ``(L/D)^2`` [-].
    """
    zeta = eps * cos_u
    kappa = -eps * sin_u
    one_minus = 1.0 - zeta
    root = math.sqrt(one_minus)
    m_zeta = one_minus * one_minus * root / (math.pi * slenderness_squared)
    m_kappa = -4.0 * kappa * one_minus * root / (math.pi * math.pi * slenderness_squared)
    return m_zeta * cos_u - m_kappa * sin_u, m_zeta * sin_u + m_kappa * cos_u


@njit(cache=True)
def load_direction(eps: float, cos_v: float, sin_v: float) -> tuple[float, float]:
    """The load direction ``u`` (cosine, sine in the frame ``(e_r, e_t)``) whose mobility
    points along the unit velocity ``(cos_v, sin_v)``.

    ``M`` is ``u`` turned by ``phi`` with ``tan(phi) = 4 eps sin(u)/(pi (1 - eps cos(u)))``
    (the ratio ``M_kappa/M_zeta``), so with ``u`` the velocity turned by ``delta`` the
    root is ``pi (1 - eps cos u) sin(delta) + 4 eps sin(u) cos(delta) = 0``. In
    ``t = tan(delta/2)`` that is the quartic ``a0 + a1 t + a2 t^2 + a3 t^3 + a0 t^4`` with
    one root in ``(-1, 1)`` (``delta`` within 90 deg of the velocity; the quartic is
    ``-4 pi (1 - eps sin v) < 0`` at ``t = -1`` and ``4 pi (1 + eps sin v) > 0`` at 1):
    Newton's method from its linear root, kept in the bracket, with no trigonometric
    call (the direction follows from ``t`` rationally).
    """
    a0 = 4.0 * eps * sin_v
    k = (8.0 - 2.0 * math.pi) * eps * cos_v
    a1 = 2.0 * math.pi + k
    a2 = (math.pi - 2.0) * a0
    a3 = 2.0 * math.pi - k
    lo = -1.0
    hi = 1.0
    t = min(max(-a0 / a1, -0.5), 0.5)
    last = False
    for _ in range(_MAX_ITERATIONS):
        g = a0 + t * (a1 + t * (a2 + t * (a3 + t * a0)))
        slope = a1 + t * (2.0 * a2 + t * (3.0 * a3 + t * 4.0 * a0))
        if last:  # the step after a small one, unbracketed: its error is of order its square
            t -= g / slope
            break
        if g < 0.0:
            lo = t
        elif g > 0.0:
            hi = t
        else:
            break
        step = g / slope if slope > 0.0 else 2.0
        t_new = t - step
        if not lo < t_new < hi:
            t_new = 0.5 * (lo + hi)
            step = t - t_new
        t = t_new
        last = abs(step) < _LAST_STEP
    w = 1.0 / (1.0 + t * t)
    cos_d = (1.0 - t * t) * w
    sin_d = 2.0 * t * w
    return cos_v * cos_d - sin_v * sin_d, sin_v * cos_d + cos_v * sin_d


@njit(cache=True)
def mobility_journal_film(
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
) -> tuple[float, float, float]:
    """Film force on the journal [N] and its torque [N m] by the mobility method;
    arguments as :func:`recipsim.physics.mechanics.journal.short_journal_film` [SI]."""
    ux, uy, eps, a, b, e_norm = film_kinematics(
        ex, ey, vx, vy, omega_journal, omega_bushing, clearance
    )
    torque = couette_torque(eps, omega_journal, omega_bushing, radius, length, clearance, viscosity)
    speed = math.sqrt(a * a + b * b)
    if speed == 0.0:
        return 0.0, 0.0, torque
    diameter = 2.0 * radius
    cos_u, sin_u = load_direction(eps, b / speed, -a / speed)
    # |M| = (1 - zeta)^(3/2) sqrt(pi^2 (1 - zeta)^2 + 16 kappa^2) / (pi^2 (L/D)^2)
    one_minus = 1.0 - eps * cos_u
    kappa = eps * sin_u
    mobility = (
        one_minus
        * math.sqrt(one_minus * (math.pi**2 * one_minus * one_minus + 16.0 * kappa * kappa))
        * (diameter / length) ** 2
        / math.pi**2
    )
    mobility_scale = (clearance / radius) ** 2 / (viscosity * length * diameter)
    load = speed / (mobility_scale * mobility)
    fr = -load * cos_u
    ft = -load * sin_u
    return fr * ux - ft * uy, fr * uy + ft * ux, torque - 0.5 * e_norm * ft


@njit(cache=True)
def mobility_film(
    par: np.ndarray,
    row: int,
    tables: np.ndarray,
    ex: float,
    ey: float,
    vx: float,
    vy: float,
    spin_journal: float,
    spin_bushing: float,
) -> tuple[float, float, float]:
    """Film force [N] and journal torque [N m] (signature: :mod:`.law`)."""
    radius, length, clearance, viscosity = journal_film_geometry(par, row)
    return mobility_journal_film(
        ex, ey, vx, vy, spin_journal, spin_bushing, radius, length, clearance, viscosity
    )


@njit(cache=True)
def mobility_peak_pressure(
    par: np.ndarray,
    row: int,
    tables: np.ndarray,
    ex: float,
    ey: float,
    vx: float,
    vy: float,
    spin_journal: float,
    spin_bushing: float,
) -> float:
    """Largest film pressure [Pa] (signature: :mod:`.law`): the mobility method gives no
    pressure field, so the short bearing's peak at the same state, scaled by the ratio of
    the mobility's load to the short bearing's (the same film shape)."""
    radius, length, clearance, mu = journal_film_geometry(par, row)
    fx, fy, _ = mobility_journal_film(ex, ey, vx, vy, spin_journal, spin_bushing, radius,
                                      length, clearance, mu)  # fmt: skip
    sx, sy, _ = short_journal_film(ex, ey, vx, vy, spin_journal, spin_bushing, radius, length,
                                   clearance, mu)  # fmt: skip
    short = math.sqrt(sx * sx + sy * sy)
    if short == 0.0:
        return 0.0
    peak = short_journal_peak_pressure(ex, ey, vx, vy, spin_journal, spin_bushing, radius,
                                       length, clearance, mu)  # fmt: skip
    return peak * math.sqrt(fx * fx + fy * fy) / short
