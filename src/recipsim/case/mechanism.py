"""Mechanism data (masses, inertias, bearings) as frozen dataclasses, and their parser.

Case tables read here (units as strings are converted by :func:`recipsim.case.units.to_si`;
bare numbers are taken in SI)::

    [mechanism.piston]          mass, length, pin_offset_from_crown,
                                centre_of_mass_from_crown (optional, default length/2),
                                transverse_inertia (optional, about the pin axis through
                                the centre of mass; default: solid-cylinder estimate)
    [mechanism.connecting_rod]  mass, centre_of_mass_fraction (from the big end), inertia
    [mechanism.rotor]           mass, polar_inertia, transverse_inertia, centre_of_mass_z,
                                primary_z, secondary_z  (eccentric plane is z = 0)
    [bearings.<name>]           law = "linear", stiffness, damping;
                                piston_top / piston_skirt also position_from_crown

for ``<name>`` in primary, secondary, eccentric, pin, piston_top, piston_skirt.
The slider-crank geometry shared with the cylinder (bore, crank radius, rod length)
is not read here: it is passed separately as a :class:`CrankGeometry`.
"""

from __future__ import annotations

import math
from collections.abc import Collection, Mapping
from dataclasses import dataclass, replace
from typing import Any

from recipsim.case.lubrication import (
    FILM_KEYS,
    FilmSpec,
    OilSpec,
    has_film_keys,
    parse_film,
    parse_oil,
)
from recipsim.case.mechanism_schema import BEARING_SPEC, PISTON_SPEC, ROD_SPEC, ROTOR_SPEC
from recipsim.case.table_reader import TableReader as _Table
from recipsim.errors import CaseError
from recipsim.physics.mechanics.layout import BEARING_LAWS, BEARING_NAMES

_INERTIA = "kg*m**2"


@dataclass(frozen=True)
class CrankGeometry:
    """Slider-crank geometry shared with the cylinder model (SI).

    Attributes
    ----------
    bore : float
        Cylinder bore = piston diameter [m].
    crank_radius : float
        Crank radius r = stroke / 2 [m].
    rod_length : float
        Connecting-rod length L between the big-end and small-end centres [m].
    """

    bore: float
    crank_radius: float
    rod_length: float

    @classmethod
    def from_stroke(cls, bore: float, stroke: float, rod_length: float) -> CrankGeometry:
        """Build from bore, stroke and rod length, all in [m]."""
        return cls(bore=bore, crank_radius=0.5 * stroke, rod_length=rod_length)

    @property
    def piston_area(self) -> float:
        """Crown area pi D^2 / 4 [m^2]."""
        return math.pi * self.bore**2 / 4.0


@dataclass(frozen=True)
class PistonSpec:
    """Piston as a rigid body (SI).

    Attributes
    ----------
    mass : float
        [kg].
    length : float
        Axial length, crown to skirt end [m].
    pin_offset_from_crown : float
        Distance of the pin axis below the crown [m].
    centre_of_mass_from_crown : float
        Distance of the centre of mass below the crown [m].
    transverse_inertia : float
        Moment of inertia about the pin axis (Z) through the centre of mass [kg m^2].
    """

    mass: float
    length: float
    pin_offset_from_crown: float
    centre_of_mass_from_crown: float
    transverse_inertia: float


@dataclass(frozen=True)
class ConnectingRodSpec:
    """Connecting rod as a planar rigid body (SI).

    Attributes
    ----------
    mass : float
        [kg].
    centre_of_mass_fraction : float
        Distance of the centre of mass from the big end over the rod length [-].
    inertia : float
        Moment of inertia about Z through the centre of mass [kg m^2].
    """

    mass: float
    centre_of_mass_fraction: float
    inertia: float


@dataclass(frozen=True)
class RotorSpec:
    """Motor rotor plus crankshaft, axisymmetric and balanced (SI).

    Attributes
    ----------
    mass : float
        [kg].
    polar_inertia, transverse_inertia : float
        About the spin axis and about a diameter through the centre of mass [kg m^2].
    centre_of_mass_z : float
        Axial position of the centre of mass (eccentric plane at z = 0) [m].
    primary_z, secondary_z : float
        Axial positions of the primary (1) and secondary (2) bearings [m].
    counterweight_mass : float
        Counterweight: a point mass on the rotor [kg] (0: none). ``mass`` and the
        inertias are the rotor's without it.
    counterweight_radius : float
        Its distance from the spin axis [m].
    counterweight_angle : float
        Its angle ahead of the crank pin about +Z [rad] (pi: opposite the pin).
    counterweight_z : float
        Its axial position [m].
    """

    mass: float
    polar_inertia: float
    transverse_inertia: float
    centre_of_mass_z: float
    primary_z: float
    secondary_z: float
    counterweight_mass: float = 0.0
    counterweight_radius: float = 0.0
    counterweight_angle: float = math.pi
    counterweight_z: float = 0.0


