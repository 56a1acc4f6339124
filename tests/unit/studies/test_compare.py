"""``recipsim compare``: the comparison table, its output directory and the command line."""

from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd
import pytest

from helpers import CASES, REFERENCE
from recipsim.atomic import MARKER
from recipsim.case.load import load_case
from recipsim.cli.compare import run_comparison
from recipsim.cli.main import main
from recipsim.pipeline import simulate_case
from recipsim.studies.compare import (
    GROUPS,
    case_labels,
    comparison_table,
    is_numeric,
    quantity_group,
    relative_difference,
)

PAPER = CASES / "paper_tabulated.toml"
FIXED = ["quantity", "group", "difference", "relative_difference [-]"]
BEARINGS = ("primary", "secondary", "eccentric", "pin", "piston_top", "piston_skirt")
OVERLAYS = {
    "overlay_pressure.png",
    "overlay_pv.png",
    "overlay_torque.png",
    "overlay_bearing_loads.png",
    "overlay_orbits.png",
}


def _coupled_twin(directory):
    """The reference case on flexible bearings, coupled to the cylinder (one state vector)."""
    path = directory / "reference_coupled.toml"
    path.write_text(
        f'extends = "{REFERENCE}"\nname = "reference_coupled"\n[options]\nmechanics = "flexible"\n'
    )
    return path


@pytest.fixture(scope="module")
def tab_vs_coupled(tmp_path_factory):
    """Tabulated-pressure flexible run (A) against the coupled flexible run (B), with plots."""
    tmp = tmp_path_factory.mktemp("compare")
    return run_comparison(PAPER, _coupled_twin(tmp), out=tmp / "out", plots=True, argv=["test"])


# --------------------------------------------------------------------------- table logic


def test_relative_difference_rules():
    """(B - A)/|A|; NaN when A is 0 or either is NaN; the sign follows B - A for A < 0."""
    a = np.array([2.0, -2.0, 0.0, 0.0, math.nan, 1.0, 4.0])
    b = np.array([3.0, -1.0, 5.0, 0.0, 1.0, math.nan, 4.0])
    rel = relative_difference(a, b)
    np.testing.assert_allclose(rel[[0, 1, 6]], [0.5, 0.5, 0.0], rtol=0, atol=0)
    assert np.isnan(rel[[2, 3, 4, 5]]).all()


def test_table_of_synthetic_rows_keeps_missing_and_text_out():
    """A quantity one row lacks (or has as NaN) stays with NaN; text and booleans go to
    cases.csv, not to the table; unknown quantities land in 'other', before 'solver'."""
    row_a = {
        "case": "a",
        "converged [-]": True,
        "shaft_power [W]": 100.0,
        "cooling_capacity [W]": math.nan,
        "revolutions [-]": 3,
        "new_thing [m]": 0.0,
        "bearing_max_pin [N]": 10.0,
        "bearing_rms_pin [N]": 5.0,
    }
    row_b = {"case": "b", "converged [-]": False, "shaft_power [W]": 90.0, "revolutions [-]": 4}
    row_b["cooling_capacity [W]"] = 200.0
    table = comparison_table(row_a, row_b, "a", "b").set_index("quantity")
    assert list(table.index) == [
        "cooling_capacity [W]",
        "shaft_power [W]",
        "bearing_rms_pin [N]",
        "bearing_max_pin [N]",
        "new_thing [m]",
        "revolutions [-]",
    ]
    assert list(table["group"]) == ["energy", "energy", "bearing", "bearing", "other", "solver"]
    assert table.loc["shaft_power [W]", "difference"] == -10.0
    assert table.loc["shaft_power [W]", "relative_difference [-]"] == pytest.approx(-0.1)
    for q in ("cooling_capacity [W]", "bearing_rms_pin [N]", "new_thing [m]"):
        assert np.isnan(table.loc[q, ["difference", "relative_difference [-]"]].astype(float)).all()
    assert case_labels("x", "x") == ("x_a", "x_b")
    assert case_labels("group", "b") == ("group_a", "b")
    with pytest.raises(ValueError):
        comparison_table(row_a, row_b, "a", "a")


