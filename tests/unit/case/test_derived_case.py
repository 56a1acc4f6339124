"""A case derived by overrides (:meth:`Case.with_`) validates only the steps the overrides
reach (:func:`recipsim.case.build.derived_sections`); it must be the case that validating
the whole file with the same overrides gives (:func:`load_case`).

Checked over the shipped cases and many override combinations: every section's keys,
valid and invalid values, random values of numeric keys, and keys whose checks cross
sections (options against the valves, the motor or the shell; the operating point
against the refrigerant; geometry against the valves and the mechanism). For each: the
same case (dataclass ``==``, raw data, overrides, path) or the same error (type and
message); and the derived steps themselves accept exactly what the whole validation
accepts, so that ``with_`` never needs its fall-back to the whole case for a valid point.
"""

from __future__ import annotations

import dataclasses
import math
import os
from functools import cache
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from recipsim.case.build import STEPS, case_sections, derived_sections
from recipsim.case.case import Case
from recipsim.case.case_schema import TOP_KEYS
from recipsim.case.load import load_case
from recipsim.case.overrides import apply_overrides, override_tables

SHIPPED = (
    "reference_r134a_lbp",
    "reference_r134a_lbp_coupled",
    "reference_r134a_lbp_lubricated",
    "paper_tabulated",
    "tles5.7kk3_r600a",
    "r290_lbp",
    "r744_transcritical",
)

#: override texts by section: valid values, invalid ones, and values whose checks cross
#: sections (a port wider than a bore, a shell pressure with the shell's network...)
POOL: dict[str, tuple[str, ...]] = {
    "header": (
        'name="other_name"',
        'description="changed"',
        'name="a/b"',
        'refrigerant="R600a"',
        'refrigerant="R290"',
        'refrigerant="R744"',
        'refrigerant="nope"',
        "refrigerant=3",
    ),
    "operating_point": (
        'operating_point.evaporating_temperature="-25 degC"',
        'operating_point.evaporating_temperature="-10 degC"',
        'operating_point.evaporating_temperature="200 degC"',
        "operating_point.evaporating_temperature=250.0",
        'operating_point.condensing_temperature="45 degC"',
        'operating_point.condensing_temperature="-40 degC"',
        'operating_point.condensing_temperature="150 degC"',
        'operating_point.shaft_speed="2500 rpm"',
        'operating_point.shaft_speed="4500 rpm"',
        'operating_point.shaft_speed="3100 rpm"',
        'operating_point.shaft_speed="-1 rpm"',
        'operating_point.shaft_speed="3 kg"',
        'operating_point.suction_temperature="32 degC"',
        'operating_point.suction_temperature="-45 degC"',
        'operating_point.liquid_temperature="30 degC"',
        'operating_point.shell_pressure="2 bar"',
        'operating_point.suction_pressure="1 bar"',
        'operating_point.discharge_pressure="90 bar"',
        'operating_point.rating_point="ashrae_mbp"',
        'operating_point.rating_point="nope"',
        'operating_point.standard="EN12900"',
        'operating_point.ambient_temperature="40 degC"',
        "operating_point.bogus=1",
        "operating_point=3",
    ),
    "options": (
        'options.properties="heos"',
        'options.properties="table"',
        'options.valves="ideal"',
        'options.valves="quasi_static"',
        'options.valves="bogus"',
        'options.heat_transfer="annand"',
        'options.leakage="piston_gap"',
        'options.mechanics="flexible"',
        'options.mechanics="pinned"',
        'options.drive="induction_motor"',
        'options.drive="constant_speed"',
        'options.motor="equivalent_circuit"',
        'options.thermal="network"',
        'options.thermal="fixed_wall"',
        'options.bearing_law="short_journal"',
        'options.friction="mean"',
        'options.friction="films"',
        'options.pressure="tabulated"',
        'options.speed="motor_slip"',
    ),
    "geometry": (
        'geometry.bore="24 mm"',
        'geometry.bore="5 mm"',
        'geometry.stroke="20 mm"',
        'geometry.connecting_rod_length="5 mm"',
        'geometry.liner_length="60 mm"',
        'geometry.liner_length="5 mm"',
        'geometry.clearance_volume="0.1 cm^3"',
        "geometry.clearance_ratio=0.03",
    ),
    "valves": (
        'valves.suction.port_diameter="6.5 mm"',
        'valves.suction.port_diameter="30 mm"',
        'valves.discharge.reed_width="3 mm"',
        'valves.discharge.preload="2 N"',
        'valves.suction.port_position="30 mm"',
        'valves.flow_model="bogus"',
        'valves.stick_velocity="0.02 m/s"',
    ),
    "others": (
        'leakage.radial_clearance="8 um"',
        'leakage.model="incompressible"',
        'heat_transfer.wall_temperature="60 degC"',
        'heat_transfer.coefficient="-1 W/m^2/K"',
        "solver.rtol=1e-7",
        'solver.start="rest"',
        "solver.min_revolutions=1000",
        "solver.max_revolutions=5",
        'solver.envelope="ignore"',
        'solver.periodic="shooting"',
        'thermal.ua_shell_ambient="5 W/K"',
        "thermal.bogus=1",
        'pressure_curve.file="paper_tabulated_pressure.csv"',
        'pressure_curve.file="missing.csv"',
        "bogus_table=1",
    ),
    "mechanism": (
        'mechanism.piston.length="24 mm"',
        'mechanism.piston.length="2 mm"',
        'mechanism.piston.mass="40 g"',
        'mechanism.rotor.secondary_z="-20 mm"',
        'mechanism.rotor.counterweight_mass="50 g"',
        'bearings.primary.law="short_journal"',
        'bearings.piston_top.position_from_crown="5 mm"',
        'bearings.piston_skirt.law="skirt_film"',
        'oil.film_temperature="50 degC"',
        'oil.name="bogus"',
    ),
    "motor": (
        'motor.rated_speed="2850 rpm"',
        "motor.poles=4",
        "motor.poles=3",
        'motor.breakdown_torque="0.1 N*m"',
        "motor.bogus=1",
    ),
}
ALL_TEXTS = tuple(text for texts in POOL.values() for text in texts)