@dataclass(frozen=True)
class BearingSpec:
    """One bearing: a law and its parameters (SI).

    Attributes
    ----------
    law : str
        ``"linear"``: isotropic spring and dashpot normal to the bearing axis;
        ``"short_journal"``, ``"finite_journal"``: hydrodynamic journal;
        ``"skirt_film"``: the piston's lubricated skirt (piston_top and piston_skirt).
    stiffness : float
        [N/m] (linear law; 0 when not given).
    damping : float
        [N s/m] (linear law).
    position_from_crown : float or None
        Piston bearings only: axial position of the bearing marker below the crown [m].
    film : FilmSpec or None
        Film data (geometry, clearance, viscosity, contact), required by the film laws
        and kept when given for a linear bearing (so the law can be switched).
    """

    law: str
    stiffness: float
    damping: float
    position_from_crown: float | None = None
    film: FilmSpec | None = None


@dataclass(frozen=True)
class MechanismSpec:
    """Everything the mechanism needs besides the slider-crank geometry.

    ``bearings`` holds one :class:`BearingSpec` per name of
    :data:`recipsim.physics.mechanics.layout.BEARING_NAMES`, in that order.
    """

    piston: PistonSpec
    connecting_rod: ConnectingRodSpec
    rotor: RotorSpec
    bearings: tuple[BearingSpec, ...]
    oil: OilSpec | None = None

    def bearing(self, name: str) -> BearingSpec:
        """The bearing called ``name`` (one of ``BEARING_NAMES``)."""
        return self.bearings[BEARING_NAMES.index(name)]


# --------------------------------------------------------------------------- helpers


def solid_cylinder_transverse_inertia(mass: float, diameter: float, length: float) -> float:
    """Moment of inertia of a solid cylinder about a diameter through its centre.

    ``m (3 R^2 + l^2) / 12``; used as the default piston inertia. A real piston is a
    hollow cup whose inertia is somewhat larger (a thin shell gives
    ``m (6 R^2 + l^2) / 12``), so this is an estimate for the reference compressor
    (35 g, 22 mm x 20 mm: 2.23e-6 kg m^2).

    Parameters
    ----------
    mass : float
        [kg].
    diameter, length : float
        [m].

    Returns
    -------
    float
        [kg m^2].
    """
    radius = 0.5 * diameter
    return mass * (3.0 * radius**2 + length**2) / 12.0


def scale_bearings(
    spec: MechanismSpec, stiffness_factor: float, damping_factor: float | None = None
) -> MechanismSpec:
    """Return a copy with every bearing stiffness scaled.

    Parameters
    ----------
    spec : MechanismSpec
    stiffness_factor : float
        Factor on every stiffness [-].
    damping_factor : float, optional
        Factor on every damping [-]. Default ``sqrt(stiffness_factor)``, which keeps
        every damping ratio ``c / (2 sqrt(k m))``.
    """
    if damping_factor is None:
        damping_factor = math.sqrt(stiffness_factor)
    bearings = tuple(
        replace(b, stiffness=b.stiffness * stiffness_factor, damping=b.damping * damping_factor)
        for b in spec.bearings
    )
    return replace(spec, bearings=bearings)


def with_damping(spec: MechanismSpec, damping: float | Mapping[str, float]) -> MechanismSpec:
    """Return a copy with the bearing damping replaced [N s/m] (one value or per name)."""
    bearings = []
    for name, b in zip(BEARING_NAMES, spec.bearings, strict=True):
        c = damping[name] if isinstance(damping, Mapping) else damping
        bearings.append(replace(b, damping=float(c)))
    return replace(spec, bearings=tuple(bearings))


# ---------------------------------------------------------------------------- parser


def _positive(v: float) -> bool:
    return v > 0.0


def _non_negative(v: float) -> bool:
    return v >= 0.0


def _any(v: float) -> bool:
    return True


