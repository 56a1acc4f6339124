"""The keys of the ``[mechanism.*]`` and ``[bearings.<name>]`` tables: SI unit, range in
words, default, when required, meaning (:class:`recipsim.schema.Described`).

:mod:`recipsim.case.mechanism` reads every key with the unit and the range words declared
here (its messages say them) and checks the rules in code; the case-file reference
(``docs/_ext/case_reference.py``) prints the same declarations.
"""

from __future__ import annotations

from recipsim.case.lubrication import FILM_SPEC
from recipsim.physics.mechanics.bearing_laws import linear
from recipsim.physics.mechanics.bearing_laws.registry import laws_of
from recipsim.physics.mechanics.layout import BEARING_NAMES
from recipsim.schema import Described, DescribedSpec

_INERTIA = "kg*m**2"
_D = Described
#: ``[mechanism.piston]``: read by :func:`_parse_piston` (units and range words from here).
PISTON_SPEC: DescribedSpec = {
    "mass": _D("kg", "> 0", doc="piston with its pin", lo=0.0, open_lo=True),
    "length": _D("m", "> 0", doc="crown to skirt end", lo=0.0, open_lo=True),
    "pin_offset_from_crown": _D("m", "0 ... length", doc="pin axis below the crown"),
    "centre_of_mass_from_crown": _D(
        "m", "0 ... length", "length / 2", doc="centre of mass below the crown"
    ),
    "transverse_inertia": _D(
        _INERTIA, "> 0", "solid cylinder of the bore and the length",
        doc="about the pin axis through the centre of mass", lo=0.0, open_lo=True,
    ),
}  # fmt: skip
#: ``[mechanism.connecting_rod]``.
ROD_SPEC: DescribedSpec = {
    "mass": _D("kg", "> 0", doc="connecting rod", lo=0.0, open_lo=True),
    "centre_of_mass_fraction": _D(
        "dimensionless",
        "0 < value < 1",
        doc="centre of mass from the big end, over the length",
        lo=0.0,
        hi=1.0,
        open_lo=True,
        open_hi=True,
    ),
    "inertia": _D(
        _INERTIA,
        "> 0",
        doc="about the rotor-parallel axis through the centre of mass",
        lo=0.0,
        open_lo=True,
    ),
}
_COUNTERWEIGHT = "with counterweight_mass"
#: ``[mechanism.rotor]``.
ROTOR_SPEC: DescribedSpec = {
    "mass": _D("kg", "> 0", doc="motor rotor plus crankshaft", lo=0.0, open_lo=True),
    "polar_inertia": _D(_INERTIA, "> 0", doc="about the spin axis", lo=0.0, open_lo=True),
    "transverse_inertia": _D(_INERTIA, "> 0", doc="about a diameter through the centre of mass",
                              lo=0.0, open_lo=True),
    "centre_of_mass_z": _D("m", "any finite value", doc="axial position, eccentric plane at z = 0"),
    "primary_z": _D("m", "any finite value", doc="axial position of the primary bearing"),
    "secondary_z": _D(
        "m", "any finite value other than primary_z", doc="axial position of the secondary bearing"
    ),
    "counterweight_mass": _D(
        "kg", ">= 0", "0 (none)",
        doc="rotating unbalance on the crank web (0: none, placement keys still checked)",
        lo=0.0,
    ),
    "counterweight_radius": _D(
        "m", "> 0", required=_COUNTERWEIGHT, doc="radius of the counterweight's centre of mass",
        lo=0.0, open_lo=True,
    ),
    "counterweight_angle": _D(
        "rad", "any angle", "pi (opposite the crank pin)",
        doc="from the crank pin, along the rotation",
    ),
    "counterweight_z": _D("m", "any finite value", "0", doc="axial position of the counterweight"),
}  # fmt: skip


def _laws_in_words() -> str:
    """The laws each bearing accepts, from the bearing laws' registry."""
    groups: dict[tuple[str, ...], list[str]] = {}
    for name in BEARING_NAMES:
        groups.setdefault(laws_of(name), []).append(name)
    return "; ".join(f"{', '.join(names)}: {', '.join(laws)}" for laws, names in groups.items())


#: ``[bearings.<name>]``: the law and the linear law's keys, then the film keys
#: (:data:`recipsim.case.lubrication.FILM_SPEC`); ``position_from_crown`` and only some
#: film keys on the piston bearings.
BEARING_SPEC: DescribedSpec = {
    "law": _D(
        "", _laws_in_words(),
        "journals: options.bearing_law; a bearing with one law: that law",
        required="piston bearings", doc="bearing force law",
    ),
    **linear.LAW.keys["bearings.<name>"],
    "position_from_crown": _D(
        "m", "0 ... piston length", required="piston_top, piston_skirt",
        doc="piston bearings: marker below the crown",
    ),
    **FILM_SPEC,
}  # fmt: skip


def described_units(*specs: DescribedSpec) -> dict[str, str]:
    """SI unit (pint syntax) of every numeric key of ``specs`` (string keys left out); a
    key declared in several tables must have one unit in all of them."""
    units: dict[str, str] = {}
    for spec in specs:
        for key, described in spec.items():
            if not described.unit:
                continue
            if units.setdefault(key, described.unit) != described.unit:
                raise ValueError(f"{key}: two units, {units[key]} and {described.unit}")
    return units


#: SI unit of every numeric key of the ``[mechanism.*]`` and ``[bearings.<name>]`` tables.
MECHANISM_UNITS = described_units(PISTON_SPEC, ROD_SPEC, ROTOR_SPEC, BEARING_SPEC)