def test_table_arithmetic_against_the_summary_rows(tab_vs_coupled):
    """Every numeric summary column is one row; values, B - A and (B - A)/|A| recomputed
    independently from the two summary rows (exact: same float operations, tolerance
    1e-12 relative only for the division order)."""
    row_a, row_b = (run.row for run in tab_vs_coupled.runs)
    label_a, label_b = tab_vs_coupled.labels
    assert (label_a, label_b) == ("paper_tabulated", "reference_coupled")
    table = tab_vs_coupled.table
    numeric = {k for row in (row_a, row_b) for k, v in row.items() if is_numeric(v)}
    assert sorted(table["quantity"]) == sorted(numeric)  # each once, none dropped
    assert set(row_a) - numeric == {
        "case",
        "refrigerant",
        "pressure",
        "mechanics",
        "drive",
        "valves",
        "heat_transfer",
        "leakage",
        "standard",
        "friction",
        "motor",
        "thermal",
        "converged [-]",
        "periodic_method",
        "status",
        "status_message",
    }
    order = [GROUPS.index(g) for g in table["group"]]
    assert order == sorted(order)  # operating point, gas, energy, mechanism, bearing, solver
    for rec in table.to_dict(orient="records"):
        q = rec["quantity"]
        a, b = float(row_a[q]), float(row_b[q])
        assert rec["group"] == quantity_group(q)
        np.testing.assert_equal([rec[label_a], rec[label_b]], [a, b])
        if math.isnan(a) or math.isnan(b):
            assert math.isnan(rec["difference"]) and math.isnan(rec["relative_difference [-]"])
            continue
        assert rec["difference"] == b - a
        if a == 0.0:
            assert math.isnan(rec["relative_difference [-]"])
        else:
            assert rec["relative_difference [-]"] == pytest.approx((b - a) / abs(a), rel=1e-12)
    # the tabulated run has no gas: its gas metrics are NaN rows, kept
    gas = table.set_index("quantity").loc["discharge_mass_flow [kg/s]"]
    assert math.isnan(gas[label_a]) and gas[label_b] > 0.0
    # the coupled run has no leakage: a zero denominator in a self-difference would be NaN
    assert table.set_index("quantity").loc["leakage_mass_flow [kg/s]", label_b] == 0.0
    # bearings: RMS, peak, orbit radius per bearing, in the paper's order
    bearing_rows = table.loc[table["group"] == "bearing", "quantity"].tolist()
    assert bearing_rows[:3] == [
        "bearing_rms_primary [N]",
        "bearing_max_primary [N]",
        "orbit_radius_max_primary [m]",
    ]
    assert [q.split(" ")[0][len("bearing_rms_") :] for q in bearing_rows[::3]] == list(BEARINGS)


def test_output_directory_layout(tab_vs_coupled):
    """comparison.csv (round trip of the table), cases.csv, overlays, provenance, and each
    case's full report under its label."""
    out = tab_vs_coupled.out
    label_a, label_b = tab_vs_coupled.labels
    names = {p.name for p in out.iterdir()}
    expected = {"comparison.csv", "cases.csv", "provenance.json", label_a, label_b, MARKER}
    assert names == expected | OVERLAYS
    assert not [p for p in out.parent.iterdir() if p.name.startswith(".")]  # no temp left
    table = pd.read_csv(out / "comparison.csv")
    assert list(table.columns) == [*FIXED[:2], label_a, label_b, *FIXED[2:]]
    pd.testing.assert_frame_equal(table, tab_vs_coupled.table, check_exact=False, rtol=1e-15)
    cases = pd.read_csv(out / "cases.csv")
    assert list(cases["label"]) == [label_a, label_b]
    assert list(cases["pressure"]) == ["tabulated", "cylinder"]
    assert list(cases["mechanics"]) == ["flexible", "flexible"]
    assert list(cases["file"]) == [str(PAPER), str(out.parent / "reference_coupled.toml")]
    for label in (label_a, label_b):
        summary = pd.read_csv(out / label / "summary.csv")
        assert {"cycle.csv", "case.toml", "provenance.json"} <= {
            p.name for p in (out / label).iterdir()
        }
        rms = summary["bearing_rms_primary [N]"].iloc[0]
        assert table.set_index("quantity").loc["bearing_rms_primary [N]", label] == rms
    meta = json.loads((out / "provenance.json").read_text())
    assert set(meta["cases"]) == {label_a, label_b}
    assert meta["cases"][label_b]["options"]["mechanics"] == "flexible"
    assert meta["command"] == ["test"] and "recipsim" in meta and "CoolProp" in meta