#: a typical sweep point (one to three keys of the operating point), and points whose
#: keys reach across sections
TABLE: tuple[tuple[str, ...], ...] = (
    (
        'operating_point.condensing_temperature="55 degC"',
        'operating_point.shaft_speed="3500 rpm"',
        'operating_point.evaporating_temperature="-25 degC"',
    ),
    ('operating_point.shaft_speed="3600 rpm"', 'options.motor="equivalent_circuit"'),
    ('operating_point.shaft_speed="3000 rpm"', 'options.speed="motor_slip"'),
    ('operating_point.shell_pressure="2 bar"', 'options.thermal="network"'),
    ('operating_point.evaporating_temperature="-25 degC"', 'refrigerant="R600a"'),
    ('operating_point.evaporating_temperature="-25 degC"', 'options.properties="heos"'),
    ('geometry.bore="5 mm"', 'options.valves="ideal"'),
    ('geometry.liner_length="30 mm"', 'mechanism.piston.length="24 mm"'),
    ('mechanism.piston.length="2 mm"', 'bearings.piston_top.position_from_crown="1 mm"'),
    ('options.mechanics="flexible"', 'bearings.primary.law="short_journal"'),
    ('options.mechanics="flexible"', 'options.bearing_law="short_journal"'),
    ('options.mechanics="flexible"', 'options.friction="films"'),
    ('solver.start="rest"', 'options.drive="induction_motor"'),
    ('solver.start="rest"', 'options.mechanics="flexible"', 'options.drive="induction_motor"'),
    ('options.heat_transfer="annand"', 'options.thermal="network"'),
    ('options.pressure="tabulated"', 'pressure_curve.file="paper_tabulated_pressure.csv"'),
    ("solver.min_revolutions=3", "solver.max_revolutions=5"),
    ('operating_point.shaft_speed="2500 rpm"', 'operating_point.shaft_speed="4500 rpm"'),
    ('operating_point.shaft_speed="3000 rpm"', 'operating_point.shaft_speed="-1 rpm"'),
)


@cache
def _base(name: str) -> Case:
    return load_case(name)


