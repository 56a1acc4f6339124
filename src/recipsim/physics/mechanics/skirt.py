"""Lubricated piston skirt: oil-film forces, friction and asperity contact (compiled).

Geometry and signs
------------------
The bore axis is X, positive towards the cylinder head; the piston's crown faces the
head. The film covers the piston's length ``L`` from its crown end to its skirt end.
``s`` runs along the piston from the crown end (``s = 0``) to the skirt end
(``s = L``); ``theta`` is measured about the axis from +Y.

- ``e_crown``, ``e_skirt`` [m]: lateral (Y) offset of the piston axis from the bore axis
  at the crown end and at the skirt end of the film; positive towards +Y. Between the
  ends the offset is linear in ``s`` (a rigid piston tilted by ``(e_crown - e_skirt)/L``
  about Z, crown towards +Y when positive: the flexible model's ``gamma``).
- ``v_crown``, ``v_skirt`` [m/s]: their rates.
- ``sliding_speed`` ``U`` [m/s]: piston velocity along X relative to the bore, positive
  towards the head (crown side).
- Film ``h(s, theta) = c - e(s) cos(theta)``: a positive ``e`` narrows the film on the
  +Y side.
- Outputs: ``f_crown``, ``f_skirt`` [N], Y forces on the piston at the two ends that
  carry the film's Y resultant and its moment about Z (linear shape functions, so that
  ``f_crown v_crown + f_skirt v_skirt`` is the film's lateral power on the piston);
  ``friction`` [N]: X force on the piston (the bore gets the opposite forces).

Film model
----------
Reynolds in the piston's frame (the bore slides past it towards +s at ``U``)::

    d/ds(h^3 dp/ds) + d/dtheta(h^3 dp/dtheta)/R^2 = 6 mu U dh/ds + 12 mu dh/dt

with ``p = 0`` at both ends and Guembel (half-Sommerfeld) cavitation: the full-film
solution clipped at 0. The right-hand side is ``cos(theta)`` times a linear function of
``s``, so at every station the circumferential shape of the long-film solution is known:
``p ~ (c/h)^2 - 1`` (zero at ``theta = +-pi/2``), for which the circumferential term is
exactly ``-(k^2/R^2) h^3 p`` with ``k^2 = 2 c^2 / (h (c + h))``. Each circumferential
station is then an independent axial problem::

    d/ds(h^3 dp/ds) - (k^2/R^2) h^3 p = 6 mu U dh/ds + 12 mu dh/dt

with ``k^2 = max(2 c^2 / (h (c + h)), 1)`` (``k = 1`` is exact as ``e -> 0``; where
``h > c`` the long-film shape is too flat and the cosine of the clipped half-film, k = 1,
is used). Dropping the term altogether (the short-film approximation) overestimates the
forces of this piston (L/D = 0.9) by 33 % at ``e = 0`` and 5.6 times at ``e = 0.9 c``;
with it, the end forces are within 1-3 % of a 2-D finite-difference solution for most
states and within 10.3 % for the random and extreme states of the tests (offsets up to
0.9 c at both ends). The weak corner: states whose pressure sits only on the thick side
(``h > c``; small loads, e.g. 14 N where the reversed sliding gives 4100 N) come out up
to 23 % high (tests/physics/test_piston_skirt.py).

Each axial problem is solved by :mod:`recipsim.physics.mechanics.skirt_axial`; the
circumferential integral uses Gauss-Legendre on ``[0, pi/2]`` and ``[pi/2, pi]`` (the
clipped pressure has a kink at ``pi/2``), doubled by the symmetry about the Y axis.

Friction: wall shear on the piston ``-(mu U/h - (h/2) dp/ds)`` plus the axial part
``p dh/ds`` of the pressure on the inclined skirt, so that the film's power on the
piston is exactly minus its dissipation. The Couette part runs over the full 360 deg
film, in closed form. All functions are compiled and allocation-free.
"""

from __future__ import annotations

import math

from numba import njit

from recipsim.physics.mechanics.skirt_axial import (
    GAUSS_NODES,
    GAUSS_WEIGHTS,
    station_pressure_integrals,
)

