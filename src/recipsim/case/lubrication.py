"""The case's oil (``[oil]``) and the film data of lubricated bearings, read once.

``[oil]`` keys (units as strings are converted; bare numbers are SI):

- ``name``: a named oil of :mod:`recipsim.physics.lubricant` (``iso_vg10``, the default;
  ``spindle_oil``) or, with ``law``, a label for the oil given here;
- ``law`` (``vogel``: three points of dynamic viscosity; ``walther``: two points),
  ``temperatures`` (list), ``viscosities`` (dynamic, list) or ``kinematic_viscosities``
  (list), ``density``: an oil of your own, fitted exactly through the points;
- ``film_temperature``: the film temperature of every lubricated bearing that does not
  give its own (default 60 C: a household compressor's oil runs at 50-70 C at the
  rating points; the films run a few kelvin above the sump).

Per lubricated bearing (``[bearings.<name>]``): ``diameter`` (journals; the piston's is
the bore), ``length`` (journals; the piston film runs between the ``piston_top`` and
``piston_skirt`` stations), ``radial_clearance``, ``film_temperature``, and the contact
law's ``contact_film``, ``contact_stiffness``, ``contact_friction`` (defaults of
:mod:`recipsim.physics.mechanics.journal`). The viscosity is evaluated once, at the film
temperature: the right-hand side never evaluates the oil's law.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from recipsim.case.table_reader import TableReader
from recipsim.case.units import to_si
from recipsim.errors import CaseError

FILM_KEYS = (
    "diameter",
    "length",
    "radial_clearance",
    "film_temperature",
    "contact_film",
    "contact_stiffness",
    "contact_friction",
)
_OIL_KEYS = (
    "name",
    "law",
    "temperatures",
    "viscosities",
    "kinematic_viscosities",
    "density",
    "film_temperature",
)
#: Default film temperature [K] (60 C).
DEFAULT_FILM_TEMPERATURE = 333.15


@dataclass(frozen=True)
class OilSpec:
    """The case's oil (SI).

    Attributes
    ----------
    oil : recipsim.physics.lubricant.Oil
        Density and the fitted viscosity-temperature law.
    film_temperature : float
        Default film temperature of the lubricated bearings [K].
    """

    oil: Any
    film_temperature: float

    def viscosity(self, temperature: float) -> float:
        """Dynamic viscosity [Pa s] at ``temperature`` [K]."""
        return float(self.oil.viscosity(temperature))


@dataclass(frozen=True)
class FilmSpec:
    """Film data of one lubricated bearing (SI).

    Attributes
    ----------
    diameter, length, radial_clearance : float
        Journal diameter, bearing length and radial clearance [m] (the piston film:
        the bore, the distance between its stations, the radial clearance).
    film_temperature : float
        [K].
    viscosity : float
        Oil dynamic viscosity at the film temperature [Pa s].
    contact_film : float
        Film thickness below which asperity contact starts [m].
    contact_stiffness : float
        Penalty stiffness of the contact [N/m].
    contact_friction : float
        Coulomb friction coefficient of the contact [-].
    """

    diameter: float
    length: float
    radial_clearance: float
    film_temperature: float
    viscosity: float
    contact_film: float
    contact_stiffness: float
    contact_friction: float


def _named_oils() -> dict[str, Any]:
    from recipsim.physics.lubricant import DEFAULT_OIL, SPINDLE_OIL

    return {"iso_vg10": DEFAULT_OIL, "spindle_oil": SPINDLE_OIL}


def _points(t: TableReader, name: str, unit: str) -> tuple[float, ...]:
    values = t.data.get(name)
    if not isinstance(values, list) or not values:
        raise CaseError(t.file, t.key(name), f"expected a list of values in {unit}")
    return tuple(to_si(v, unit, t.file, f"{t.key(name)}[{i}]") for i, v in enumerate(values))


def parse_oil(data: Any, file: str) -> OilSpec:
    """Read the ``[oil]`` table (``None``: the default oil at the default temperature)."""
    t = TableReader({} if data is None else data, file, "oil")
    t.check_keys(_OIL_KEYS)
    temperature = t.quantity(
        "film_temperature", "K", lambda v: 200.0 < v < 500.0, "200 ... 500 K",
        DEFAULT_FILM_TEMPERATURE,
    )  # fmt: skip
    named = _named_oils()
    if "law" not in t.data:
        name = t.choice("name", tuple(named), "iso_vg10")
        extra = set(t.data) - {"name", "film_temperature"}
        if extra:
            raise CaseError(file, t.key(sorted(extra)[0]), "needs oil.law (vogel or walther)")
        return OilSpec(named[name], temperature)
    from recipsim.physics.lubricant import fit_vogel, fit_walther

    law = t.choice("law", ("vogel", "walther"))
    label = str(t.data.get("name", "oil of the case"))
    density = t.quantity("density", "kg/m**3", lambda v: 500.0 < v < 2000.0, "500 ... 2000")
    temps = _points(t, "temperatures", "K")
    kinematic = "kinematic_viscosities" in t.data
    key = "kinematic_viscosities" if kinematic else "viscosities"
    visc = _points(t, key, "m**2/s" if kinematic else "Pa*s")
    wanted = 3 if law == "vogel" else 2
    if len(temps) != wanted or len(visc) != wanted:
        raise CaseError(file, t.key(key), f"the {law} law needs exactly {wanted} points")
    try:
        if law == "vogel":
            oil = fit_vogel(
                label, (temps[0], temps[1], temps[2]), (visc[0], visc[1], visc[2]), density,
                kinematic=kinematic, source=file,
            )  # fmt: skip
        else:
            oil = fit_walther(
                label, (temps[0], temps[1]), (visc[0], visc[1]), density,
                kinematic=kinematic, source=file,
            )  # fmt: skip
    except ValueError as exc:
        raise CaseError(file, t.key(key), str(exc)) from None
    return OilSpec(oil, temperature)


def parse_film(
    t: TableReader, oil: OilSpec, *, diameter: float | None = None, length: float | None = None
) -> FilmSpec:
    """Film data of a lubricated bearing from its table.

    ``diameter`` and ``length`` given here (the piston film) are not read from the table.
    """
    from recipsim.physics.mechanics.journal import (
        DEFAULT_CONTACT_FILM,
        DEFAULT_CONTACT_STIFFNESS,
        DEFAULT_FRICTION_COEFFICIENT,
    )

    positive = "> 0"
    if diameter is None:
        diameter = t.quantity("diameter", "m", lambda v: 1e-3 < v < 1.0, "1 mm ... 1 m")
    if length is None:
        length = t.quantity("length", "m", lambda v: 0.1 * diameter <= v <= 3.0 * diameter,
                            f"0.1 ... 3 diameters ({diameter:g} m)")  # fmt: skip
    clearance = t.quantity(
        "radial_clearance", "m", lambda v: 1e-4 * diameter <= v <= 1e-2 * diameter,
        "1e-4 ... 1e-2 of the diameter",
    )  # fmt: skip
    temperature = t.quantity(
        "film_temperature", "K", lambda v: 200.0 < v < 500.0, "200 ... 500 K",
        oil.film_temperature,
    )  # fmt: skip
    contact_film = t.quantity(
        "contact_film", "m", lambda v: 0.0 <= v < clearance,
        f"0 ... the radial clearance ({clearance:g} m)", DEFAULT_CONTACT_FILM,
    )  # fmt: skip
    stiffness = t.quantity(
        "contact_stiffness", "N/m", lambda v: v > 0.0, positive, DEFAULT_CONTACT_STIFFNESS
    )
    friction = t.quantity(
        "contact_friction", "dimensionless", lambda v: 0.0 <= v <= 1.0, "0 ... 1",
        DEFAULT_FRICTION_COEFFICIENT,
    )  # fmt: skip
    return FilmSpec(
        diameter, length, clearance, temperature, oil.viscosity(temperature),
        contact_film, stiffness, friction,
    )  # fmt: skip


def has_film_keys(data: Mapping[str, Any]) -> bool:
    """Whether a bearing table carries any film key."""
    return any(k in data for k in FILM_KEYS)
