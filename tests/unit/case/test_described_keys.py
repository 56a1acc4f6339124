"""The ``Described`` declarations of the tables validated in code are what the loaders
use: the keys they accept, the units they convert to, the range words of their messages,
and the defaults they apply (issue 14: the case-file reference is generated from them)."""

from __future__ import annotations

import pytest

from recipsim.case import mechanism
from recipsim.case.load import load_case
from recipsim.case.lubrication import FILM_KEYS, FILM_SPEC, OIL_SPEC, parse_oil
from recipsim.case.mechanism_schema import BEARING_SPEC, PISTON_SPEC, ROD_SPEC, ROTOR_SPEC
from recipsim.errors import CaseError
from recipsim.units import to_si


def test_declared_keys_are_the_accepted_keys() -> None:
    assert mechanism._PISTON_KEYS == tuple(PISTON_SPEC)
    assert mechanism._ROD_KEYS == tuple(ROD_SPEC)
    assert mechanism._ROTOR_KEYS == tuple(ROTOR_SPEC)
    accepted = {*mechanism._BEARING_KEYS, *mechanism.PISTON_BEARING_KEYS}
    assert accepted == set(BEARING_SPEC)
    assert FILM_KEYS == tuple(FILM_SPEC)
    with pytest.raises(CaseError, match="unknown key"):
        parse_oil({"viscosity_index": 100}, "f.toml")
    for spec in (PISTON_SPEC, ROD_SPEC, ROTOR_SPEC, BEARING_SPEC, OIL_SPEC):
        for key, field in spec.items():
            assert field.allowed and field.doc, key
            assert field.requirement() in ("yes", "no") or field.required, key


@pytest.mark.parametrize(
    ("override", "spec", "key"),
    [
        ('mechanism.piston.pin_offset_from_crown="30 mm"', PISTON_SPEC, "pin_offset_from_crown"),
        (
            "mechanism.connecting_rod.centre_of_mass_fraction=1.5",
            ROD_SPEC,
            "centre_of_mass_fraction",
        ),
        ('mechanism.rotor.secondary_z="-20 mm"', ROTOR_SPEC, "secondary_z"),
        ('bearings.primary.radial_clearance="1 mm"', FILM_SPEC, "radial_clearance"),
        ('bearings.eccentric.length="100 mm"', FILM_SPEC, "length"),
        ("bearings.pin.damping=-1", BEARING_SPEC, "damping"),
        ('oil.film_temperature="600 K"', OIL_SPEC, "film_temperature"),
    ],
)
def test_messages_say_the_declared_range(override: str, spec: dict, key: str) -> None:
    """An out-of-range value is refused with the declaration's own words."""
    with pytest.raises(CaseError) as info:
        load_case("reference_r134a_lbp_lubricated", [override])
    assert key in str(info.value) and spec[key].allowed in str(info.value)


def test_declared_defaults_are_the_applied_ones() -> None:
    """The defaults in words are the values the loader applies (the contact law's, the
    oil's film temperature, no counterweight)."""
    from recipsim.physics.mechanics.journal import (
        DEFAULT_CONTACT_FILM,
        DEFAULT_CONTACT_STIFFNESS,
        DEFAULT_FRICTION_COEFFICIENT,
    )

    case = load_case("reference_r134a_lbp_lubricated")
    film = case.mechanism.bearing("primary").film
    assert film is not None
    assert to_si(FILM_SPEC["contact_film"].default, "m", "", "") == film.contact_film
    assert film.contact_film == DEFAULT_CONTACT_FILM
    stiffness = to_si(FILM_SPEC["contact_stiffness"].default, "N/m", "", "")
    assert stiffness == film.contact_stiffness == DEFAULT_CONTACT_STIFFNESS
    assert float(FILM_SPEC["contact_friction"].default) == DEFAULT_FRICTION_COEFFICIENT
    oil = parse_oil(None, "f.toml")
    assert to_si(OIL_SPEC["film_temperature"].default, "K", "", "") == pytest.approx(
        oil.film_temperature, abs=1e-9
    )
    assert ROTOR_SPEC["counterweight_mass"].default.startswith("0 ")
    assert load_case("reference_r134a_lbp").mechanism.rotor.counterweight_mass == 0.0


def _specs() -> list[tuple[str, dict]]:
    return [
        ("mechanism.piston", PISTON_SPEC),
        ("mechanism.connecting_rod", ROD_SPEC),
        ("mechanism.rotor", ROTOR_SPEC),
        ("bearings", BEARING_SPEC),
        ("oil", OIL_SPEC),
    ]


def test_declared_numeric_ranges_agree_with_their_words() -> None:
    """A range held in numbers (checked from the declaration) says the same in words:
    an open bound reads '<' or '> ', a closed one '...' or '>='."""
    bounded = 0
    for table, spec in _specs():
        for key, field in spec.items():
            if not field.bounded:
                continue
            bounded += 1
            words = field.allowed
            if field.lo > -float("inf"):
                closed = "..." in words or ">=" in words
                assert closed != field.open_lo, (table, key, words)
            if field.hi < float("inf"):
                closed = "..." in words
                assert closed != field.open_hi, (table, key, words)
    assert bounded >= 15


@pytest.mark.parametrize(
    ("override", "key", "refused"),
    [
        ('bearings.primary.diameter="1 mm"', "bearings.primary.diameter", True),
        ('bearings.primary.film_temperature="200 K"', "bearings.primary.film_temperature", True),
        ("bearings.primary.contact_friction=1", "bearings.primary.contact_friction", False),
        ("bearings.primary.contact_friction=1.01", "bearings.primary.contact_friction", True),
        ("mechanism.rotor.counterweight_mass=0", "mechanism.rotor.counterweight_mass", False),
        ("mechanism.rotor.counterweight_mass=-1", "mechanism.rotor.counterweight_mass", True),
        ("mechanism.connecting_rod.centre_of_mass_fraction=1", "centre_of_mass_fraction", True),
        ("mechanism.piston.mass=0", "mechanism.piston.mass", True),
        ('oil.film_temperature="500 K"', "oil.film_temperature", True),
    ],
)
def test_the_declared_ranges_are_the_checked_ones(override: str, key: str, refused: bool) -> None:
    """The declaration's bounds decide, at the bound itself, and the message names the
    key with the declaration's words."""
    if not refused:
        load_case("reference_r134a_lbp_lubricated", [override])
        return
    with pytest.raises(CaseError) as info:
        load_case("reference_r134a_lbp_lubricated", [override])
    assert key in str(info.value) and "out of range; allowed:" in str(info.value)


def test_a_rule_in_code_cannot_shadow_a_declared_range() -> None:
    from recipsim.case.table_reader import TableReader

    reader = TableReader({"mass": 1.0}, "f.toml", "mechanism.piston")
    assert reader.described(PISTON_SPEC, "mass") == 1.0
    with pytest.raises(ValueError, match="declared"):
        reader.described(PISTON_SPEC, "mass", lambda v: v > 2.0)
