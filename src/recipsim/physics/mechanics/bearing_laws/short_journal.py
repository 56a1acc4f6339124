"""The short journal bearing law: Ocvirk's short bearing with Guembel cavitation over the
region where the pressure is positive, in Booker's closed form
(:mod:`recipsim.physics.mechanics.journal`), plus asperity contact (added by the
registry)."""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from recipsim.physics.mechanics.bearing_laws.law import (
    FILM_OUTPUTS,
    BearingLaw,
    journal_film_geometry,
)
from recipsim.physics.mechanics.journal import short_journal_film, short_journal_peak_pressure
from recipsim.physics.mechanics.layout import (
    JOURNAL_NAMES,
)

CODE = 1


def film_secant_stiffness(par: np.ndarray, row: int, speed: float) -> float:
    """Secant stiffness of a short-bearing film at eccentricity ratio 0.5 [N/m]: the
    steady load at ``speed`` [rad/s] (fixed bushing) over the displacement ``c/2``."""
    radius, length, c, mu = journal_film_geometry(par, row)
    omega = max(abs(speed), 1.0)
    eps = 0.5
    shape = eps * math.sqrt(math.pi**2 * (1 - eps**2) + 16 * eps**2) / (1 - eps**2) ** 2
    load = mu * omega * radius * length**3 / (4 * c * c) * shape
    return float(load / (eps * c))


LAW = BearingLaw(
    name="short_journal",
    code=CODE,
    summary="Ocvirk short bearing, Guembel cavitation on the moving positive-pressure "
    "half, in closed form; asperity contact",
    source="Booker (1965), J. Basic Eng. 87, 537-546; Ocvirk (1952), NACA TN 2808",
    bearings=JOURNAL_NAMES,
    start_stiffness=film_secant_stiffness,
    outputs=FILM_OUTPUTS,
)


@njit(cache=True)
def short_film(
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
    return short_journal_film(
        ex, ey, vx, vy, spin_journal, spin_bushing, radius, length, clearance, viscosity
    )


@njit(cache=True)
def short_peak_pressure(
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
    """Largest film pressure [Pa] (signature: :mod:`.law`)."""
    radius, length, clearance, viscosity = journal_film_geometry(par, row)
    return short_journal_peak_pressure(
        ex, ey, vx, vy, spin_journal, spin_bushing, radius, length, clearance, viscosity
    )
