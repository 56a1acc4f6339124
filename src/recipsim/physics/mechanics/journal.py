"""Hydrodynamic short journal bearing (Ocvirk, Guembel cavitation) and asperity contact.

Conventions (``docs/references/mechanics-notes.md`` section 2.1): ``e = r_journal -
r_bushing`` in the plane normal to the bearing axis, its rate ``v``, absolute spins
``omega_journal`` and ``omega_bushing`` about the axis (+Z, right-handed). With ``c``
the radial clearance, ``eps = |e|/c``, ``e_r = e/|e|``, ``e_t = z x e_r``:

- squeeze ``B = (e . v)/(c |e|)`` (the rate of ``eps``);
- wedge ``A = eps (omega_mean - phi_dot) = eps omega_mean - (e_t . v)/c`` with
  ``omega_mean = (omega_journal + omega_bushing)/2`` (frame-invariant).

The short-bearing film pressure, integrated over the length, is
``p(theta) = (mu L^3/c^2) (A sin theta - B cos theta)/(1 + eps cos theta)^3`` with theta
from the thickest film. It is kept only where it is positive (Guembel, half-Sommerfeld),
which is the half-circle ``(theta0, theta0 + pi)`` with ``tan theta0 = B/A``: this moving
boundary is exact for any mix of rotation and squeeze, unlike the fixed ``(0, pi)`` film
that is right only for ``B = 0``. For a fixed ``theta0`` the force is linear in ``(A, B)``
and Booker's integrals give it in closed form (no ``1/eps`` singularity, so ``e = 0`` is
regular: there the force is the squeeze damper ``-pi mu R L^3 v/(2 c^3)``).

Forces are on the journal, the bushing gets the opposite force; torques are about the
bearing axis. The journal's friction torque is the Couette shear of a full 360 deg film
(Petroff at ``e = 0``) plus the pressure-gradient shear, which integrates exactly to
``-(|e|/2) F_t``; the bushing's follows from the film's moment balance
(:func:`bushing_torque`). With these, the power taken from the bodies,
``-(F.v + T_j omega_j + T_b omega_b)``, equals the Couette dissipation plus
``c (A F_t - B F_r) >= 0``.

At ``eps >= FILM_ECCENTRICITY_CAP`` the film law is evaluated at the capped eccentricity
(same direction, same velocities): it stays finite and continuous there (its
derivatives are not), and :func:`journal_contact` carries the rest of the load. It never
divides by zero, for any finite input.
"""

from __future__ import annotations

import math

from numba import njit

#: Largest eccentricity ratio at which the film law is evaluated [-]. Beyond it the film
#: force is that of the capped eccentricity; 1e-3 c is 10 nm for the reference bearings,
#: far below the roughness at which :func:`journal_contact` has already taken over.
FILM_ECCENTRICITY_CAP = 0.999

#: Film thickness below which asperities touch [m]. Ground steel journals have an Rq of
#: about 0.1-0.2 um and fine-bored cast-iron or bronze bushings about 0.3-0.4 um, so the
#: composite roughness is sigma ~ 0.35 um; mixed lubrication begins near h/sigma ~ 3.
DEFAULT_CONTACT_FILM = 1.0e-6

#: Penalty stiffness of the asperity contact [N/m]. It carries 5 kN (eight times the
#: reference eccentric bearing's 600 N peak) at half the contact film, so the journal never
#: reaches the sleeve (|e| < c) under a few kN even with no film at all. It is of the order
#: of the elastic stiffness of a steel journal pressed into a conforming cast-iron bore
#: (E' L ~ 1e9-1e10 N/m for L ~ 10-20 mm) and is a penalty, not a measured value.
DEFAULT_CONTACT_STIFFNESS = 1.0e10

#: Boundary-lubrication friction coefficient of steel on cast iron or bronze with oil [-].
DEFAULT_FRICTION_COEFFICIENT = 0.1

#: Sliding speed over which Coulomb friction is regularised (tanh-like ramp) [m/s];
#: 1e-3 m/s is 0.04 % of the reference journal's surface speed (2.6 m/s).
DEFAULT_SLIP_SPEED = 1.0e-3


@njit(cache=True)
def short_film_unit_forces(eps: float, s0: float, c0: float) -> tuple[float, float]:
    """Short-bearing Guembel force per unit ``mu R L^3 V/c^2`` for a film direction.

    Parameters
    ----------
    eps : float
        Eccentricity ratio, ``0 <= eps < 1`` [-].
    s0, c0 : float
        ``sin theta0 = B/V`` and ``cos theta0 = A/V`` of the film direction [-].

    Returns
    -------
    fr, ft : float
        Radial and tangential force components on the journal [-] (Booker's integrals:
        ``fr = c0 J11 - s0 J02``, ``ft = c0 J20 - s0 J11``).
    """
    one_m = 1.0 - eps * eps
    r = math.sqrt(one_m)
    d = 1.0 - eps * eps * c0 * c0
    d = d * d
    k = (math.pi + 2.0 * math.atan(eps * s0 / r)) / r
    j11 = -2.0 * eps * c0 * c0 * c0 / d
    j20 = (k + 2.0 * eps * s0 * (1.0 - (2.0 - eps * eps) * c0 * c0) / d) / (2.0 * one_m)
    j02 = (
        (1.0 + 2.0 * eps * eps) * k + 2.0 * eps * s0 * (3.0 + (2.0 - 5.0 * eps * eps) * c0 * c0) / d
    ) / (2.0 * one_m * one_m)
    return c0 * j11 - s0 * j02, c0 * j20 - s0 * j11