_PISTON_KEYS = tuple(PISTON_SPEC)
_ROD_KEYS = tuple(ROD_SPEC)
_COUNTERWEIGHT_KEYS = (
    "counterweight_mass",
    "counterweight_radius",
    "counterweight_angle",
    "counterweight_z",
)
_ROTOR_KEYS = tuple(ROTOR_SPEC)
_BEARING_KEYS = ("law", "stiffness", "damping", *FILM_KEYS)
#: Keys of the piston bearings (the film's diameter and length come from the piston).
PISTON_BEARING_KEYS = ("law", "stiffness", "damping", "position_from_crown",
                       "radial_clearance", "film_temperature", "contact_film",
                       "contact_stiffness", "contact_friction")  # fmt: skip


def _parse_piston(t: _Table, bore: float | None) -> PistonSpec:
    t.check_keys(_PISTON_KEYS)
    spec = PISTON_SPEC
    mass = t.described(spec, "mass", _positive)
    length = t.described(spec, "length", _positive)
    within = f"{length:g} m"
    pin = t.described(spec, "pin_offset_from_crown", lambda v: 0.0 <= v <= length, None, within)
    com = t.described(
        spec, "centre_of_mass_from_crown", lambda v: 0.0 <= v <= length, 0.5 * length, within
    )
    if "transverse_inertia" in t.data:
        inertia = t.described(spec, "transverse_inertia", _positive)
    elif bore is None:
        raise CaseError(
            t.file,
            t.key("transverse_inertia"),
            "missing, and no bore was given for the solid-cylinder estimate; allowed: > 0 "
            f"({_INERTIA})",
        )
    else:
        inertia = solid_cylinder_transverse_inertia(mass, bore, length)
    return PistonSpec(mass, length, pin, com, inertia)


def _parse_rod(t: _Table) -> ConnectingRodSpec:
    t.check_keys(_ROD_KEYS)
    mass = t.described(ROD_SPEC, "mass", _positive)
    frac = t.described(ROD_SPEC, "centre_of_mass_fraction", lambda v: 0.0 < v < 1.0)
    inertia = t.described(ROD_SPEC, "inertia", _positive)
    return ConnectingRodSpec(mass, frac, inertia)


def _parse_rotor(t: _Table) -> RotorSpec:
    t.check_keys(_ROTOR_KEYS)
    spec = ROTOR_SPEC
    mass = t.described(spec, "mass", _positive)
    ip = t.described(spec, "polar_inertia", _positive)
    it = t.described(spec, "transverse_inertia", _positive)
    zg = t.described(spec, "centre_of_mass_z", _any)
    z1 = t.described(spec, "primary_z", _any)
    z2 = t.described(spec, "secondary_z", lambda v: v != z1, None, f"primary_z = {z1:g} m")
    extra = [k for k in _COUNTERWEIGHT_KEYS[1:] if k in t.data]
    if extra and "counterweight_mass" not in t.data:
        raise CaseError(t.file, t.key(extra[0]), "needs counterweight_mass")
    m_u = t.described(spec, "counterweight_mass", _non_negative, 0.0)
    if not extra and m_u == 0.0:
        return RotorSpec(mass, ip, it, zg, z1, z2)
    r_u = t.described(spec, "counterweight_radius", _positive)
    ang = t.described(spec, "counterweight_angle", _any, math.pi)
    z_u = t.described(spec, "counterweight_z", _any, 0.0)
    if m_u == 0.0:  # a sweep's zero point: the other keys are checked, nothing is added
        return RotorSpec(mass, ip, it, zg, z1, z2)
    return RotorSpec(mass, ip, it, zg, z1, z2, m_u, r_u, ang, z_u)


class _LazyOil:
    """The ``[oil]`` table, parsed when a lubricated bearing first needs it (a case
    without one never imports the oil laws)."""

    def __init__(self, data: Any, file: str) -> None:
        self.data = data
        self.file = file
        self.spec: OilSpec | None = None

    def get(self) -> OilSpec:
        if self.spec is None:
            self.spec = parse_oil(self.data, self.file)
        return self.spec


