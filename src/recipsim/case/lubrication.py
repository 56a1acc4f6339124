"""The case's oil (``[oil]``) and the film data of lubricated bearings, read once.

``[oil]`` keys (units as strings are converted; bare numbers are SI):

- ``name``: a named oil of :mod:`recipsim.physics.lubricant` (``iso_vg10``, the default;
  ``spindle_oil``) or, with ``law``, a label for the oil given here;
- ``law`` (``vogel``: three points of dynamic viscosity; ``walther``: two points),
  ``temperatures`` (list), ``viscosities`` (dynamic, list) or ``kinematic_viscosities``
  (list), ``density``: an oil of your own, fitted exactly through the points;
- ``film_temperature``: the film temperature of every lubricated bearing that does not
  give its own (default 60 C: a household compressor's oil runs at 50-70 C at the
  rating points; the films run a few kelvin above the sump). With ``options.thermal =
  "network"`` the mean friction (``options.friction = "mean"``) takes every film at the
  network's oil node temperature instead;
- ``dissolved_refrigerant_fraction``, ``molar_mass``: refrigerant dissolved in the oil
  (a mass fraction, default 0) and the oil's molar mass, which lower the mean friction's
  film viscosity by the logarithmic mixing rule in mole fractions
  (:func:`recipsim.physics.lubricant.diluted_viscosity`); the fraction is given, not
  computed from a solubility law (none for R600a in a mineral oil is implemented here).

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
from recipsim.errors import CaseError
from recipsim.physics.lubricant import (
    DEFAULT_OIL,
    MINERAL_OIL_MOLAR_MASS,
    fit_vogel,
    fit_walther,
    spindle_oil,
)
from recipsim.physics.mechanics.journal import (
    DEFAULT_CONTACT_FILM,
    DEFAULT_CONTACT_STIFFNESS,
    DEFAULT_FRICTION_COEFFICIENT,
)
from recipsim.schema import Described, DescribedSpec
from recipsim.units import to_si

#: Default film temperature [K] (60 C).
DEFAULT_FILM_TEMPERATURE = 333.15
_FILM = "with a film law"
_OWN = "with law"
#: The film keys of a lubricated bearing, read by :func:`parse_film` (units and range
#: words from here; the contact defaults are
#: :mod:`recipsim.physics.mechanics.journal`'s).
FILM_SPEC: DescribedSpec = {
    "diameter": Described(
        "m", "1 mm < value < 1 m", required=f"journals {_FILM}",
        doc="journal diameter (the piston film: the bore)",
        lo=1e-3, hi=1.0, open_lo=True, open_hi=True,
    ),
    "length": Described(
        "m", "0.1 ... 3 diameters", required=f"journals {_FILM}",
        doc="bearing length (the piston film: between piston_top and piston_skirt)",
    ),
    "radial_clearance": Described(
        "m", "1e-4 ... 1e-2 of the diameter", required=_FILM,
        doc="radial clearance, sleeve radius minus journal radius",
    ),
    "film_temperature": Described(
        "K", "200 K < value < 500 K", "oil.film_temperature",
        doc="film temperature at which the oil's viscosity is taken",
        lo=200.0, hi=500.0, open_lo=True, open_hi=True,
    ),
    "contact_film": Described(
        "m", "0 ... the radial clearance", "1 um",
        doc="film below which the asperity contact law acts",
    ),
    "contact_stiffness": Described(
        "N/m", "> 0", "1e10 N/m", doc="stiffness of the asperity contact (penalty) law",
        lo=0.0, open_lo=True,
    ),
    "contact_friction": Described(
        "dimensionless", "0 ... 1", "0.1", doc="friction coefficient of the asperity contact",
        lo=0.0, hi=1.0,
    ),
}  # fmt: skip
#: ``[oil]``: read by :func:`parse_oil`.
OIL_SPEC: DescribedSpec = {
    "name": Described(
        "", "iso_vg10, spindle_oil (a label with law)", "iso_vg10",
        doc="a named oil of recipsim.physics.lubricant, or a label for an oil given by law",
    ),
    "law": Described(
        "", "vogel (3 points), walther (2 points)", "not set (the named oil)",
        doc="viscosity-temperature law fitted through the points",
    ),
    "temperatures": Described(
        "K", "a list of 3 (vogel) or 2 (walther) temperatures", required=_OWN,
        doc="temperatures of the viscosity points",
    ),
    "viscosities": Described(
        "Pa*s", "a list, one per temperature", required=f"{_OWN} (or kinematic_viscosities)",
        doc="dynamic viscosity at the temperatures",
    ),
    "kinematic_viscosities": Described(
        "m**2/s", "a list, one per temperature", required=f"{_OWN} (or viscosities)",
        doc="kinematic viscosity at the temperatures (with density)",
    ),
    "density": Described(
        "kg/m**3", "500 < value < 2000", required=_OWN, doc="oil density",
        lo=500.0, hi=2000.0, open_lo=True, open_hi=True,
    ),
    "film_temperature": Described(
        "K", "200 K < value < 500 K", "60 degC",
        doc="film temperature of every lubricated bearing that gives none (with "
        'options.thermal = "network", the mean friction takes the oil node\'s instead)',
        lo=200.0, hi=500.0, open_lo=True, open_hi=True,
    ),
    "dissolved_refrigerant_fraction": Described(
        "dimensionless", "0 ... 0.5", "0 (no dilution)",
        doc="mass fraction of refrigerant dissolved in the oil of the mean friction's films "
        "(mixing rule in recipsim.physics.lubricant.diluted_viscosity)",
        lo=0.0, hi=0.5,
    ),
    "molar_mass": Described(
        "kg/mol", "0.1 ... 2", "0.30 kg/mol (a light mineral oil)",
        doc="the oil's mean molar mass, for the dilution's mole fractions",
        lo=0.1, hi=2.0,
    ),
}  # fmt: skip
_OIL_KEYS = tuple(OIL_SPEC)
_DILUTION_KEYS = ("dissolved_refrigerant_fraction", "molar_mass")
FILM_KEYS = tuple(FILM_SPEC)


@dataclass(frozen=True)
class OilSpec:
    """The case's oil (SI).

    Attributes
    ----------
    oil : recipsim.physics.lubricant.Oil
        Density and the fitted viscosity-temperature law.
    film_temperature : float
        Default film temperature of the lubricated bearings [K].
    dissolved_refrigerant_fraction : float
        Mass fraction of refrigerant in the oil of the mean friction's films [-].
    molar_mass : float
        The oil's mean molar mass [kg/mol].
    """

    oil: Any
    film_temperature: float
    dissolved_refrigerant_fraction: float = 0.0
    molar_mass: float = MINERAL_OIL_MOLAR_MASS

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


_OIL_NAMES = ("iso_vg10", "spindle_oil")


def _named_oil(name: str) -> Any:
    """The shipped oil called ``name`` (one of ``_OIL_NAMES``); the spindle oil's Vogel
    fit runs only when it is asked for."""
    return DEFAULT_OIL if name == "iso_vg10" else spindle_oil()


def _points(t: TableReader, name: str, unit: str) -> tuple[float, ...]:
    values = t.data.get(name)
    if not isinstance(values, list) or not values:
        raise CaseError(t.file, t.key(name), f"expected a list of values in {unit}")
    return tuple(to_si(v, unit, t.file, f"{t.key(name)}[{i}]") for i, v in enumerate(values))


def parse_oil(data: Any, file: str) -> OilSpec:
    """Read the ``[oil]`` table (``None``: the default oil at the default temperature)."""
    t = TableReader({} if data is None else data, file, "oil")
    t.check_keys(_OIL_KEYS)
    temperature = t.described(OIL_SPEC, "film_temperature", default=DEFAULT_FILM_TEMPERATURE)
    dilution = (
        t.described(OIL_SPEC, "dissolved_refrigerant_fraction", default=0.0),
        t.described(OIL_SPEC, "molar_mass", default=MINERAL_OIL_MOLAR_MASS),
    )
    if "law" not in t.data:
        name = t.choice("name", _OIL_NAMES, "iso_vg10")
        extra = set(t.data) - {"name", "film_temperature", *_DILUTION_KEYS}
        if extra:
            raise CaseError(file, t.key(sorted(extra)[0]), "needs oil.law (vogel or walther)")
        return OilSpec(_named_oil(name), temperature, *dilution)

    law = t.choice("law", ("vogel", "walther"))
    label = str(t.data.get("name", "oil of the case"))
    density = t.described(OIL_SPEC, "density")
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
    return OilSpec(oil, temperature, *dilution)


def parse_film(
    t: TableReader, oil: OilSpec, *, diameter: float | None = None, length: float | None = None
) -> FilmSpec:
    """Film data of a lubricated bearing from its table.

    ``diameter`` and ``length`` given here (the piston film) are not read from the table.
    """
    spec = FILM_SPEC
    if diameter is None:
        diameter = t.described(spec, "diameter")
    if length is None:
        length = t.described(spec, "length", lambda v: 0.1 * diameter <= v <= 3.0 * diameter,
                             None, f"diameter {diameter:g} m")  # fmt: skip
    clearance = t.described(
        spec, "radial_clearance", lambda v: 1e-4 * diameter <= v <= 1e-2 * diameter
    )
    temperature = t.described(spec, "film_temperature", default=oil.film_temperature)
    contact_film = t.described(spec, "contact_film", lambda v: 0.0 <= v < clearance,
                               DEFAULT_CONTACT_FILM, f"{clearance:g} m")  # fmt: skip
    stiffness = t.described(spec, "contact_stiffness", default=DEFAULT_CONTACT_STIFFNESS)
    friction = t.described(spec, "contact_friction", default=DEFAULT_FRICTION_COEFFICIENT)
    return FilmSpec(
        diameter, length, clearance, temperature, oil.viscosity(temperature),
        contact_film, stiffness, friction,
    )  # fmt: skip


def has_film_keys(data: Mapping[str, Any]) -> bool:
    """Whether a bearing table carries any film key."""
    return any(k in data for k in FILM_KEYS)