@njit(cache=True)
def film_kinematics(
    ex: float,
    ey: float,
    vx: float,
    vy: float,
    omega_journal: float,
    omega_bushing: float,
    clearance: float,
) -> tuple[float, float, float, float, float, float]:
    """Film frame and film velocities of a journal, eccentricity capped.

    Parameters
    ----------
    ex, ey : float
        Journal centre minus bushing centre [m].
    vx, vy : float
        Its rate [m/s].
    omega_journal, omega_bushing : float
        Absolute spins about the axis [rad/s].
    clearance : float
        Radial clearance [m].

    Returns
    -------
    ux, uy : float
        Unit vector ``e_r`` [-] (``(1, 0)`` at ``e = 0``, where the law does not depend
        on it).
    eps : float
        Eccentricity ratio used by the film law, ``min(|e|/c, FILM_ECCENTRICITY_CAP)`` [-].
    wedge, squeeze : float
        ``A = eps (omega_mean - phi_dot)`` and ``B = d eps/dt`` [1/s].
    e_norm : float
        ``|e|`` [m] (not capped).
    """
    e_norm = math.sqrt(ex * ex + ey * ey)
    if e_norm > 1e-14 * clearance:
        ux = ex / e_norm
        uy = ey / e_norm
    else:
        ux = 1.0
        uy = 0.0
    eps_true = e_norm / clearance
    eps = min(eps_true, FILM_ECCENTRICITY_CAP)
    scale = eps / eps_true if eps_true > FILM_ECCENTRICITY_CAP else 1.0
    v_radial = vx * ux + vy * uy
    v_tangential = vy * ux - vx * uy
    wedge = eps * 0.5 * (omega_journal + omega_bushing) - scale * v_tangential / clearance
    squeeze = v_radial / clearance
    return ux, uy, eps, wedge, squeeze, e_norm


@njit(cache=True)
def couette_torque(
    eps: float,
    omega_journal: float,
    omega_bushing: float,
    radius: float,
    length: float,
    clearance: float,
    viscosity: float,
) -> float:
    """Couette shear torque of a full 360 deg film on the journal [N m].

    ``-2 pi mu R^3 L (omega_journal - omega_bushing)/(c sqrt(1 - eps^2))``; Petroff's law
    at ``eps = 0``. Arguments as in :func:`short_journal_film` (``eps`` [-], below 1).
    """
    return (
        -2.0
        * math.pi
        * viscosity
        * radius**3
        * length
        * (omega_journal - omega_bushing)
        / (clearance * math.sqrt(1.0 - eps * eps))
    )