def _parse_bearing(
    t: _Table, name: str, piston: PistonSpec, bore: float | None, oil: _LazyOil, default_law: str
) -> BearingSpec:
    """One ``[bearings.<name>]`` table; ``default_law`` (``options.bearing_law``) applies
    to the journals that name no law of their own."""
    is_piston = name in ("piston_top", "piston_skirt")
    t.check_keys(PISTON_BEARING_KEYS if is_piston else _BEARING_KEYS)
    allowed = BEARING_LAWS[name]
    fallback = default_law if default_law in allowed and not is_piston else "linear"
    law = t.choice("law", allowed, None if is_piston or name == "pin" else fallback)
    needs_spring = law == "linear"
    spec = BEARING_SPEC
    k = t.described(spec, "stiffness", _positive, None if needs_spring else 0.0)
    c = t.described(spec, "damping", _non_negative, None if needs_spring else 0.0)
    position = None
    if is_piston:
        position = t.described(
            spec,
            "position_from_crown",
            lambda v: 0.0 <= v <= piston.length,
            None,
            f"{piston.length:g} m",
        )
    film = None
    if law == "skirt_film" or (is_piston and "radial_clearance" in t.data):
        if bore is None:
            raise CaseError(t.file, t.key("law"), "the piston film needs the bore")
        film = parse_film(t, oil.get(), diameter=bore, length=piston.length)
    elif law != "linear" or (not is_piston and has_film_keys(t.data)):
        film = parse_film(t, oil.get())
    return BearingSpec(law=law, stiffness=k, damping=c, position_from_crown=position, film=film)


def _check_piston_film(bearings: list[BearingSpec], file: str) -> None:
    """The piston's two stations form one film: both ``skirt_film`` or neither, with one
    clearance and one temperature."""
    top, skirt = bearings[4], bearings[5]
    if (top.law == "skirt_film") != (skirt.law == "skirt_film"):
        raise CaseError(
            file,
            "bearings.piston_skirt.law",
            "piston_top and piston_skirt form one film: both skirt_film or neither",
        )
    if top.law == "skirt_film" and top.film is not None and skirt.film is not None:
        for key in ("radial_clearance", "film_temperature"):
            if getattr(top.film, key) != getattr(skirt.film, key):
                raise CaseError(file, f"bearings.piston_skirt.{key}",
                                "differs from piston_top's; allowed: the same value")  # fmt: skip


def mechanism_from_dict(
    tables: Mapping[str, Any],
    file: str,
    *,
    bore: float | None = None,
    allowed_extra_keys: Collection[str] = (),
    default_law: str = "linear",
) -> MechanismSpec:
    """Read the ``[mechanism.*]`` and ``[bearings.*]`` tables of a case.

    Parameters
    ----------
    tables : mapping
        The parsed case file (other top-level tables are ignored).
    file : str
        Path of the case file, for error messages.
    bore : float, optional
        Cylinder bore [m]; used only for the default piston inertia.
    allowed_extra_keys : collection of str
        Keys of ``[mechanism]`` and ``[bearings]`` that belong to someone else (e.g. a
        model-selection key) and are skipped instead of being rejected.
    default_law : str
        Law of the journals whose table names none (``options.bearing_law``).

    Returns
    -------
    MechanismSpec

    Raises
    ------
    CaseError
        For a missing table or key, an unknown key, a wrong unit or a value out of range;
        the message lists what is allowed.
    """
    if "mechanism" not in tables:
        raise CaseError(file, "mechanism", "missing table; needs piston, connecting_rod, rotor")
    mech = _Table(tables["mechanism"], file, "mechanism")
    mech.check_keys(("piston", "connecting_rod", "rotor", *allowed_extra_keys))
    for sub in ("piston", "connecting_rod", "rotor"):
        if sub not in mech.data:
            raise CaseError(file, mech.key(sub), "missing table")
    piston = _parse_piston(_Table(mech.data["piston"], file, "mechanism.piston"), bore)
    rod = _parse_rod(_Table(mech.data["connecting_rod"], file, "mechanism.connecting_rod"))
    rotor = _parse_rotor(_Table(mech.data["rotor"], file, "mechanism.rotor"))

    if "bearings" not in tables:
        raise CaseError(file, "bearings", f"missing table; needs {', '.join(BEARING_NAMES)}")
    brg = _Table(tables["bearings"], file, "bearings")
    brg.check_keys((*BEARING_NAMES, *allowed_extra_keys))
    oil = _LazyOil(tables.get("oil"), file)
    bearings = []
    for name in BEARING_NAMES:
        if name not in brg.data:
            raise CaseError(file, brg.key(name), "missing table")
        table = _Table(brg.data[name], file, brg.key(name))
        bearings.append(_parse_bearing(table, name, piston, bore, oil, default_law))
    _check_piston_film(bearings, file)
    top, skirt = bearings[4].position_from_crown, bearings[5].position_from_crown
    if top == skirt:
        raise CaseError(
            file,
            "bearings.piston_skirt.position_from_crown",
            f"equals the piston_top position ({top!r} m); allowed: any other position",
        )
    if "oil" in tables:
        oil.get()  # validated even when no bearing uses it
    return MechanismSpec(piston, rod, rotor, tuple(bearings), oil.spec)