def _same(a: Any, b: Any) -> bool:
    """Dataclass ``==``, field by field, with arrays compared by value (a tabulated
    pressure curve's ``==`` cannot compare two arrays), nan equal to nan and the types
    equal too (``1 == 1.0`` is not enough)."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return type(a) is type(b) and a.dtype == b.dtype and np.array_equal(a, b)
    if dataclasses.is_dataclass(a) and not isinstance(a, type):
        return type(a) is type(b) and all(
            _same(getattr(a, f.name), getattr(b, f.name))
            for f in dataclasses.fields(a)
            if f.compare
        )
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    if isinstance(a, (tuple, list)) and isinstance(b, (tuple, list)):
        return type(a) is type(b) and len(a) == len(b) and all(map(_same, a, b))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    return type(a) is type(b) and bool(a == b)


def _outcome(make: Any) -> tuple[str, Any]:
    try:
        return "case", make()
    except Exception as exc:  # the type and message are what is compared
        return type(exc).__name__, str(exc)


def _check(name: str, texts: tuple[str, ...]) -> None:
    """``with_`` gives what ``load_case`` gives; the derived steps accept the same."""
    base = _base(name)
    whole = _outcome(lambda: load_case(name, list(texts)))
    derived = _outcome(lambda: base.with_(list(texts)))
    assert derived[0] == whole[0], (texts, whole, derived)
    if whole[0] != "case":
        assert derived[1] == whole[1]
    else:
        got, expected = derived[1], whole[1]
        assert _same(got, expected)
        assert got.raw == expected.raw
        assert got.overrides == expected.overrides == texts
        assert (got.path, got.source_text, got.allow_external_paths) == (
            expected.path,
            expected.source_text,
            expected.allow_external_paths,
        )

    # the steps alone: accepted exactly where the whole case is (no silent fall-back)
    def steps_alone() -> dict[str, Any]:
        raw = apply_overrides(base.raw, list(texts), base.path)
        return derived_sections(vars(base), raw, override_tables(list(texts)))

    steps = _outcome(steps_alone)
    assert (steps[0] == "case") == (whole[0] == "case"), (texts, whole, steps)


@pytest.mark.parametrize("name", SHIPPED)
@pytest.mark.parametrize("texts", TABLE, ids=lambda texts: "+".join(texts)[:60])
def test_table_of_points(name: str, texts: tuple[str, ...]) -> None:
    _check(name, texts)


@pytest.mark.parametrize("name", SHIPPED)
def test_every_single_override(name: str) -> None:
    """Each text of the pool alone on each shipped case."""
    for text in ALL_TEXTS:
        _check(name, (text,))


#: numeric keys of several sections, their unit and a range wider than the allowed one
#: (not the motor's: each new rated point fits the equivalent circuit again, seconds)
NUMBERS: dict[str, tuple[str, float, float]] = {
    "operating_point.evaporating_temperature": ("degC", -90.0, 120.0),
    "operating_point.condensing_temperature": ("degC", -40.0, 140.0),
    "operating_point.suction_temperature": ("degC", -60.0, 80.0),
    "operating_point.shaft_speed": ("rpm", -100.0, 12000.0),
    "operating_point.shell_pressure": ("bar", -1.0, 200.0),
    "geometry.bore": ("mm", 0.5, 40.0),
    "geometry.liner_length": ("mm", 1.0, 80.0),
    "valves.suction.port_diameter": ("mm", 0.5, 30.0),
    "mechanism.piston.length": ("mm", 1.0, 40.0),
    "bearings.piston_top.position_from_crown": ("mm", -1.0, 30.0),
}
#: the project's fuzz settings (tests/unit/cli/test_hardening.py): the same draws on every
#: run unless RECIPSIM_FUZZ_RANDOM is set
FUZZ = settings(
    max_examples=300,
    deadline=None,
    derandomize=os.environ.get("RECIPSIM_FUZZ_RANDOM") is None,
    suppress_health_check=[HealthCheck.too_slow],
)


@FUZZ
@given(
    name=st.sampled_from(SHIPPED),
    texts=st.lists(st.sampled_from(ALL_TEXTS), min_size=1, max_size=4),
)
def test_random_combinations(name: str, texts: list[str]) -> None:
    """One to four overrides from any sections, in any order, repeats included."""
    _check(name, tuple(texts))


@st.composite
def _number_override(draw: st.DrawFn) -> str:
    key = draw(st.sampled_from(sorted(NUMBERS)))
    unit, lo, hi = NUMBERS[key]
    value = draw(st.floats(lo, hi, allow_nan=False))
    return f'{key}="{value:.5g} {unit}"'


@FUZZ
@given(
    name=st.sampled_from(SHIPPED),
    numbers=st.lists(_number_override(), min_size=1, max_size=3),
    text=st.one_of(st.none(), st.sampled_from(ALL_TEXTS)),
)
def test_random_values(name: str, numbers: list[str], text: str | None) -> None:
    """Random values of numeric keys across sections (near and across the bounds their
    checks put on each other), with or without one text of the pool."""
    _check(name, tuple(numbers) + (() if text is None else (text,)))


def test_with_of_a_derived_case() -> None:
    """A point derived from a derived case is the case with both sets of overrides."""
    first = ('options.valves="quasi_static"',)
    second = ('operating_point.shaft_speed="2500 rpm"', 'geometry.bore="24 mm"')
    got = _base("reference_r134a_lbp").with_(list(first)).with_(list(second))
    expected = load_case("reference_r134a_lbp", list(first + second))
    assert _same(got, expected) and got == expected
    assert got.overrides == first + second


def test_a_sweep_point_rebuilds_only_the_operating_point() -> None:
    """A point of the operating point changes the operating point alone: the other
    sections are the base's own objects."""
    base = _base("reference_r134a_lbp")
    point = base.with_(['operating_point.evaporating_temperature="-25 degC"'])
    assert point.operating_point.evaporating_temperature == pytest.approx(248.15)
    assert point.operating_point != base.operating_point
    for field in ("refrigerant", "options", "geometry", "valves", "mechanism", "thermal"):
        assert getattr(point, field) is getattr(base, field)


def test_the_steps_read_every_top_level_table() -> None:
    """Every table a case may hold is read by some step (else an override of it would
    change nothing), and every step uses only steps before it."""
    assert set().union(*(step.reads for step in STEPS)) == TOP_KEYS
    seen: set[str] = set()
    for step in STEPS:
        assert set(step.uses) <= seen, step.name
        seen.add(step.name)


def test_the_whole_validation_is_unchanged_by_the_steps() -> None:
    """``case_sections`` (every step) builds what the shipped case holds."""
    base = _base("tles5.7kk3_r600a")
    sections = case_sections(base.raw, base.path)
    assert _same(Case(**sections, raw=base.raw), base)
