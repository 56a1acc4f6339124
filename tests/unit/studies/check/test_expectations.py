"""The hard cases' expectations file is read through the shared schema
(:data:`recipsim.studies.check.expectations.EXPECTATION_SPEC`): a bad file is refused
naming the file, the key and what is allowed, as a case file is."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from helpers import CASES
from recipsim.errors import CaseError
from recipsim.schema import Field, TextList, read_table
from recipsim.studies.check.expectations import (
    EXPECTATION_SPEC,
    FAST_OVERRIDES,
    MASS_TOLERANCE,
    MINIMUM_SPEC,
    load_expectations,
)
from recipsim.studies.check.metrics import METRICS


def _expectations(tmp_path: Path, text: str) -> Path:
    (tmp_path / "a.toml").write_text("")
    path = tmp_path / "expectations.toml"
    path.write_text(text)
    return path


def test_every_bounded_metric_is_declared():
    assert tuple(MINIMUM_SPEC) == METRICS


def test_shipped_hard_expectations_load():
    default, cases = load_expectations(CASES / "hard" / "expectations.toml")
    assert default.expected == "converged" and default.mass_tolerance == MASS_TOLERANCE
    assert cases and all(e.fast[: len(FAST_OVERRIDES)] == FAST_OVERRIDES for e in cases.values())


def test_a_case_table_keeps_what_it_leaves_out_from_the_defaults(tmp_path):
    path = _expectations(
        tmp_path,
        '[defaults]\nmass_tolerance = 2e-3\nfast = ["solver.rtol=1e-6"]\n'
        '[cases.a]\nreason = "why"\nminimum = { suction_reed_openings = 2 }\n'
        'fast = ["solver.max_step=\\"1 deg\\""]\n',
    )
    default, cases = load_expectations(path)
    a = cases["a"]
    assert a.mass_tolerance == 2e-3 and a.reason == "why" and a.expected == "converged"
    assert a.minimum == {"suction_reed_openings": 2.0}
    assert a.fast == FAST_OVERRIDES + ("solver.rtol=1e-6", 'solver.max_step="1 deg"')
    assert default.minimum == {} and default.reason == ""


@pytest.mark.parametrize(
    ("body", "key", "allowed"),
    [
        ('[cases.a]\nexpected = "passed"\n', "cases.a.expected", "converged"),
        ("[cases.a]\nmass_tolerance = -1e-3\n", "cases.a.mass_tolerance", "(0, inf]"),
        ("[cases.a]\nenergy_tolerance = nan\n", "cases.a.energy_tolerance", "(0, inf]"),
        ('[cases.a]\ndrive_tolerance = "tight"\n', "cases.a.drive_tolerance", ""),
        ("[cases.a]\ndrive_tolerance = true\n", "cases.a.drive_tolerance", "dimensionless"),
        ('[cases.a]\nfast = "solver.rtol=1e-6"\n', "cases.a.fast", "list of strings"),
        ("[cases.a]\nfast = [1]\n", "cases.a.fast", "list of strings"),
        ("[cases.a]\nmessage = 3\n", "cases.a.message", "string"),
        ('[cases.a]\nmessage = "("\n', "cases.a.message", "regular expression"),
        ("[cases.a]\nminimum = 2\n", "cases.a.minimum", "suction_reed_openings"),
        ("[cases.a]\nminimum = { openings = 2 }\n", "cases.a.minimum.openings", "allowed"),
        (
            '[cases.a]\nminimum = { suction_reed_openings = "many" }\n',
            "cases.a.minimum.suction_reed_openings",
            "",
        ),
        (
            "[cases.a]\nminimum = { volumetric_efficiency = -0.5 }\n",
            "cases.a.minimum.volumetric_efficiency",
            "[0, 2]",
        ),
        ("[defaults]\nmass_tol = 1e-3\n", "defaults.mass_tol", "did you mean 'mass_tolerance'"),
        ("[cases.b]\n", "cases.b", "no case file b.toml"),
        ("[elsewhere]\n", "elsewhere", "allowed: cases, defaults"),
    ],
)
def test_a_bad_expectations_file_names_file_key_and_what_is_allowed(tmp_path, body, key, allowed):
    path = _expectations(tmp_path, body)
    with pytest.raises(CaseError) as err:
        load_expectations(path)
    text = str(err.value)
    assert str(path) in text
    assert re.search(rf"\b{re.escape(key)}\b", text), text
    assert allowed in text


def test_text_lists_and_ranges_are_read_by_the_shared_schema():
    spec = {"fast": TextList(()), "x": Field("dimensionless", 1.0, lo=0.0, open_lo=True)}
    assert read_table({"fast": ["a", "b"]}, spec, "f.toml", "t") == {"fast": ("a", "b"), "x": 1.0}
    with pytest.raises(CaseError, match=r"f\.toml: t\.fast: expected a list of strings"):
        read_table({"fast": ["a", 2]}, spec, "f.toml", "t")
    assert isinstance(EXPECTATION_SPEC["fast"], TextList)
    assert all(
        isinstance(EXPECTATION_SPEC[k], Field) and not math.isfinite(EXPECTATION_SPEC[k].hi)
        for k in ("mass_tolerance", "energy_tolerance", "drive_tolerance")
    )
