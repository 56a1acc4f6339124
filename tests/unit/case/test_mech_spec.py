"""Case-table parser of the mechanism: values, units and every kind of error."""

from __future__ import annotations

import copy
import math

import pytest

from recipsim.case.mechanism import mechanism_from_dict
from recipsim.case.mechanism_spec import scale_bearings, solid_cylinder_transverse_inertia
from recipsim.case.reference_mechanism import reference_mechanism_tables
from recipsim.errors import CaseError
from recipsim.physics.mechanics.layout import BEARING_NAMES

FILE = "cases/test.toml"


def tables() -> dict:
    return copy.deepcopy(reference_mechanism_tables())


def test_reference_tables_parse_to_si() -> None:
    spec = mechanism_from_dict(tables(), FILE)
    assert spec.piston.mass == pytest.approx(0.035)
    assert spec.piston.length == pytest.approx(0.020)
    assert spec.piston.pin_offset_from_crown == pytest.approx(0.010)
    assert spec.piston.transverse_inertia == pytest.approx(2.2254e-6)
    assert spec.connecting_rod.mass == pytest.approx(0.030)
    assert spec.connecting_rod.centre_of_mass_fraction == pytest.approx(0.35)
    assert spec.connecting_rod.inertia == pytest.approx(4e-6)
    assert spec.rotor.mass == pytest.approx(0.9)
    assert spec.rotor.polar_inertia == pytest.approx(3.5e-4)
    assert spec.rotor.transverse_inertia == pytest.approx(7.0e-4)
    assert spec.rotor.centre_of_mass_z == pytest.approx(-0.040)
    assert spec.rotor.primary_z == pytest.approx(-0.020)
    assert spec.rotor.secondary_z == pytest.approx(-0.052)
    k = {name: spec.bearing(name).stiffness for name in BEARING_NAMES}
    assert k == pytest.approx(
        {
            "primary": 5e7,
            "secondary": 4e7,
            "eccentric": 2.5e7,
            "pin": 5e7,
            "piston_top": 3e7,
            "piston_skirt": 3e7,
        }
    )
    # Gauss points of the 20 mm piston: 10 mm -/+ 10 mm / sqrt(3)
    top = spec.bearing("piston_top").position_from_crown
    skirt = spec.bearing("piston_skirt").position_from_crown
    assert top == pytest.approx(0.010 - 0.010 / math.sqrt(3.0), abs=1e-7)
    assert skirt == pytest.approx(0.010 + 0.010 / math.sqrt(3.0), abs=1e-7)


def test_bare_numbers_are_si_and_percent_works() -> None:
    t = tables()
    t["mechanism"]["piston"]["mass"] = 0.04
    t["mechanism"]["connecting_rod"]["centre_of_mass_fraction"] = "40 %"
    spec = mechanism_from_dict(t, FILE)
    assert spec.piston.mass == 0.04
    assert spec.connecting_rod.centre_of_mass_fraction == pytest.approx(0.40)


def test_default_piston_inertia_is_the_solid_cylinder_estimate() -> None:
    t = tables()
    del t["mechanism"]["piston"]["transverse_inertia"]
    spec = mechanism_from_dict(t, FILE, bore=0.022)
    expected = 0.035 * (3 * 0.011**2 + 0.020**2) / 12
    assert spec.piston.transverse_inertia == pytest.approx(expected, rel=1e-12)
    assert solid_cylinder_transverse_inertia(0.035, 0.022, 0.020) == pytest.approx(2.2254e-6, 1e-4)
    with pytest.raises(CaseError) as err:
        mechanism_from_dict(t, FILE)
    assert err.value.key == "mechanism.piston.transverse_inertia"


def _error(t: dict) -> CaseError:
    with pytest.raises(CaseError) as err:
        mechanism_from_dict(t, FILE)
    assert err.value.file == FILE
    return err.value


