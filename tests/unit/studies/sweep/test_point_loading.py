"""Cheap case loading: cached unit strings and sweep points derived from one base case.

The cached paths must give exactly what the uncached ones give: the same values (the
cases compare equal, every field in SI), the same overrides recorded and the same
error messages, at every point.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from helpers import REFERENCE, REFRIGERANTS
from recipsim.case.load import load_case
from recipsim.errors import CaseError
from recipsim.studies.sweep.worker import point_case
from recipsim.units import _convert, to_si

POINTS = [
    ('operating_point.shaft_speed="2500 rpm"', 'operating_point.condensing_temperature="45 degC"'),
    ('operating_point.shaft_speed="4500 rpm"', "operating_point.evaporating_temperature=250.0"),
    ("solver.rtol=1e-7", 'geometry.bore="22 mm"'),
    ('refrigerant="R600a"',),
]


def test_cached_conversion_equals_a_fresh_one() -> None:
    """The second conversion of a string (from the cache) equals the first, exactly;
    the offset unit is converted with its offset (-23.3 degC = 249.85 K to 1e-12 K,
    the float rounding of the sum)."""
    _convert.cache_clear()
    first = to_si("-23.3 degC", "K", "f", "k")
    second = to_si("-23.3 degC", "K", "f", "k")
    assert first == second
    assert first == pytest.approx(273.15 - 23.3, abs=1e-12)
    assert to_si("3000 rpm", "rad/s", "f", "k") == pytest.approx(3000 * 2 * 3.141592653589793 / 60)


@pytest.mark.parametrize(
    ("value", "unit", "message"),
    [
        ("3 kg", "m", "'3 kg' has the wrong dimension: expected a quantity in m"),
        ("3 furlongz", "m", "cannot read '3 furlongz' as a quantity"),
    ],
)
def test_cached_errors_name_the_file_and_key_each_time(value: str, unit: str, message: str) -> None:
    """A bad string raises the same message twice (the second from the cache), each
    time with the file and key of the call."""
    for file, key in (("a.toml", "geometry.bore"), ("b.toml", "geometry.stroke")):
        with pytest.raises(CaseError) as info:
            to_si(value, unit, file, key)
        assert info.value.file == file and info.value.key == key
        assert info.value.message.startswith(message)


@pytest.mark.parametrize("overrides", POINTS)
def test_point_case_equals_load_case(overrides: tuple[str, ...]) -> None:
    """A point derived from the cached base case is the case ``load_case`` builds."""
    expected = load_case(REFERENCE, list(overrides))
    got = point_case(str(REFERENCE), overrides, False)
    assert got == expected
    assert got.overrides == expected.overrides == overrides
    assert got.raw == expected.raw


def test_point_case_invalid_point_has_load_case_message() -> None:
    """An invalid value gives the message of ``load_case`` (file, key, what is allowed)."""
    bad = ('operating_point.evaporating_temperature="200 degC"',)
    with pytest.raises(CaseError) as direct:
        load_case(REFERENCE, list(bad))
    with pytest.raises(CaseError) as derived:
        point_case(str(REFERENCE), bad, False)
    assert str(derived.value) == str(direct.value)


def test_point_case_reads_an_edited_base_again(tmp_path: Path) -> None:
    """A base case edited between two points is read again (modification stamp)."""
    base = tmp_path / "base.toml"
    text = REFERENCE.read_text()
    assert text.count("rtol = 1e-6") == 1
    base.write_text(text)
    first = point_case(str(base), (), True)
    base.write_text(text.replace("rtol = 1e-6", "rtol = 3e-7"))
    os.utime(base, ns=(1, 1))  # a different stamp even within the clock's resolution
    second = point_case(str(base), (), True)
    assert second.solver.rtol == 3e-7
    assert first.solver.rtol != 3e-7


def test_point_case_reads_an_edited_refrigerant_file_again(tmp_path: Path) -> None:
    """The base case is read again when its refrigerant file changes (the sections a
    point does not override are the base's: its refrigerant too)."""
    base = tmp_path / "base.toml"
    base.write_text(REFERENCE.read_text())
    fluid = tmp_path / "refrigerants" / "R134a.toml"
    fluid.parent.mkdir()
    text = (REFRIGERANTS / "R134a.toml").read_text()
    fluid.write_text(text)
    point = ('operating_point.shaft_speed="3000 rpm"',)
    first = point_case(str(base), point, True)
    assert first.refrigerant.path == str(fluid)
    fluid.write_text(text.replace('max_temperature = "180 degC"', 'max_temperature = "170 degC"'))
    os.utime(fluid, ns=(1, 1))
    second = point_case(str(base), point, True)
    assert first.refrigerant.max_temperature == pytest.approx(453.15)
    assert second.refrigerant.max_temperature == pytest.approx(443.15)
    assert second == load_case(base, list(point), allow_external_paths=True)


def test_point_case_base_invalid_alone(tmp_path: Path) -> None:
    """A base case that only the point's overrides complete still loads per point."""
    base = tmp_path / "incomplete.toml"
    text = REFERENCE.read_text()
    lines = [ln for ln in text.splitlines() if not ln.startswith("shaft_speed")]
    assert len(lines) == len(text.splitlines()) - 1
    base.write_text("\n".join(lines) + "\n")
    with pytest.raises(CaseError):
        load_case(base, allow_external_paths=True)
    point = ('operating_point.shaft_speed="3000 rpm"',)
    assert point_case(str(base), point, True) == load_case(
        base, list(point), allow_external_paths=True
    )