def test_self_comparison_has_zero_differences(tmp_path, capsys):
    """The same case twice: every difference is 0 (the solver is deterministic), except the
    measured wall time; relative differences are 0 or NaN (A = 0, or a NaN gas metric)."""
    argv = ["compare", str(PAPER), str(PAPER), "--out", str(tmp_path / "self"), "--no-plots"]
    assert main(argv) == 0
    out = tmp_path / "self" / "paper_tabulated_vs_paper_tabulated"  # --out is the parent
    printed = capsys.readouterr().out
    assert "paper_tabulated_a" in printed and "bearing_rms_primary [N]" in printed
    table = pd.read_csv(out / "comparison.csv").set_index("quantity")
    assert list(table.columns[1:3]) == ["paper_tabulated_a", "paper_tabulated_b"]
    table = table.drop(index="wall_time [s]")
    a, b = table["paper_tabulated_a"], table["paper_tabulated_b"]
    both = a.notna() & b.notna()
    assert (a.isna() == b.isna()).all()
    assert (table.loc[both, "difference"] == 0.0).all()
    rel = table["relative_difference [-]"]
    assert ((rel == 0.0) | rel.isna()).all()
    assert rel.isna().sum() == (a.isna() | (a == 0.0)).sum()
    assert {p.name for p in out.iterdir()} == {
        "comparison.csv",
        "cases.csv",
        "provenance.json",
        "paper_tabulated_a",
        "paper_tabulated_b",
        MARKER,
    }


def test_pinned_against_flexible_rows_equal_direct_runs(tmp_path):
    """Pinned vs flexible crank train under the tabulated curve: the bearing rows are the
    summaries of the two cases run directly through simulate_case (deterministic: equal
    to the last bit), and flexible damped bearings stay within 10 % of pinned (the
    README's study: within 6 %)."""
    pinned = ['options.mechanics="pinned"', 'options.drive="constant_speed"', 'name="pinned"']
    comparison = run_comparison(
        PAPER, PAPER, overrides_a=pinned, out=tmp_path / "pf", plots=False, argv=["test"]
    )
    table = comparison.table.set_index("quantity")
    direct = [simulate_case(load_case(PAPER, pinned)).row, simulate_case(load_case(PAPER)).row]
    assert comparison.labels == ("pinned", "paper_tabulated")
    for bearing in BEARINGS:
        for kind in ("rms", "max"):
            q = f"bearing_{kind}_{bearing} [N]"
            assert table.loc[q, "pinned"] == direct[0][q]
            assert table.loc[q, "paper_tabulated"] == direct[1][q]
        rel = table.loc[f"bearing_rms_{bearing} [N]", "relative_difference [-]"]
        assert 0.0 < abs(rel) < 0.10
        # a pinned crank has no journal displacement, so relative orbit radii are NaN
        q = f"orbit_radius_max_{bearing} [m]"
        assert table.loc[q, "pinned"] == 0.0 and table.loc[q, "paper_tabulated"] > 0.0
        assert math.isnan(table.loc[q, "relative_difference [-]"])