#: Speed below which the contact's Coulomb friction is scaled down linearly [m/s].
CONTACT_FRICTION_REGULARISATION_SPEED = 1.0e-3
#: Smallest film used in the contact law, as a fraction of the contact film.
_CONTACT_FLOOR = 1.0e-3


@njit(cache=True)
def _couette_integral(e_crown: float, e_skirt: float, clearance: float, length: float) -> float:
    """``int_0^L int_0^2pi dtheta ds / h`` [rad m / m] in closed form."""
    ac = e_crown / clearance
    as_ = e_skirt / clearance
    d = as_ - ac
    if abs(d) < 1.0e-6:
        em = 0.5 * (ac + as_)
        inner = (
            1.0
            / math.sqrt(1.0 - em * em)
            * (1.0 + d * d * (1.0 + 2.0 * em * em) / 24.0 / (1.0 - em * em) ** 2)
        )
        return 2.0 * math.pi * length / clearance * inner
    return 2.0 * math.pi * length / clearance * (math.asin(as_) - math.asin(ac)) / d


@njit(cache=True)
def _film(
    e_crown: float,
    e_skirt: float,
    v_crown: float,
    v_skirt: float,
    sliding_speed: float,
    radius: float,
    length: float,
    clearance: float,
    viscosity: float,
    peak: bool,
) -> tuple[float, float, float, float]:
    """Film forces, friction and (with ``peak``) the peak pressure on the quadrature nodes."""
    c = clearance
    r2 = radius * radius
    mu = viscosity
    # source 6 mu U dh/ds + 12 mu dh/dt = cos(theta) (q0 + q1 s)
    q0 = -6.0 * mu * sliding_speed * (e_skirt - e_crown) / length - 12.0 * mu * v_crown
    q1 = -12.0 * mu * (v_skirt - v_crown) / length
    sum_crown = 0.0
    sum_skirt = 0.0
    sum_friction = 0.0
    p_peak = 0.0
    quarter = 0.25 * math.pi
    for half in range(2):
        for j in range(len(GAUSS_NODES)):
            theta = quarter * (1.0 + GAUSS_NODES[j]) + 2.0 * quarter * half
            weight = quarter * GAUSS_WEIGHTS[j]
            cos_t = math.cos(theta)
            w0, w1, g, p_max = station_pressure_integrals(
                cos_t, e_crown, e_skirt, q0, q1, c, r2, length, peak
            )
            sum_crown += weight * cos_t * (w0 - w1 / length)
            sum_skirt += weight * cos_t * w1 / length
            sum_friction += weight * 0.5 * g * w0
            if p_max > p_peak:
                p_peak = p_max
    # x2: the film is symmetric about the Y axis (theta -> -theta)
    f_crown = -2.0 * radius * sum_crown
    f_skirt = -2.0 * radius * sum_skirt
    couette = mu * sliding_speed * radius * _couette_integral(e_crown, e_skirt, c, length)
    friction = -couette + 2.0 * radius * sum_friction
    return f_crown, f_skirt, friction, p_peak


@njit(cache=True)
def skirt_film(
    e_crown: float,
    e_skirt: float,
    v_crown: float,
    v_skirt: float,
    sliding_speed: float,
    radius: float,
    length: float,
    clearance: float,
    viscosity: float,
) -> tuple[float, float, float]:
    """Oil-film forces on the piston (signs in the module docstring).

    Parameters
    ----------
    e_crown, e_skirt : float
        Lateral (Y) offsets of the piston axis at the crown and skirt ends of the film
        [m], ``|e| < clearance``.
    v_crown, v_skirt : float
        Their rates [m/s].
    sliding_speed : float
        Piston velocity along the bore axis relative to the bore [m/s], positive
        towards the cylinder head (crown side).
    radius, length, clearance : float
        Piston radius, film length and radial clearance [m].
    viscosity : float
        Oil dynamic viscosity [Pa s].

    Returns
    -------
    f_crown, f_skirt : float
        Y forces on the piston at the crown and skirt ends of the film [N]; together
        they carry the film's Y resultant and its moment about Z.
    friction : float
        X force on the piston [N], opposing its sliding (Couette shear, pressure-driven
        shear and the pressure on the inclined skirt).
    """
    f_crown, f_skirt, friction, _ = _film(
        e_crown,
        e_skirt,
        v_crown,
        v_skirt,
        sliding_speed,
        radius,
        length,
        clearance,
        viscosity,
        False,
    )
    return f_crown, f_skirt, friction


