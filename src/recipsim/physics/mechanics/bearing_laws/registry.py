"""The bearing laws' slot: ``options.bearing_law`` and each ``[bearings.<name>]``'s
``law``.

:data:`BEARING_LAWS` lists the laws (:class:`~.law.BearingLaw` entries, one module each in
this folder); the case reader, the model builder, the start-up and the reports read it.
:func:`bearing_load` and :func:`bearing_peak_pressure` are the compiled dispatch the
flexible model calls for one bearing's row.

Adding a journal law
--------------------
1. A module in this folder with its entry ``LAW`` (name, a new ``CODE``, summary, source,
   the bearings it serves, any keys of its own, ``outputs=law.FILM_OUTPUTS``: the film
   bearing's report columns) and its compiled ``film`` and ``peak_pressure`` functions
   with the signature of :mod:`.law`.
2. Here: import the module, add ``LAW`` to :data:`BEARING_LAWS`, and one branch in
   :func:`bearing_film` and :func:`bearing_peak_pressure` (numba dispatches statically).
3. Its tests (the forces against a closed form or another law's limit) and a shipped case
   or docs page that uses it.
The asperity contact, the bushing's torque and the dissipation are added here for every
film law. The general contract of a model slot: :mod:`recipsim.slots`.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from recipsim.physics.mechanics.bearing_laws import (
    finite_journal,
    linear,
    mobility,
    short_journal,
    skirt_film,
)
from recipsim.physics.mechanics.bearing_laws.law import BearingLaw
from recipsim.physics.mechanics.journal import bushing_torque, journal_contact
from recipsim.physics.mechanics.layout import (
    BEARING_NAMES,
    BP_CLEARANCE,
    BP_CONTACT_FILM,
    BP_CONTACT_FRICTION,
    BP_CONTACT_STIFFNESS,
    BP_DIAMETER,
    BP_LAW,
    JOURNAL_NAMES,
)
from recipsim.slots import Slot

#: The law of a bearing whose table names none, where it has a choice.
DEFAULT_LAW: str = linear.LAW.name

BEARING_LAWS: Slot[BearingLaw] = Slot(
    "options.bearing_law",
    "law of the journal bearings (primary, secondary, eccentric) whose table names none",
    (linear.LAW, short_journal.LAW, finite_journal.LAW, mobility.LAW, skirt_film.LAW),
    default=DEFAULT_LAW,
)

#: The laws a journal may run on (``options.bearing_law``'s choices).
JOURNAL_LAWS: tuple[str, ...] = tuple(
    law.name for law in BEARING_LAWS if set(JOURNAL_NAMES) <= set(law.bearings)
)


def laws_of(bearing: str) -> tuple[str, ...]:
    """The laws bearing ``bearing`` (one of ``layout.BEARING_NAMES``) accepts."""
    if bearing not in BEARING_NAMES:
        raise KeyError(f"no bearing {bearing!r}; bearings: {', '.join(BEARING_NAMES)}")
    return tuple(law.name for law in BEARING_LAWS if bearing in law.bearings)


def law_in_row(par: np.ndarray, row: int) -> BearingLaw:
    """The law of the bearing whose parameter row starts at ``row``."""
    return BEARING_LAWS.by_code(int(par[row + BP_LAW]))


_LINEAR = linear.CODE
_SHORT = short_journal.CODE
_FINITE = finite_journal.CODE
_MOBILITY = mobility.CODE


@njit(cache=True)
def bearing_film(
    law: int,
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
    """The film force [N] and journal torque [N m] of journal law ``law`` (its code;
    none for a code that is not a journal law's)."""
    if law == _SHORT:
        return short_journal.short_film(par, row, tables, ex, ey, vx, vy, spin_journal,
                                        spin_bushing)  # fmt: skip
    if law == _FINITE:
        return finite_journal.finite_film(par, row, tables, ex, ey, vx, vy, spin_journal,
                                          spin_bushing)  # fmt: skip
    if law == _MOBILITY:
        return mobility.mobility_film(par, row, tables, ex, ey, vx, vy, spin_journal,
                                      spin_bushing)  # fmt: skip
    return 0.0, 0.0, 0.0


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
        Bearing-table array (a law's table at ``par[row + BP_TABLE]``).
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
    if law == _LINEAR:
        return linear.linear_load(par, row, ex, ey, vx, vy)
    fx, fy, tj = bearing_film(law, par, row, tables, ex, ey, vx, vy, spin_journal, spin_bushing)
    cx, cy, ctj = journal_contact(
        ex, ey, vx, vy, spin_journal, spin_bushing, 0.5 * par[row + BP_DIAMETER],
        par[row + BP_CLEARANCE], par[row + BP_CONTACT_FILM], par[row + BP_CONTACT_STIFFNESS],
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
    if law == _SHORT:
        return short_journal.short_peak_pressure(par, row, tables, ex, ey, vx, vy,
                                                 spin_journal, spin_bushing)  # fmt: skip
    if law == _FINITE:
        return finite_journal.finite_peak_pressure(par, row, tables, ex, ey, vx, vy,
                                                   spin_journal, spin_bushing)  # fmt: skip
    if law == _MOBILITY:
        return mobility.mobility_peak_pressure(par, row, tables, ex, ey, vx, vy,
                                               spin_journal, spin_bushing)  # fmt: skip
    return 0.0


@njit(cache=True)
def bearing_spring_energy(par: np.ndarray, row: int, ex: float, ey: float) -> float:
    """Elastic energy stored in the bearing [J] (0 for laws without one)."""
    if int(par[row + BP_LAW]) == _LINEAR:
        return linear.linear_spring_energy(par, row, ex, ey)
    return 0.0
