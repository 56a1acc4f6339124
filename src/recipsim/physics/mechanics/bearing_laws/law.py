"""What a bearing law declares (:class:`BearingLaw`) and the signature of its compiled
functions.

A journal law's compiled film function has the signature ::

    film(par, row, tables, ex, ey, vx, vy, spin_journal, spin_bushing) -> (fx, fy, torque)

``par`` the mechanism's parameter array with the bearing's row starting at ``row``
(offsets ``BP_*`` of :mod:`recipsim.physics.mechanics.layout`), ``tables`` the bearing
tables, ``ex, ey`` [m] and ``vx, vy`` [m/s] the journal marker relative to the bushing
marker in the plane normal to the bearing axis, the spins about the axis [rad/s]; it
returns the film force on the journal [N] and the film torque on the journal [N m]. Its
peak-pressure function takes the same arguments and returns [Pa]. The registry adds the
asperity contact, the bushing's torque and the dissipation, the same for every film law.

Every film law's entry carries :data:`FILM_OUTPUTS`, the report columns of a bearing on
an oil film (:mod:`recipsim.results.bearings` writes them for each such bearing).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numba import njit

from recipsim.physics.mechanics import layout as lay
from recipsim.physics.mechanics.layout import BP_CLEARANCE, BP_DIAMETER, BP_LENGTH, BP_VISCOSITY
from recipsim.slots import PER_BEARING, ModelChoice, Output


@njit(cache=True)
def journal_film_geometry(par: np.ndarray, row: int) -> tuple[float, float, float, float]:
    """A journal film's radius, length and radial clearance [m] and its oil's viscosity
    [Pa s], from the bearing's parameter row starting at ``row`` of ``par``."""
    return (
        0.5 * par[row + BP_DIAMETER],
        par[row + BP_LENGTH],
        par[row + BP_CLEARANCE],
        par[row + BP_VISCOSITY],
    )


def mechanism_output(name: str, table: str = "cycle") -> Output:
    """The output ``name`` that is a slot of the mechanism's outputs
    (:data:`~recipsim.physics.mechanics.layout.OUTPUTS`), with that slot's unit and meaning
    (a per-bearing one's are its first bearing's, the series')."""
    entry = lay.OUTPUTS.entry(name.replace(PER_BEARING, lay.BEARING_NAMES[0]))
    return Output(name, entry.unit, entry.meaning, table)


#: The report columns of a bearing on an oil film, per bearing: the cycle's orbit in the
#: clearance, friction torque, absorbed power, contact force and peak film pressure, and
#: the summary's extremes and mean friction power over the revolution.
FILM_OUTPUTS: tuple[Output, ...] = (
    Output(
        "film_thickness_<name>",
        "m",
        "film thickness at the thinnest point, radial clearance - displacement",
        "cycle",
    ),
    Output("eccentricity_ratio_<name>", "-", "displacement over the radial clearance", "cycle"),
    mechanism_output("friction_torque_<name>"),
    mechanism_output("bearing_power_loss_<name>"),
    mechanism_output("contact_force_<name>"),
    mechanism_output("film_peak_pressure_<name>"),
    Output(
        "min_film_thickness_<name>",
        "m",
        "smallest film over the revolution, radial clearance - journal displacement (the "
        "piston film at piston_top and piston_skirt)",
        "summary",
    ),
    Output(
        "max_eccentricity_ratio_<name>",
        "-",
        "largest journal displacement over the radial clearance",
        "summary",
    ),
    Output(
        "max_film_pressure_<name>",
        "Pa",
        "largest film pressure over the revolution (the piston film reports it at piston_skirt)",
        "summary",
    ),
    Output(
        "max_contact_force_<name>",
        "N",
        "largest asperity-contact normal force (0: the film carried the load all revolution)",
        "summary",
    ),
    Output(
        "friction_power_<name>",
        "W",
        "time mean of the power the bearing dissipates: film shear (Couette and "
        "pressure-gradient parts), squeeze, contact friction",
        "summary",
    ),
)


@dataclass(frozen=True)
class BearingLaw(ModelChoice):
    """A bearing law: a :class:`~recipsim.slots.ModelChoice` with what the case reader,
    the model builder and the start-up need.

    Attributes
    ----------
    bearings : tuple of str
        The bearings (``layout.BEARING_NAMES``) that may run on it.
    film : bool
        It reads the oil-film keys of ``[bearings.<name>]`` (geometry, clearance, oil,
        contact) and the model writes them into the bearing's row; its ``outputs`` hold
        :data:`FILM_OUTPUTS`.
    spring : bool
        It reads ``stiffness`` and ``damping`` (required).
    station_pair : bool
        It acts on the piston's two stations together (both name it or neither).
    table : callable or None
        ``table(length_over_diameter) -> numpy.ndarray``: the law's per-bearing table
        (read-only), built once per L/D; None: no table.
    start_stiffness : callable or None
        ``start_stiffness(par, row, speed) -> float`` [N/m]: a stiffness for start poses
        and tolerances; None: 0 (the body starts centred).
    """

    bearings: tuple[str, ...] = ()
    film: bool = True
    spring: bool = False
    station_pair: bool = False
    table: Callable[[float], np.ndarray] | None = None
    start_stiffness: Callable[[np.ndarray, int, float], float] | None = None
