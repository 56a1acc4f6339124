"""The parser of the mechanism tables of a case into :mod:`.mechanism_spec`'s dataclasses.

Case tables read here (units as strings are converted by :func:`recipsim.units.to_si`;
bare numbers are taken in SI)::

    [mechanism.piston]          mass, length, pin_offset_from_crown,
                                centre_of_mass_from_crown (optional, default length/2),
                                transverse_inertia (optional, about the pin axis through
                                the centre of mass; default: solid-cylinder estimate)
    [mechanism.connecting_rod]  mass, centre_of_mass_fraction (from the big end), inertia
    [mechanism.rotor]           mass, polar_inertia, transverse_inertia, centre_of_mass_z,
                                primary_z, secondary_z  (eccentric plane is z = 0)
    [bearings.<name>]           law (a bearing law), stiffness, damping (linear law);
                                piston_top / piston_skirt also position_from_crown

for ``<name>`` in primary, secondary, eccentric, pin, piston_top, piston_skirt.
The slider-crank geometry shared with the cylinder (bore, crank radius, rod length)
is not read here: it is passed separately as a :class:`CrankGeometry`.

:class:`CrankGeometry` and :class:`MechanismSpec` live in :mod:`.mechanism_spec`; they
are imported from here by :mod:`recipsim.case.build` and :mod:`recipsim.model.build`.
"""

from __future__ import annotations

import math
from collections.abc import Collection, Mapping
from typing import Any

from recipsim.case.lubrication import FILM_KEYS, OilSpec, has_film_keys, parse_film, parse_oil
from recipsim.case.mechanism_schema import BEARING_SPEC, PISTON_SPEC, ROD_SPEC, ROTOR_SPEC
from recipsim.case.mechanism_spec import (
    BearingSpec,
    ConnectingRodSpec,
    CrankGeometry,
    MechanismSpec,
    PistonSpec,
    RotorSpec,
    solid_cylinder_transverse_inertia,
)
from recipsim.case.table_reader import TableReader as _Table
from recipsim.errors import CaseError
from recipsim.physics.mechanics.bearing_laws.registry import (
    BEARING_LAWS,
    DEFAULT_LAW,
    laws_of,
)
from recipsim.physics.mechanics.layout import BEARING_NAMES, PISTON_STATION_NAMES

__all__ = ["PISTON_BEARING_KEYS", "CrankGeometry", "MechanismSpec", "mechanism_from_dict"]

_INERTIA = "kg*m**2"


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
    mass = t.described(spec, "mass")
    length = t.described(spec, "length")
    within = f"{length:g} m"
    pin = t.described(spec, "pin_offset_from_crown", lambda v: 0.0 <= v <= length, None, within)
    com = t.described(
        spec, "centre_of_mass_from_crown", lambda v: 0.0 <= v <= length, 0.5 * length, within
    )
    if "transverse_inertia" in t.data:
        inertia = t.described(spec, "transverse_inertia")
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
    mass = t.described(ROD_SPEC, "mass")
    frac = t.described(ROD_SPEC, "centre_of_mass_fraction")
    inertia = t.described(ROD_SPEC, "inertia")
    return ConnectingRodSpec(mass, frac, inertia)


def _parse_rotor(t: _Table) -> RotorSpec:
    t.check_keys(_ROTOR_KEYS)
    spec = ROTOR_SPEC
    mass = t.described(spec, "mass")
    ip = t.described(spec, "polar_inertia")
    it = t.described(spec, "transverse_inertia")
    zg = t.described(spec, "centre_of_mass_z")
    z1 = t.described(spec, "primary_z")
    z2 = t.described(spec, "secondary_z", lambda v: v != z1, None, f"primary_z = {z1:g} m")
    extra = [k for k in _COUNTERWEIGHT_KEYS[1:] if k in t.data]
    if extra and "counterweight_mass" not in t.data:
        raise CaseError(t.file, t.key(extra[0]), "needs counterweight_mass")
    m_u = t.described(spec, "counterweight_mass", default=0.0)
    if not extra and m_u == 0.0:
        return RotorSpec(mass, ip, it, zg, z1, z2)
    r_u = t.described(spec, "counterweight_radius")
    ang = t.described(spec, "counterweight_angle", default=math.pi)
    z_u = t.described(spec, "counterweight_z", default=0.0)
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
    is_piston = name in PISTON_STATION_NAMES
    t.check_keys(PISTON_BEARING_KEYS if is_piston else _BEARING_KEYS)
    allowed = laws_of(name)
    fallback = default_law if default_law in allowed and not is_piston else DEFAULT_LAW
    default = None if is_piston else allowed[0] if len(allowed) == 1 else fallback
    law = t.choice("law", allowed, default)
    needs_spring = BEARING_LAWS[law].spring
    spec = BEARING_SPEC
    k = t.described(spec, "stiffness", default=None if needs_spring else 0.0)
    c = t.described(spec, "damping", default=None if needs_spring else 0.0)
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
    if BEARING_LAWS[law].station_pair or (is_piston and "radial_clearance" in t.data):
        if bore is None:
            raise CaseError(t.file, t.key("law"), "the piston film needs the bore")
        film = parse_film(t, oil.get(), diameter=bore, length=piston.length)
    elif BEARING_LAWS[law].film or (not is_piston and has_film_keys(t.data)):
        film = parse_film(t, oil.get())
    return BearingSpec(law=law, stiffness=k, damping=c, position_from_crown=position, film=film)


def _check_piston_film(bearings: list[BearingSpec], file: str) -> None:
    """The piston's two stations form one film: both on a station-pair law (the skirt
    film) or neither, the same law, with one clearance and one temperature."""
    top, skirt = bearings[4], bearings[5]
    paired = BEARING_LAWS[top.law].station_pair
    if paired != BEARING_LAWS[skirt.law].station_pair or (paired and top.law != skirt.law):
        law = top.law if paired else skirt.law
        raise CaseError(
            file,
            "bearings.piston_skirt.law",
            f"piston_top and piston_skirt form one film: both {law} or neither",
        )
    if paired and top.film is not None and skirt.film is not None:
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
    default_law: str | None = None,
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
    default_law : str or None
        Law of the journals whose table names none (``options.bearing_law``; None: the
        slot's default).

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
        law = DEFAULT_LAW if default_law is None else default_law
        bearings.append(_parse_bearing(table, name, piston, bore, oil, law))
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