@njit(cache=True)
def short_journal_film(
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
    """Short-bearing (Ocvirk) film force and journal torque, Guembel cavitation.

    Parameters
    ----------
    ex, ey : float
        Journal centre minus bushing centre, normal to the axis [m].
    vx, vy : float
        Its rate [m/s].
    omega_journal, omega_bushing : float
        Absolute spins of journal and bushing about the axis (+Z) [rad/s].
    radius : float
        Journal radius R [m].
    length : float
        Bearing length L [m].
    clearance : float
        Radial clearance c [m].
    viscosity : float
        Oil dynamic viscosity mu [Pa s].

    Returns
    -------
    fx, fy : float
        Film force on the journal [N] (the bushing gets the opposite).
    torque_journal : float
        Film torque on the journal about its centre and the axis [N m]: Couette shear of
        the full film plus the pressure-gradient part ``-(|e|/2) F_t``.
    """
    ux, uy, eps, a, b, e_norm = film_kinematics(
        ex, ey, vx, vy, omega_journal, omega_bushing, clearance
    )
    torque = couette_torque(eps, omega_journal, omega_bushing, radius, length, clearance, viscosity)
    v = math.sqrt(a * a + b * b)
    if v == 0.0:
        return 0.0, 0.0, torque
    fr, ft = short_film_unit_forces(eps, b / v, a / v)
    scale = viscosity * radius * length**3 * v / (clearance * clearance)
    fr *= scale
    ft *= scale
    return fr * ux - ft * uy, fr * uy + ft * ux, torque - 0.5 * e_norm * ft


@njit(cache=True)
def bushing_torque(ex: float, ey: float, fx: float, fy: float, torque_journal: float) -> float:
    """Film (or contact) torque on the bushing about its centre and the axis [N m].

    From the moment balance of the massless film: ``-torque_journal - (e x F)_z``.

    Parameters
    ----------
    ex, ey : float
        Journal centre minus bushing centre [m].
    fx, fy : float
        Force on the journal [N].
    torque_journal : float
        Torque on the journal about its centre [N m].
    """
    return -torque_journal - (ex * fy - ey * fx)


@njit(cache=True)
def journal_contact(
    ex: float,
    ey: float,
    vx: float,
    vy: float,
    omega_journal: float,
    omega_bushing: float,
    radius: float,
    clearance: float,
    contact_film: float,
    contact_stiffness: float,
    friction_coefficient: float,
    slip_speed: float = DEFAULT_SLIP_SPEED,
) -> tuple[float, float, float]:
    """Asperity (penalty) contact with regularised Coulomb friction.

    Once the minimum film ``h_min = c - |e|`` falls below ``contact_film`` the normal force
    ``N = k (contact_film - h_min)`` pushes the journal back along ``-e_r`` (zero at the
    onset: the force is continuous). Friction ``-friction_coefficient N s/sqrt(s^2 +
    slip_speed^2)`` acts along ``e_t`` against the sliding speed of the journal surface on
    the bushing at the contact point, ``s = (e_t . v) + R omega_j - (R + |e|) omega_b``
    (zero for a rigid rotation of the pair), with the torque ``R F_t`` on the journal; the
    bushing's follows from :func:`bushing_torque`. No contact damping: the squeeze film
    damps the approach.

    Parameters
    ----------
    ex, ey, vx, vy, omega_journal, omega_bushing, radius, clearance : float
        As in :func:`short_journal_film` [m, m/s, rad/s].
    contact_film : float
        Film thickness at which contact begins [m] (``DEFAULT_CONTACT_FILM``).
    contact_stiffness : float
        Penalty stiffness [N/m] (``DEFAULT_CONTACT_STIFFNESS``).
    friction_coefficient : float
        Coulomb coefficient [-] (``DEFAULT_FRICTION_COEFFICIENT``).
    slip_speed : float, optional
        Regularisation speed of the friction [m/s].

    Returns
    -------
    fx, fy : float
        Contact force on the journal [N].
    torque_journal : float
        Friction torque on the journal about its centre [N m].
    """
    e_norm = math.sqrt(ex * ex + ey * ey)
    penetration = e_norm - (clearance - contact_film)
    if penetration <= 0.0 or e_norm == 0.0:
        return 0.0, 0.0, 0.0
    ux = ex / e_norm
    uy = ey / e_norm
    normal = contact_stiffness * penetration
    slip = vy * ux - vx * uy + radius * omega_journal - (radius + e_norm) * omega_bushing
    ft = -friction_coefficient * normal * slip / math.sqrt(slip * slip + slip_speed * slip_speed)
    return -normal * ux - ft * uy, -normal * uy + ft * ux, radius * ft


@njit(cache=True)
def _unit_pressure(t: float, theta0: float, eps: float) -> float:
    """``sin t/(1 + eps cos(theta0 + t))^3``: the mid-plane pressure shape [-]."""
    h = 1.0 + eps * math.cos(theta0 + t)
    return math.sin(t) / (h * h * h)


@njit(cache=True)
def film_peak_shape(eps: float, theta0: float) -> float:
    """Largest ``sin(theta - theta0)/(1 + eps cos theta)^3`` over the positive film [-].

    A scan of 256 points over ``(theta0, theta0 + pi)`` then a golden-section search
    around the best point (to 1e-12 rad).
    """
    n = 256
    step = math.pi / n
    best_t = 0.5 * math.pi
    best = -1.0
    for i in range(1, n):
        value = _unit_pressure(i * step, theta0, eps)
        if value > best:
            best = value
            best_t = i * step
    lo = best_t - step
    hi = best_t + step
    golden = 0.5 * (math.sqrt(5.0) - 1.0)
    x1 = hi - golden * (hi - lo)
    x2 = lo + golden * (hi - lo)
    f1 = _unit_pressure(x1, theta0, eps)
    f2 = _unit_pressure(x2, theta0, eps)
    while hi - lo > 1e-12:
        if f1 < f2:
            lo = x1
            x1 = x2
            f1 = f2
            x2 = lo + golden * (hi - lo)
            f2 = _unit_pressure(x2, theta0, eps)
        else:
            hi = x2
            x2 = x1
            f2 = f1
            x1 = hi - golden * (hi - lo)
            f1 = _unit_pressure(x1, theta0, eps)
    return max(best, f1, f2)


@njit(cache=True)
def short_journal_peak_pressure(
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
) -> float:
    """Largest short-bearing film pressure (mid-plane, Guembel film) [Pa].

    ``p(theta, 0) = (3 mu L^2/(2 c^2)) V sin(theta - theta0)/(1 + eps cos theta)^3``
    maximised over the positive film; arguments as in :func:`short_journal_film`.
    Post-processing only.
    """
    _, _, eps, a, b, _ = film_kinematics(ex, ey, vx, vy, omega_journal, omega_bushing, clearance)
    v = math.sqrt(a * a + b * b)
    if v == 0.0:
        return 0.0
    shape = film_peak_shape(eps, math.atan2(b, a))
    return 1.5 * viscosity * length * length * v / (clearance * clearance) * shape