# ------------------------------------------------------------------ reference compressor


def reference_mechanism_tables() -> dict[str, Any]:
    """Case tables of the reference compressor (design notes section 4), with units.

    Masses, inertias and damping are engineering estimates; stiffnesses k1, k2, k3, k5,
    k6 are the paper's (Kurka et al., ISMA 2010). Choices made here:

    - piston inertia: solid cylinder 35 g, 22 mm x 20 mm (2.23e-6 kg m^2), centre of
      mass at mid-length, i.e. on the pin axis;
    - piston pin stiffness: 5e7 N/m (stiff; the paper treats the pin as rigid);
    - piston_top / piston_skirt markers at the two Gauss points of the piston length
      (4.23 mm and 15.77 mm below the crown): two springs k/2 there have the same force
      and moment stiffness as a uniform elastic foundation of total stiffness k;
    - damping: about 50 % of critical on the carried mass
      (c = 2 * 0.5 * sqrt(k m), m = 0.45 kg per rotor bearing, 65 g for the eccentric,
      35 g for the pin, 17.5 g for each piston bearing), rounded. With it the viscous
      bearing forces are about a tenth of the elastic ones, as the paper reports for
      its "parametric dissipation" (whose values it does not give). Real oil films
      damp far more (short-bearing squeeze damping is of order 1e5 N s/m);
    - journal film data (diameter, length, 10 um radial clearance) and the ISO VG 10
      oil at 60 C for the hydrodynamic laws; the journals take the default law
      (``options.bearing_law``, linear unless set).
    """
    gauss = 10.0 / math.sqrt(3.0)
    return {
        "mechanism": {
            "piston": {
                "mass": "35 g",
                "length": "20 mm",
                "pin_offset_from_crown": "10 mm",
                "centre_of_mass_from_crown": "10 mm",
                "transverse_inertia": "2.2254e-6 kg*m**2",
            },
            "connecting_rod": {
                "mass": "30 g",
                "centre_of_mass_fraction": 0.35,
                "inertia": "4e-6 kg*m**2",
            },
            "rotor": {
                "mass": "0.90 kg",
                "polar_inertia": "3.5e-4 kg*m**2",
                "transverse_inertia": "7.0e-4 kg*m**2",
                "centre_of_mass_z": "-40 mm",
                "primary_z": "-20 mm",
                "secondary_z": "-52 mm",
            },
        },
        "bearings": {
            "primary": {
                "stiffness": "5.0e7 N/m",
                "damping": "4700 N*s/m",
                **_journal("16 mm", "20 mm"),
            },
            "secondary": {
                "stiffness": "4.0e7 N/m",
                "damping": "4200 N*s/m",
                **_journal("14 mm", "12 mm"),
            },
            "eccentric": {
                "stiffness": "2.5e7 N/m",
                "damping": "1300 N*s/m",
                **_journal("14 mm", "12 mm"),
            },
            "pin": {"law": "linear", "stiffness": "5.0e7 N/m", "damping": "1300 N*s/m"},
            "piston_top": {
                "law": "linear",
                "stiffness": "3.0e7 N/m",
                "damping": "730 N*s/m",
                "position_from_crown": f"{10.0 - gauss:.4f} mm",
            },
            "piston_skirt": {
                "law": "linear",
                "stiffness": "3.0e7 N/m",
                "damping": "730 N*s/m",
                "position_from_crown": f"{10.0 + gauss:.4f} mm",
            },
        },
        "oil": {"name": "iso_vg10", "film_temperature": "60 degC"},
    }


def _journal(diameter: str, length: str) -> dict[str, str]:
    """Film data of a reference journal (design notes section 4): 10 um radial clearance."""
    return {"diameter": diameter, "length": length, "radial_clearance": "10 um"}


def reference_geometry() -> CrankGeometry:
    """Reference compressor slider-crank: bore 22 mm, stroke 18.4 mm, rod 36 mm."""
    return CrankGeometry.from_stroke(bore=0.022, stroke=0.0184, rod_length=0.036)


def reference_mechanism() -> MechanismSpec:
    """:func:`reference_mechanism_tables` parsed."""
    return mechanism_from_dict(reference_mechanism_tables(), "<reference>")


#: Reference compressor speed, 3500 rpm [rad/s].
REFERENCE_SPEED = 3500.0 * 2.0 * math.pi / 60.0
