"""recipsim run writes a complete, documented report, atomically."""

import json
import re

import pandas as pd
import pytest

from helpers import REFERENCE, REFRIGERANTS, ROOT
from recipsim.atomic import swap_in
from recipsim.cli.main import main
from recipsim.physics.mechanics.layout import BEARING_NAMES
from recipsim.physics.thermo.shell_network import NODES

SUMMARY_REQUIRED = [
    "refrigerant",
    "evaporating_temperature [K]",
    "condensing_temperature [K]",
    "suction_pressure [Pa]",
    "suction_temperature [K]",
    "discharge_pressure [Pa]",
    "shaft_speed [rpm]",
    "swept_volume [m3]",
    "clearance_volume [m3]",
    "suction_mass_flow [kg/s]",
    "discharge_mass_flow [kg/s]",
    "leakage_mass_flow [kg/s]",
    "cooling_capacity [W]",
    "indicated_power [W]",
    "shaft_power [W]",
    "COP [-]",
    "volumetric_efficiency [-]",
    "isentropic_efficiency [-]",
    "discharge_temperature [K]",
    "revolutions [-]",
    "cycle_residual [-]",
    "wall_time [s]",
]
CYCLE_REQUIRED = [
    "crank_angle [deg]",
    "time [s]",
    "cylinder_volume [m3]",
    "cylinder_pressure [Pa]",
    "gas_temperature [K]",
    "suction_valve_lift [m]",
    "discharge_valve_lift [m]",
    "suction_mass_flow [kg/s]",
    "discharge_mass_flow [kg/s]",
    "shaft_torque [N m]",
]


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    out = tmp_path_factory.mktemp("reports")
    assert main(["run", str(REFERENCE), "--out", str(out), "--quiet"]) == 0
    return out / "reference_r134a_lbp_ideal"


def test_report_files(report):
    names = {p.name for p in report.iterdir()}
    assert {
        "summary.csv",
        "summary.md",
        "cycle.csv",
        "case.toml",
        "provenance.json",
        "p_V.png",
        "p_V_loglog.png",
        "p_theta.png",
        "valves.png",
        "torque.png",
    } <= names
    meta = json.loads((report / "provenance.json").read_text())
    assert meta["property_backend"] == "CoolProp TABLE" and meta["solver"]["rtol"] > 0
    assert meta["property_table_max_error [-]"] < 1e-4  # measured against HEOS at build
    # the case as run, resolved (tests/unit/report/test_resolved_case.py): the same case
    from recipsim.case.load import load_case

    resolved, original = load_case(report / "case.toml"), load_case(REFERENCE)
    assert resolved.operating_point == original.operating_point
    assert resolved.geometry == original.geometry and resolved.valves == original.valves


def test_columns_carry_units_and_are_documented(report):
    summary = pd.read_csv(report / "summary.csv")
    cycle = pd.read_csv(report / "cycle.csv")
    assert len(summary) == 1
    assert set(SUMMARY_REQUIRED) <= set(summary.columns)
    assert set(CYCLE_REQUIRED) <= set(cycle.columns)
    doc = (ROOT / "reports" / "README.md").read_text()
    documented = set()
    for name in re.findall(r"^\| `([^`]+)`", doc, flags=re.M):
        # per-bearing rows are documented once, with <name> for each of the six bearings
        names = BEARING_NAMES if "<name>" in name else ("",)
        documented |= {name.replace("<name>", b) for b in names}
        # the thermal network's nodes likewise, with <node>
        if "<node>" in name:
            documented |= {name.replace("<node>", n) for n in NODES}
    text_columns = {
        "case",
        "refrigerant",
        "pressure",
        "mechanics",
        "drive",
        "valves",
        "heat_transfer",
        "leakage",
        "periodic_method",
        "standard",
        "friction",
        "motor",
        "thermal",
        "status",
        "status_message",
    }
    for col in list(summary.columns) + list(cycle.columns):
        assert col in documented, f"column {col!r} is not documented in reports/README.md"
        if col not in text_columns:
            assert re.search(r"\[[^\]]+\]$", col), f"column {col!r} has no unit"


def test_cycle_table_is_uniform_in_crank_angle(report):
    cycle = pd.read_csv(report / "cycle.csv")
    assert len(cycle) == 720
    theta = cycle["crank_angle [deg]"].to_numpy()
    assert theta[0] == pytest.approx(0.0, abs=1e-9)
    assert (abs(theta[1:] - theta[:-1] - 0.5) < 1e-9).all()
    # TDC: smallest volume; mean of torque x omega over the samples ~ shaft power
    v = cycle["cylinder_volume [m3]"].to_numpy()
    assert v.argmin() == 0
    summary = pd.read_csv(report / "summary.csv").iloc[0]
    omega = summary["shaft_speed [rpm]"] * 2 * 3.141592653589793 / 60
    mean_power = cycle["shaft_torque [N m]"].mean() * omega
    assert mean_power == pytest.approx(summary["shaft_power [W]"], rel=1e-2)


def test_swap_in_replaces_directory_whole(tmp_path):
    target = tmp_path / "case"
    target.mkdir()
    (target / "old.csv").write_text("old")
    new = tmp_path / "new"
    new.mkdir()
    (new / "summary.csv").write_text("new")
    swap_in(new, target)
    assert sorted(p.name for p in target.iterdir()) == ["summary.csv"]
    assert not new.exists()
    assert [p.name for p in tmp_path.iterdir()] == ["case"]


def test_solver_failure_names_crank_angle_and_state(capsys, tmp_path):
    """A state outside the refrigerant's range mid-cycle stops with angle and state."""
    (tmp_path / "refrigerants").mkdir()
    # R134a with the model's range capped at 100 C, and the reference's rating point
    lbp = (REFRIGERANTS / "R134a.toml").read_text()
    lbp = lbp[lbp.index("[rating_points.ashrae_lbp]") : lbp.index("[rating_points.en12900_lbp]")]
    (tmp_path / "refrigerants" / "R134a_cold.toml").write_text(
        'name = "R134a_cold"\ncoolprop_name = "R134a"\n[limits]\nmax_temperature = "100 degC"\n'
        + lbp
    )
    case = tmp_path / "hot.toml"
    case.write_text(f'extends = "{REFERENCE}"\nrefrigerant = "R134a_cold"\n')
    status = main(["run", str(case), "--out", str(tmp_path / "out"), "--no-plots"])
    err = capsys.readouterr().err
    assert status == 1
    # isentropic compression passes 100 C (373 K) at about 40 deg before TDC
    match = re.search(r"crank angle ([0-9.]+) deg", err)
    assert match and 300.0 < float(match.group(1)) < 340.0
    assert "equation of state" in err and "T = 373.1" in err
    assert "Traceback" not in err
    assert not (tmp_path / "out" / "hot").exists()  # nothing half-written
