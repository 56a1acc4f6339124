"""The public API: load a shipped case by name, change it, simulate, plot, write; the
same numbers as the command line, the same validation as the file."""

from __future__ import annotations

import dataclasses

import pandas as pd
import pytest
from matplotlib.figure import Figure

import recipsim
from helpers import REFERENCE
from recipsim.cli import main

FAST = {"solver.max_revolutions": 3, "solver.min_revolutions": 1, "solver.cycle_tolerance": 0.05}


def test_round_trip_by_name_equals_the_command_line(tmp_path, capsys):
    case = recipsim.load_case(
        "reference_r134a_lbp_ideal", {"operating_point.shaft_speed": "3000 rpm"}
    )
    case = case.with_(FAST)
    assert case.path == str(REFERENCE)
    assert case.operating_point.shaft_speed == pytest.approx(3000 * 2 * 3.141592653589793 / 60)
    result = recipsim.simulate(case)
    assert isinstance(result.summary, pd.Series) and result.converged
    cop = result.summary["COP [-]"]
    assert 1.0 < cop < 5.0
    fig = Figure()
    ax = fig.add_subplot()
    assert result.plot_pv(ax=ax) is ax and ax.lines
    assert result.plot_pressure().figure is not fig
    report = result.write(tmp_path / "api" / "reference")
    assert (report / "summary.csv").is_file()
    sets = ['operating_point.shaft_speed="3000 rpm"'] + [f"{k}={v}" for k, v in FAST.items()]
    argv = ["run", str(REFERENCE), "--out", str(tmp_path / "cli"), "--no-plots", "--quiet"]
    assert main([*argv, *[a for s in sets for a in ("--set", s)]]) == 0
    (written,) = (tmp_path / "cli").iterdir()  # reference_r134a_lbp_ideal+<digest of the --set>
    assert written.name.startswith("reference_r134a_lbp_ideal+")
    cli = pd.read_csv(written / "summary.csv")
    api = pd.read_csv(report / "summary.csv")
    for column in ("COP [-]", "cooling_capacity [W]", "shaft_power [W]", "revolutions [-]"):
        assert api[column].iloc[0] == cli[column].iloc[0], column
    header = [line for line in (report / "case.toml").read_text().splitlines() if line[:1] == "#"]
    assert any("--set" in line and "shaft_speed" in line for line in header)


def test_with_validates_like_the_file_and_keeps_cases_immutable():
    case = recipsim.load_case("reference_r134a_lbp_ideal")
    with pytest.raises(recipsim.CaseError) as api:
        case.with_(solver__rtol=-1)
    with pytest.raises(recipsim.CaseError) as cli:
        recipsim.load_case(REFERENCE, ["solver.rtol=-1"])
    assert api.value.key == cli.value.key == "solver.rtol"
    assert api.value.message == cli.value.message
    slower = case.with_({"operating_point.shaft_speed": "2000 rpm"})
    assert slower.operating_point.shaft_speed < case.operating_point.shaft_speed
    assert case.overrides == () and slower.overrides == ('operating_point.shaft_speed="2000 rpm"',)
    with pytest.raises(dataclasses.FrozenInstanceError):
        case.name = "x"  # type: ignore[misc]
    with pytest.raises(recipsim.CaseError, match="not allowed"):
        case.with_({"geometry.bore": [1, 2]})


def test_an_unknown_name_is_a_clear_error():
    with pytest.raises(recipsim.CaseError, match="no such case file"):
        recipsim.load_case("no_such_case")


def test_a_shipped_name_wins_over_a_local_folder_of_that_name(tmp_path, monkeypatch):
    """Running from a folder that holds a report directory named like the case."""
    (tmp_path / "reference_r134a_lbp_ideal").mkdir()
    monkeypatch.chdir(tmp_path)
    assert recipsim.load_case("reference_r134a_lbp_ideal").path == str(REFERENCE)
    local = tmp_path / "mine.toml"
    local.write_text('extends = "reference_r134a_lbp_ideal"\nname = "mine"\n')
    assert recipsim.load_case("mine.toml").name == "mine"  # a local file is itself


def test_sweep_and_compare_through_the_api_match_the_engine(tmp_path):
    """``recipsim.sweep`` runs the sweep engine on a grid built in Python (resumable in a
    directory); ``recipsim.compare`` gives the comparison table of two results."""
    case = recipsim.load_case("reference_r134a_lbp_ideal", FAST)
    axes = {"operating_point.evaporating_temperature": ["-30 degC", "-20 degC"]}
    table = recipsim.sweep(case, axes, directory=tmp_path)
    assert list(table["status"]) == ["ok", "ok"]
    capacity = table["cooling_capacity [W]"].to_numpy()
    assert capacity[1] > capacity[0]  # capacity rises with evaporating temperature
    assert (tmp_path / "reference_r134a_lbp_ideal_sweep" / "summary.csv").is_file()
    again = recipsim.sweep(case, axes, directory=tmp_path)  # resumed: nothing recomputed
    pd.testing.assert_frame_equal(table, again)
    single = recipsim.simulate(case.with_({"operating_point.evaporating_temperature": "-20 degC"}))
    assert single.summary["cooling_capacity [W]"] == pytest.approx(capacity[1], rel=1e-12)
    cmp = recipsim.compare(case, case.with_({"operating_point.shaft_speed": "3000 rpm"}))
    row = cmp.set_index("quantity").loc["cooling_capacity [W]"]
    assert row["difference"] < 0  # slower, less capacity
    with pytest.raises(recipsim.CaseError, match="unknown key"):
        recipsim.sweep(case, {"geometry.bore_typo": [1, 2]})
