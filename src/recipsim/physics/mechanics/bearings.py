"""Bearing laws: forces and friction torques from the relative motion of two markers.

A bearing joins a marker on a journal-side body A to a marker on a bushing-side body
B (or ground). Its law sees only the relative displacement ``e = r_A - r_B`` normal to
the bearing axis, its rate and the spin rates of both sides about the axis, and returns
the force on A (B receives the opposite force) and the friction torques about the axis
on A and on B. Laws are chosen per bearing by an integer code in the bearing's
parameter row (:mod:`.layout`), dispatched here:

- ``linear``: isotropic spring and dashpot (the paper);
- ``short_journal``: Ocvirk's short bearing with Guembel cavitation over the region
  where the pressure is positive (:mod:`.journal`), plus asperity contact;
- ``finite_journal``: the finite-length impedance table (:mod:`.journal_finite`), plus
  asperity contact.

The piston's lubricated skirt (``skirt_film``) acts on two stations at once and is
evaluated by the flexible model itself (:mod:`.skirt`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from recipsim.physics.mechanics.journal import (
    bushing_torque,
    journal_contact,
    short_journal_film,
    short_journal_peak_pressure,
)
from recipsim.physics.mechanics.journal_finite import (
    finite_journal_film,
    finite_journal_peak_pressure,
)
from recipsim.physics.mechanics.layout import (
    BP_CLEARANCE,
    BP_CONTACT_FILM,
    BP_CONTACT_FRICTION,
    BP_CONTACT_STIFFNESS,
    BP_DAMPING,
    BP_DIAMETER,
    BP_LAW,
    BP_LENGTH,
    BP_STIFFNESS,
    BP_TABLE,
    BP_VISCOSITY,
    LAW_LINEAR,
    LAW_SHORT_JOURNAL,
)


@njit(cache=True)
def linear_bearing_force(
    k: float, c: float, ex: float, ey: float, vx: float, vy: float
) -> tuple[float, float]:
    """Isotropic spring and dashpot, ``F = -k e - c de/dt`` (the paper's law).

    Parameters
    ----------
    k : float
        Stiffness [N/m].
    c : float
        Damping [N s/m].
    ex, ey : float
        Relative displacement journal minus bushing, normal to the axis [m].
    vx, vy : float
        Its time derivative [m/s].

    Returns
    -------
    fx, fy : float
        Force on the journal [N].
    """
    return -k * ex - c * vx, -k * ey - c * vy


@njit(cache=True)
def bearing_load(
    par: np.ndarray,
    row: int,
    tables: np.ndarray,
    ex: float,
    ey: float,
    vx: float,
    vy: float,
    spin_journal: float,
    spin_bushing: float,
) -> tuple[float, float, float, float, float, float]:
    """Force and friction torques of the bearing whose parameter row starts at ``row``.

    Parameters
    ----------
    par : numpy.ndarray
        Parameter array holding the bearing's row.
    row : int
        Index of the row's first entry.
    tables : numpy.ndarray
        Bearing-table array (``finite_journal`` tables at ``par[row + BP_TABLE]``).
    ex, ey : float
        Relative displacement journal minus bushing in the plane normal to the
        bearing axis [m].
    vx, vy : float
        Its rate [m/s].
    spin_journal, spin_bushing : float
        Absolute angular speeds of the two sides about the bearing axis [rad/s].

    Returns
    -------
    fx, fy : float
        Force on the journal [N].
    torque_journal, torque_bushing : float
        Friction torque about the axis on the journal and on the bushing [N m].
    absorbed : float
        Power absorbed by the bearing, ``-(F.de/dt + T_j w_j + T_b w_b)`` [W]: all of it
        dissipated for the film laws; for the linear law it includes the spring's rate
        of storage (zero over a period).
    contact : float
        Normal force of the asperity contact [N] (0 while the film carries the load).
    """
    law = int(par[row + BP_LAW])
    if law == LAW_LINEAR:
        fx, fy = linear_bearing_force(
            par[row + BP_STIFFNESS], par[row + BP_DAMPING], ex, ey, vx, vy
        )
        return fx, fy, 0.0, 0.0, -(fx * vx + fy * vy), 0.0
    radius = 0.5 * par[row + BP_DIAMETER]
    length = par[row + BP_LENGTH]
    clearance = par[row + BP_CLEARANCE]
    mu = par[row + BP_VISCOSITY]
    if law == LAW_SHORT_JOURNAL:
        fx, fy, tj = short_journal_film(
            ex, ey, vx, vy, spin_journal, spin_bushing, radius, length, clearance, mu
        )
    else:
        fx, fy, tj = finite_journal_film(
            ex, ey, vx, vy, spin_journal, spin_bushing, radius, length, clearance, mu,
            tables, int(par[row + BP_TABLE]),
        )  # fmt: skip
    cx, cy, ctj = journal_contact(
        ex, ey, vx, vy, spin_journal, spin_bushing, radius, clearance,
        par[row + BP_CONTACT_FILM], par[row + BP_CONTACT_STIFFNESS],
        par[row + BP_CONTACT_FRICTION],
    )  # fmt: skip
    contact = 0.0
    if cx != 0.0 or cy != 0.0:
        emag = (ex * ex + ey * ey) ** 0.5
        contact = -(cx * ex + cy * ey) / emag if emag > 0.0 else (cx * cx + cy * cy) ** 0.5
    fx += cx
    fy += cy
    tj += ctj
    tb = bushing_torque(ex, ey, fx, fy, tj)
    absorbed = -(fx * vx + fy * vy + tj * spin_journal + tb * spin_bushing)
    return fx, fy, tj, tb, absorbed, contact


@njit(cache=True)
def bearing_peak_pressure(
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
    """Largest film pressure of a journal bearing [Pa] (0 for the linear law).

    Arguments as :func:`bearing_load`; for post-processing (not in the integrator's
    right-hand side).
    """
    law = int(par[row + BP_LAW])
    if law == LAW_LINEAR:
        return 0.0
    radius = 0.5 * par[row + BP_DIAMETER]
    length = par[row + BP_LENGTH]
    clearance = par[row + BP_CLEARANCE]
    mu = par[row + BP_VISCOSITY]
    if law == LAW_SHORT_JOURNAL:
        return short_journal_peak_pressure(
            ex, ey, vx, vy, spin_journal, spin_bushing, radius, length, clearance, mu
        )
    return finite_journal_peak_pressure(
        ex, ey, vx, vy, spin_journal, spin_bushing, radius, length, clearance, mu,
        tables, int(par[row + BP_TABLE]),
    )  # fmt: skip


@njit(cache=True)
def bearing_spring_energy(par: np.ndarray, row: int, ex: float, ey: float) -> float:
    """Elastic energy stored in the bearing [J] (0 for laws without one)."""
    if int(par[row + BP_LAW]) == LAW_LINEAR:
        return 0.5 * par[row + BP_STIFFNESS] * (ex * ex + ey * ey)
    return 0.0