@pytest.mark.parametrize(
    ("valves", "band"),
    [
        # lossless valves, adiabatic, no leakage: the cycle in crank angle does not depend
        # on the speed, so the mass per revolution is the same and the flow scales with
        # the speed exactly (1e-5: the periodic solver's tolerance is 1e-4 on the states;
        # both runs take the same path in crank angle to 1e-13 unless a last-bit change
        # of the start state flips one of the adaptive steps: a start temperature 1 ulp
        # lower or a suction entropy 4 ulps higher gives 1.5e-6)
        ("ideal", (-1.0 / 7.0 - 1e-5, -1.0 / 7.0 + 1e-5)),
        # reed valves: the discharge reed closes later (in crank angle) at the higher
        # speed and lets gas flow back, so the volumetric efficiency rises at 3000 rpm
        # (measured 0.695 -> 0.775) and the flow falls less than the speed; it still falls
        # (the efficiency cannot exceed the ratio 7/6). Band: (-1/7, 0).
        ("reed", (-1.0 / 7.0, 0.0)),
    ],
)
def test_speed_change_scales_mass_flow(tmp_path, valves, band):
    """3500 -> 3000 rpm: mass flow relative difference within the band; and it equals the
    speed ratio times the volumetric-efficiency ratio (same suction density and swept
    volume), a consistency check between three rows of the table (1e-9: round-off)."""
    comparison = run_comparison(
        REFERENCE,
        REFERENCE,
        overrides=[f"options.valves={valves}"],
        overrides_b=['operating_point.shaft_speed="3000 rpm"'],
        out=tmp_path / "speed",
        plots=False,
    )
    rel = comparison.table.set_index("quantity")["relative_difference [-]"]
    flow = rel["discharge_mass_flow [kg/s]"]
    assert rel["shaft_speed [rpm]"] == pytest.approx(-1.0 / 7.0, rel=1e-12)
    assert band[0] < flow < band[1]
    expected = (1.0 + rel["shaft_speed [rpm]"]) * (1.0 + rel["volumetric_efficiency [-]"]) - 1.0
    assert flow == pytest.approx(expected, rel=1e-9)


# ------------------------------------------------------------------------- command line


def test_missing_second_file_exits_2_and_keeps_previous_output(tmp_path, capsys):
    """A missing case B stops before anything runs: exit 2, one line naming the file, the
    previous comparison directory untouched, no temporary directory left."""
    out = tmp_path / "cmp"
    assert (
        main(["compare", str(PAPER), str(PAPER), "--out", str(out), "--no-plots", "--quiet"]) == 0
    )
    written = out / "paper_tabulated_vs_paper_tabulated"
    before = (written / "comparison.csv").read_bytes()
    missing = tmp_path / "nope.toml"
    assert main(["compare", str(PAPER), str(missing), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and str(missing) in err and "no such case file" in err
    assert (written / "comparison.csv").read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cmp"]


def test_bad_set_exits_2(tmp_path, capsys):
    out = tmp_path / "cmp"
    status = main(["compare", str(PAPER), str(PAPER), "--out", str(out), "--set", "solver.rtol=-1"])
    err = capsys.readouterr().err
    assert status == 2 and "solver.rtol" in err and "Traceback" not in err
    assert not out.exists()


def test_solver_failure_in_case_b_writes_nothing(tmp_path, capsys):
    """Case A runs, case B fails mid-cycle (state outside the refrigerant's range): exit 1,
    the message names B's file and the crank angle, and no output directory appears."""
    (tmp_path / "refrigerants").mkdir()
    lbp = (CASES.parent / "refrigerants" / "R134a.toml").read_text()
    lbp = lbp[lbp.index("[rating_points.ashrae_lbp]") : lbp.index("[rating_points.en12900_lbp]")]
    (tmp_path / "refrigerants" / "R134a_cold.toml").write_text(
        'name = "R134a_cold"\ncoolprop_name = "R134a"\n[limits]\nmax_temperature = "100 degC"\n'
        + lbp
    )
    hot = tmp_path / "hot.toml"
    hot.write_text(f'extends = "{REFERENCE}"\nrefrigerant = "R134a_cold"\n')
    out = tmp_path / "cmp"
    assert main(["compare", str(REFERENCE), str(hot), "--out", str(out), "--no-plots"]) == 1
    err = capsys.readouterr().err
    assert str(hot) in err and "crank angle" in err and "Traceback" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["hot.toml", "refrigerants"]


def test_refuses_to_replace_a_directory_that_is_not_a_comparison(tmp_path, capsys):
    """A directory of the user's where the comparison would go is never replaced: exit 2,
    the directory untouched."""
    mine = tmp_path / "paper_tabulated_vs_paper_tabulated"
    mine.mkdir()
    (mine / "keep.txt").write_text("mine")
    assert main(["compare", str(PAPER), str(PAPER), "--out", str(tmp_path), "--no-plots"]) == 2
    assert "not written by recipsim" in capsys.readouterr().err
    assert [p.name for p in tmp_path.iterdir()] == [mine.name]
    assert [p.name for p in mine.iterdir()] == ["keep.txt"]
