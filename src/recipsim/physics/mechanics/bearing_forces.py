"""Bearing forces of the flexible crank train: one bearing between two markers by its
law, and the lubricated piston skirt between the ``piston_top`` and ``piston_skirt``
stations; each records its force, displacement, torques, dissipation, contact and peak
film pressure in the outputs (layout :mod:`.layout`). Called by :mod:`.flexible`.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from recipsim.physics.mechanics import layout as lay
from recipsim.physics.mechanics.bearing_laws.registry import (
    bearing_load,
    bearing_peak_pressure,
    bearing_spring_energy,
)
from recipsim.physics.mechanics.skirt import skirt_contact, skirt_film, skirt_peak_pressure

_ROW = lay.P_BEARINGS
_NB = lay.N_BEARING_PAR


@njit(cache=True)
def bearing_force(
    i: int,
    par: np.ndarray,
    tables: np.ndarray,
    aux: np.ndarray,
    ex: float,
    ey: float,
    vx: float,
    vy: float,
    spin_journal: float,
    spin_bushing: float,
) -> tuple[float, float, float, float, float, float]:
    """Evaluate bearing ``i`` (relative motion in X-Y), record it in ``aux``.

    ``ex``, ``ey`` [m] and ``vx``, ``vy`` [m/s]: journal marker relative to the bushing
    marker; ``spin_journal``, ``spin_bushing`` [rad/s]: their spin rates; ``par`` and
    ``tables`` the mechanism parameters and the bearing tables. Returns fx, fy (force on
    the journal) [N], the friction torques on journal and bushing [N m], the power
    absorbed [W] and the spring energy [J].
    """
    row = _ROW + i * _NB
    if int(par[row + lay.BP_AXIS]) == lay.AXIS_X:
        ex = 0.0
        vx = 0.0
    fx, fy, tj, tb, absorbed, contact = bearing_load(
        par, row, tables, ex, ey, vx, vy, spin_journal, spin_bushing
    )
    aux[lay.A_BEARING_FORCE + 3 * i] = fx
    aux[lay.A_BEARING_FORCE + 3 * i + 1] = fy
    aux[lay.A_BEARING_FORCE + 3 * i + 2] = 0.0
    aux[lay.A_BEARING_DISPLACEMENT + 3 * i] = ex
    aux[lay.A_BEARING_DISPLACEMENT + 3 * i + 1] = ey
    aux[lay.A_BEARING_DISPLACEMENT + 3 * i + 2] = 0.0
    aux[lay.A_BEARING_TORQUE + 2 * i] = tj
    aux[lay.A_BEARING_TORQUE + 2 * i + 1] = tb
    aux[lay.A_BEARING_DISSIPATION + i] = absorbed
    aux[lay.A_BEARING_CONTACT + i] = contact
    peak = 0.0
    if par[lay.P_DETAILED_OUTPUTS] != 0.0:
        peak = bearing_peak_pressure(par, row, tables, ex, ey, vx, vy, spin_journal, spin_bushing)
    aux[lay.A_BEARING_PEAK_PRESSURE + i] = peak
    return fx, fy, tj, tb, absorbed, bearing_spring_energy(par, row, ex, ey)


@njit(cache=True)
def _record_station(
    i: int, aux: np.ndarray, e: float, f: float, absorbed: float, contact: float, peak: float
) -> None:
    """Record a piston station of the skirt film as bearing ``i`` in ``aux``."""
    for k in range(3):
        aux[lay.A_BEARING_FORCE + 3 * i + k] = 0.0
        aux[lay.A_BEARING_DISPLACEMENT + 3 * i + k] = 0.0
    aux[lay.A_BEARING_FORCE + 3 * i + 1] = f
    aux[lay.A_BEARING_DISPLACEMENT + 3 * i + 1] = e
    aux[lay.A_BEARING_TORQUE + 2 * i] = 0.0
    aux[lay.A_BEARING_TORQUE + 2 * i + 1] = 0.0
    aux[lay.A_BEARING_DISSIPATION + i] = absorbed
    aux[lay.A_BEARING_CONTACT + i] = contact
    aux[lay.A_BEARING_PEAK_PRESSURE + i] = peak


@njit(cache=True)
def _cached_skirt(aux: np.ndarray, arguments: tuple) -> int:  # type: ignore[type-arg]
    """The row of the skirt film's cache (:data:`.layout.A_SKIRT_CACHE_ROWS`) that holds
    ``arguments`` exactly, made the row used last; -1 if none does."""
    for k in range(2):
        row = lay.A_SKIRT_CACHE_ROWS + k * lay.N_FILM_CACHE
        if aux[row + lay.FC_VALID] != 1.0:
            continue
        same = True
        for j in range(lay.N_FILM_ARGUMENTS):
            if aux[row + lay.FC_ARGUMENTS + j] != arguments[j]:
                same = False
                break
        if same:
            aux[lay.A_SKIRT_CACHE] = k
            return row
    return -1


@njit(cache=True)
def _cache_skirt(aux: np.ndarray, arguments: tuple, results: tuple) -> None:  # type: ignore[type-arg]
    """Keep ``arguments`` and their ``results`` in the row of the skirt film's cache
    not used last, which becomes the row used last."""
    k = 1 - int(aux[lay.A_SKIRT_CACHE])
    row = lay.A_SKIRT_CACHE_ROWS + k * lay.N_FILM_CACHE
    for j in range(lay.N_FILM_ARGUMENTS):
        aux[row + lay.FC_ARGUMENTS + j] = arguments[j]
    for j in range(len(results)):
        aux[row + lay.FC_RESULTS + j] = results[j]
    aux[row + lay.FC_VALID] = 1.0
    aux[lay.A_SKIRT_CACHE] = k


@njit(cache=True)
def piston_skirt_forces(
    par: np.ndarray,
    aux: np.ndarray,
    e_top: float,
    e_skirt: float,
    v_top: float,
    v_skirt: float,
    sliding_speed: float,
    top_to_skirt: float,
) -> tuple[float, float, float]:
    """The lubricated skirt between the ``piston_top`` and ``piston_skirt`` stations.

    ``e_top``, ``e_skirt`` [m] and ``v_top``, ``v_skirt`` [m/s]: lateral offsets of the
    piston axis at the stations and their rates; ``sliding_speed`` [m/s] towards the
    head; ``top_to_skirt`` [m]: the film length between the stations.

    Returns the lateral (Y) forces on the piston at the two stations and the axial
    friction force on the piston (positive towards the head) [N]; records the stations
    in ``aux`` as bearings 5 and 6 (the film's peak pressure at ``piston_skirt``).

    Arguments met in one of the last two evaluations with this ``aux`` (the
    finite-difference Jacobian's columns of states that do not move the piston) take
    that evaluation's results from the cache in ``aux`` (:data:`.layout.FILM_CACHE`):
    the same numbers, bit for bit, without the film's 8-20 us. Not with the detailed
    outputs (the peak pressure is not cached).
    """
    row = _ROW + lay.B_PISTON_SKIRT * _NB
    radius = 0.5 * par[row + lay.BP_DIAMETER]
    clearance = par[row + lay.BP_CLEARANCE]
    mu = par[row + lay.BP_VISCOSITY]
    arguments = (
        e_top, e_skirt, v_top, v_skirt, sliding_speed, top_to_skirt, radius, clearance, mu,
        par[row + lay.BP_CONTACT_FILM], par[row + lay.BP_CONTACT_STIFFNESS],
        par[row + lay.BP_CONTACT_FRICTION],
    )  # fmt: skip
    detailed = par[lay.P_DETAILED_OUTPUTS] != 0.0
    cached = -1 if detailed else _cached_skirt(aux, arguments)
    peak = 0.0
    if cached >= 0:
        r = cached + lay.FC_RESULTS
        f_top, f_skirt, friction = aux[r], aux[r + 1], aux[r + 2]
        c_top, c_skirt = aux[r + 3], aux[r + 4]
    else:
        f_top, f_skirt, friction = skirt_film(
            e_top, e_skirt, v_top, v_skirt, sliding_speed, radius, top_to_skirt, clearance, mu
        )
        c_top, c_skirt, c_friction = skirt_contact(
            e_top, e_skirt, v_top, v_skirt, sliding_speed, radius, top_to_skirt, clearance,
            arguments[9], arguments[10], arguments[11],
        )  # fmt: skip
        f_top += c_top
        f_skirt += c_skirt
        friction += c_friction
        if detailed:
            peak = skirt_peak_pressure(
                e_top, e_skirt, v_top, v_skirt, sliding_speed, radius, top_to_skirt, clearance, mu
            )
        else:
            _cache_skirt(aux, arguments, (f_top, f_skirt, friction, c_top, c_skirt))
    _record_station(lay.B_PISTON_TOP, aux, e_top, f_top, -f_top * v_top, abs(c_top), 0.0)
    _record_station(
        lay.B_PISTON_SKIRT, aux, e_skirt, f_skirt, -f_skirt * v_skirt, abs(c_skirt), peak
    )
    aux[lay.A_PISTON_FRICTION] = friction
    return f_top, f_skirt, friction