@pytest.mark.parametrize(
    ("path", "key"),
    [
        (("mechanism", "piston", "mass"), "mechanism.piston.mass"),
        (("mechanism", "connecting_rod", "inertia"), "mechanism.connecting_rod.inertia"),
        (("mechanism", "rotor", "secondary_z"), "mechanism.rotor.secondary_z"),
        (("bearings", "eccentric", "stiffness"), "bearings.eccentric.stiffness"),
        (("bearings", "piston_top", "law"), "bearings.piston_top.law"),
        (
            ("bearings", "piston_skirt", "position_from_crown"),
            "bearings.piston_skirt.position_from_crown",
        ),
        (("bearings", "secondary"), "bearings.secondary"),
        (("mechanism", "rotor"), "mechanism.rotor"),
    ],
)
def test_missing_key_names_it_and_what_is_allowed(path: tuple[str, ...], key: str) -> None:
    t = tables()
    node = t
    for p in path[:-1]:
        node = node[p]
    del node[path[-1]]
    e = _error(t)
    assert e.key == key
    assert "missing" in e.message


def test_missing_mechanism_table() -> None:
    e = _error({"bearings": tables()["bearings"]})
    assert e.key == "mechanism" and "missing" in e.message


@pytest.mark.parametrize(
    ("table", "name"),
    [(("mechanism", "rotor"), "colour"), (("bearings", "primary"), "z"), (("bearings",), "thrust")],
)
def test_unknown_key_lists_allowed(table: tuple[str, ...], name: str) -> None:
    t = tables()
    node = t
    for p in table:
        node = node[p]
    node[name] = 1.0
    e = _error(t)
    assert e.key == ".".join((*table, name))
    assert "allowed" in e.message


def test_extra_keys_can_be_allowed() -> None:
    t = tables()
    t["mechanism"]["model"] = "flexible"
    mechanism_from_dict(t, FILE, allowed_extra_keys=("model",))
    assert _error(t).key == "mechanism.model"


@pytest.mark.parametrize(
    ("path", "value", "key"),
    [
        (("mechanism", "piston", "mass"), "-35 g", "mechanism.piston.mass"),
        (("mechanism", "piston", "pin_offset_from_crown"), "25 mm", None),
        (("mechanism", "connecting_rod", "centre_of_mass_fraction"), 1.2, None),
        (("mechanism", "rotor", "polar_inertia"), 0.0, None),
        (("mechanism", "rotor", "secondary_z"), "-20 mm", None),
        (("bearings", "primary", "stiffness"), 0.0, None),
        (("bearings", "primary", "damping"), "-1 N*s/m", None),
        (("bearings", "piston_top", "position_from_crown"), "21 mm", None),
        (("bearings", "piston_top", "position_from_crown"), "15.7735 mm", None),
        (("bearings", "primary", "stiffness"), "5 kg", None),
        (("bearings", "primary", "stiffness"), "lots", None),
        (("mechanism", "piston", "mass"), float("nan"), None),
        (("mechanism", "piston", "mass"), True, None),
    ],
)
def test_out_of_range_or_wrong_unit(path: tuple[str, ...], value: object, key: str | None) -> None:
    t = tables()
    node = t
    for p in path[:-1]:
        node = node[p]
    node[path[-1]] = value
    e = _error(t)
    # the piston_top == piston_skirt position error is reported on the skirt
    assert e.key in (key or ".".join(path), "bearings.piston_skirt.position_from_crown")


def test_unknown_law_says_what_is_allowed() -> None:
    t = tables()
    t["bearings"]["primary"]["law"] = "ball_bearing"
    e = _error(t)
    assert e.key == "bearings.primary.law"
    assert "linear, short_journal, finite_journal" in e.message
    t = tables()
    t["bearings"]["pin"]["law"] = "short_journal"  # the pin stays linear
    e = _error(t)
    assert e.key == "bearings.pin.law"
    assert e.message.endswith("allowed: linear")


def test_film_law_needs_its_geometry() -> None:
    t = tables()
    t["bearings"]["primary"]["law"] = "short_journal"
    del t["bearings"]["primary"]["diameter"]
    e = _error(t)
    assert e.key == "bearings.primary.diameter"
    assert "missing" in e.message


def test_scale_bearings_keeps_damping_ratio() -> None:
    spec = mechanism_from_dict(tables(), FILE)
    stiff = scale_bearings(spec, 100.0)
    for a, b in zip(spec.bearings, stiff.bearings, strict=True):
        assert b.stiffness == pytest.approx(100.0 * a.stiffness)
        assert b.damping / math.sqrt(b.stiffness) == pytest.approx(
            a.damping / math.sqrt(a.stiffness)
        )
