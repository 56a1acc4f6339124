"""The report's ``case.toml`` is the case fully resolved and re-runs to the same result.

Re-running a report's ``case.toml`` must reproduce its ``summary.csv`` to the printed
precision. pandas prints every float with ``repr`` (17 significant digits), and the
resolved file writes every input with ``repr`` too, so the two runs see the same floats
and the deterministic solver gives the same summary to the last bit: the comparison is
exact, except the measured wall time.
"""

from __future__ import annotations

import math
import shutil
import tomllib
from pathlib import Path

import pandas as pd

from helpers import CASES, REFERENCE
from recipsim.case.load import load_case
from recipsim.cli.main import main

QUIET = ["--no-plots", "--quiet"]
MEASURED = {"wall_time [s]"}


def _run(case: Path, out: Path, overrides: list[str] = ()) -> Path:
    sets = [a for text in overrides for a in ("--set", text)]
    assert main(["run", str(case), "--out", str(out), *QUIET, *sets]) == 0
    (report,) = out.iterdir()
    return report


def _assert_same_summary(first: Path, second: Path) -> None:
    a = pd.read_csv(first / "summary.csv").iloc[0]
    b = pd.read_csv(second / "summary.csv").iloc[0]
    assert list(a.index) == list(b.index)
    for column in a.index:
        if column in MEASURED:
            continue
        x, y = a[column], b[column]
        same = x == y or (isinstance(x, float) and math.isnan(x) and math.isnan(y))
        assert same, (column, x, y)


def test_default_case_reruns_to_the_same_summary(tmp_path):
    report = _run(REFERENCE, tmp_path / "first")
    text = (report / "case.toml").read_text()
    data = tomllib.loads(text)
    assert "extends" not in data and "rating_point" not in data["operating_point"]
    assert data["geometry"]["bore"] == "0.022 m"  # SI, unit written
    assert data["operating_point"]["evaporating_temperature"].endswith(" K")
    assert (report / "refrigerants" / "R134a.toml").is_file()
    again = _run(report / "case.toml", tmp_path / "second")
    assert again.name == report.name
    _assert_same_summary(report, again)


def test_overridden_case_reruns_to_the_same_summary(tmp_path):
    """Overrides of a unit value, of a value given another way (a clearance ratio, written
    back as a volume) and of the rating point are in the resolved file."""
    sets = [
        'operating_point.shaft_speed="3000 rpm"',
        'operating_point.rating_point="ashrae_mbp"',
        "geometry.clearance_ratio=0.03",
        "options.valves=quasi_static",
    ]
    report = _run(REFERENCE, tmp_path / "first", sets)
    text = (report / "case.toml").read_text()
    assert all(f"# --set {s}" in text for s in sets)
    data = tomllib.loads(text)
    assert data["options"]["valves"] == "quasi_static"
    assert "clearance_volume" in data["geometry"] and "clearance_ratio" not in data["geometry"]
    resolved = load_case(report / "case.toml")
    original = load_case(REFERENCE, sets)
    assert resolved.operating_point == original.operating_point
    assert resolved.geometry == original.geometry and resolved.mechanism == original.mechanism
    assert resolved.valves == original.valves and resolved.solver == original.solver
    again = _run(report / "case.toml", tmp_path / "second")
    _assert_same_summary(report, again)


def test_report_reruns_without_the_original_files(tmp_path):
    """A case of the user's (its own refrigerant file, a base case and a pressure curve
    beside it) re-runs from its report after the inputs are gone."""
    inputs = tmp_path / "inputs"
    (inputs / "refrigerants").mkdir(parents=True)
    r134a = (CASES.parent / "refrigerants" / "R134a.toml").read_text()
    (inputs / "refrigerants" / "MyR134a.toml").write_text(
        r134a.replace('\nname = "R134a"', '\nname = "MyR134a"')
    )
    shutil.copy(CASES / "paper_tabulated_pressure.csv", inputs / "curve.csv")
    (inputs / "base.toml").write_text('extends = "paper_tabulated"\nrefrigerant = "MyR134a"\n')
    (inputs / "mine.toml").write_text(
        'extends = "base.toml"\nname = "mine"\n[pressure_curve]\nfile = "curve.csv"\n'
    )
    pinned = ['options.mechanics="pinned"', 'options.drive="constant_speed"']
    report = _run(inputs / "mine.toml", tmp_path / "first", pinned)
    shutil.rmtree(inputs)
    assert (report / "curve.csv").is_file() and (report / "refrigerants" / "MyR134a.toml").is_file()
    again = _run(report / "case.toml", tmp_path / "second")
    _assert_same_summary(report, again)
    cycle = [pd.read_csv(r / "cycle.csv") for r in (report, again)]
    pd.testing.assert_frame_equal(*cycle)
