"""Messages that send the user the right way: the file and key that hold the mistake,
what is allowed, and where the value came from."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from helpers import CASES, REFERENCE
from recipsim.case.load import load_case
from recipsim.errors import CaseError


def test_a_typo_in_a_valve_table_name_suggests_suction_or_discharge(tmp_path: Path) -> None:
    case = tmp_path / "typo.toml"
    case.write_text(f'extends = "{REFERENCE}"\n[valves.suctoin]\nmass = 1\n')
    with pytest.raises(CaseError, match="did you mean 'suction'") as info:
        load_case(case)
    assert info.value.key == "valves.suctoin" and "discharge" in info.value.message


def test_a_refrigerant_whose_range_is_empty_is_blamed_on_its_own_file(
    tmp_path: Path, monkeypatch
) -> None:
    text = (CASES.parent / "refrigerants" / "R134a.toml").read_text()
    text = re.sub(r'min_temperature = "[^"]*"', 'min_temperature = "80 degC"', text)
    text = re.sub(r'max_temperature = "[^"]*"', 'max_temperature = "20 degC"', text)
    (tmp_path / "refrigerants").mkdir()
    (tmp_path / "refrigerants" / "R134a.toml").write_text(text)
    monkeypatch.chdir(tmp_path)
    with pytest.raises(CaseError, match="temperature range is empty") as info:
        load_case(REFERENCE)
    assert info.value.file.endswith("refrigerants/R134a.toml") and info.value.key == "limits"


@pytest.mark.parametrize(
    ("value", "words"),
    [
        ("2**2**2**2**2 mm", "too large for a float"),
        ("nan", "not a finite number"),
        ("3 kg", "wrong dimension"),
    ],
)
def test_an_override_is_named_as_the_source_of_its_value(value: str, words: str) -> None:
    with pytest.raises(CaseError, match=words) as info:
        load_case(REFERENCE, {"geometry.bore": value})
    assert info.value.file.startswith("override geometry.bore=")
    with pytest.raises(CaseError, match=words) as info:
        load_case(REFERENCE).with_({"geometry.bore": value})
    assert info.value.file.startswith("override geometry.bore=")


@pytest.mark.parametrize(
    ("key", "value", "words"),
    [
        (
            "operating_point.shaft_speed",
            "30000 rpm",
            "30000 rpm (3141.59 rad/s) is out of range; allowed (0, 2000] rad/s, that is "
            "(0, 19099] rpm",
        ),
        (
            "operating_point.evaporating_temperature",
            "-300 degC",
            "allowed [50, 700] K, that is [-223.15, 426.85] degC",
        ),
        ("geometry.bore", 0.9, "0.9 is out of range; allowed [0.001, 0.5] m"),
    ],
)
def test_a_value_out_of_range_is_given_back_in_the_unit_it_was_written_in(key, value, words):
    with pytest.raises(CaseError) as info:
        load_case(REFERENCE).with_({key: value})
    assert words in info.value.message