@njit(cache=True)
def skirt_peak_pressure(
    e_crown: float,
    e_skirt: float,
    v_crown: float,
    v_skirt: float,
    sliding_speed: float,
    radius: float,
    length: float,
    clearance: float,
    viscosity: float,
) -> float:
    """Largest film pressure [Pa] (gauge; for post-processing).

    Arguments as in :func:`skirt_film`. The largest value on the quadrature nodes and
    on the two lines of extreme film (``theta = 0`` and ``pi``).
    """
    _, _, _, p_peak = _film(
        e_crown,
        e_skirt,
        v_crown,
        v_skirt,
        sliding_speed,
        radius,
        length,
        clearance,
        viscosity,
        True,
    )
    mu = viscosity
    q0 = -6.0 * mu * sliding_speed * (e_skirt - e_crown) / length - 12.0 * mu * v_crown
    q1 = -12.0 * mu * (v_skirt - v_crown) / length
    r2 = radius * radius
    for cos_t in (1.0, -1.0):
        _, _, _, p_max = station_pressure_integrals(
            cos_t, e_crown, e_skirt, q0, q1, clearance, r2, length, True
        )
        if p_max > p_peak:
            p_peak = p_max
    return p_peak


@njit(cache=True)
def _contact_normal(e: float, clearance: float, contact_film: float, stiffness: float) -> float:
    """Y force on the piston from asperity contact at one end [N]."""
    film = clearance - abs(e)
    if film >= contact_film:
        return 0.0
    floor = _CONTACT_FLOOR * contact_film
    if film > floor:
        depth = contact_film - film
        magnitude = stiffness * depth * depth / film
    else:
        # beyond the floor: the tangent of the law there (finite, still increasing)
        depth = contact_film - floor
        slope = stiffness * depth * (2.0 * floor + depth) / (floor * floor)
        magnitude = stiffness * depth * depth / floor + slope * (floor - film)
    return -magnitude if e > 0.0 else magnitude


@njit(cache=True)
def skirt_contact(
    e_crown: float,
    e_skirt: float,
    v_crown: float,
    v_skirt: float,
    sliding_speed: float,
    radius: float,
    length: float,
    clearance: float,
    contact_film: float,
    contact_stiffness: float,
    friction_coefficient: float,
) -> tuple[float, float, float]:
    """Asperity contact of the piston's ends with the bore (penalty law).

    The film is thinnest at an end (the offset is linear along the piston), so contact
    is checked at the two ends. With ``h = clearance - |e|`` at an end, the normal force
    is ``k (h_c - h)^2 / h`` once ``h < h_c`` (continuous with its slope at onset, and
    unbounded as ``h -> 0``, so that no finite load pushes the piston through the
    wall; below ``1e-3 h_c`` it continues along its tangent to stay finite). Coulomb
    friction opposes the sliding, scaled by ``U / sqrt(U^2 + v_r^2)`` with
    ``v_r`` = :data:`CONTACT_FRICTION_REGULARISATION_SPEED`.

    Parameters
    ----------
    e_crown, e_skirt, v_crown, v_skirt, sliding_speed, radius, length, clearance : float
        As in :func:`skirt_film` [m], [m/s]; ``v_*``, ``radius`` and ``length`` are not
        used by this law (no contact damping).
    contact_film : float
        Film below which contact starts ``h_c`` [m] (about 0.5e-6).
    contact_stiffness : float
        ``k`` [N/m].
    friction_coefficient : float
        Coulomb coefficient [-].

    Returns
    -------
    f_crown, f_skirt, friction : float
        Y forces on the piston at the crown and skirt ends and X friction force [N].
    """
    f_crown = _contact_normal(e_crown, clearance, contact_film, contact_stiffness)
    f_skirt = _contact_normal(e_skirt, clearance, contact_film, contact_stiffness)
    u = sliding_speed
    vr = CONTACT_FRICTION_REGULARISATION_SPEED
    friction = (
        -friction_coefficient * (abs(f_crown) + abs(f_skirt)) * u / math.sqrt(u * u + vr * vr)
    )
    return f_crown, f_skirt, friction
