"""The finite journal bearing law: the short-bearing force times an impedance ratio
tabulated from Reynolds solutions with Swift-Stieber cavitation for the bearing's L/D
(:mod:`recipsim.physics.mechanics.journal_finite`), plus asperity contact (added by the
registry)."""

from __future__ import annotations

import functools

import numpy as np
from numba import njit

from recipsim.physics.mechanics.bearing_laws.law import (
    FILM_OUTPUTS,
    BearingLaw,
    journal_film_geometry,
)
from recipsim.physics.mechanics.bearing_laws.short_journal import film_secant_stiffness
from recipsim.physics.mechanics.journal_finite import (
    finite_journal_film,
    finite_journal_peak_pressure,
)
from recipsim.physics.mechanics.journal_table import finite_journal_table
from recipsim.physics.mechanics.layout import (
    BP_TABLE,
    JOURNAL_NAMES,
)

CODE = 2


@functools.lru_cache(maxsize=16)
def impedance_table(length_over_diameter: float) -> np.ndarray:
    """The impedance table of one L/D, read (or built) once per process and read-only:
    the parameter array and the bearing-table array of every model built need it."""
    table = finite_journal_table(length_over_diameter)
    table.flags.writeable = False
    return table


LAW = BearingLaw(
    name="finite_journal",
    code=CODE,
    summary="finite-length journal: the short bearing times an impedance ratio from "
    "Reynolds solutions (Swift-Stieber cavitation) tabulated for the bearing's L/D; "
    "asperity contact",
    source="Childs, Moes & van Leeuwen (1977), J. Lubr. Technol. 99, 269-276 (impedance "
    "descriptions); the tables are this package's own Reynolds solutions",
    bearings=JOURNAL_NAMES,
    table=impedance_table,
    start_stiffness=film_secant_stiffness,
    outputs=FILM_OUTPUTS,
)


@njit(cache=True)
def finite_film(
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
    return finite_journal_film(
        ex, ey, vx, vy, spin_journal, spin_bushing, radius, length, clearance, viscosity,
        tables, int(par[row + BP_TABLE]),
    )  # fmt: skip


@njit(cache=True)
def finite_peak_pressure(
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
    return finite_journal_peak_pressure(
        ex, ey, vx, vy, spin_journal, spin_bushing, radius, length, clearance, viscosity,
        tables, int(par[row + BP_TABLE]),
    )  # fmt: skip
