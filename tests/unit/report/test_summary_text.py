"""The summary for a person (summary.md, the console after ``recipsim run``,
``Result.summary_text()``): the row's values in W, bar, C, kg/h and rpm, the electrical
figures only where a motor model is on, the three largest losses in order; and
summary.csv keeps the SI values, each written as the shortest text that reads back."""

from __future__ import annotations

import math

import pandas as pd

from recipsim.report.report_figures import write_tables
from recipsim.report.summary_text import key_figures, summary_markdown, summary_text
from recipsim.results.loss_breakdown import LOSS_COLUMNS
from recipsim.units import to_si


def _row(**changes):
    row = {
        "case": "point",
        "refrigerant": "R134a",
        "pressure": "cylinder",
        "mechanics": "pinned",
        "drive": "constant_speed",
        "motor": "lossless",
        "evaporating_temperature [K]": 249.85,
        "condensing_temperature [K]": 327.55,
        "suction_pressure [Pa]": 1.148e5,
        "suction_temperature [K]": 305.35,
        "discharge_pressure [Pa]": 14.7e5,
        "mean_crank_speed [rpm]": 3500.0,
        "discharge_temperature [K]": 397.75,
        "discharge_mass_flow [kg/s]": 5.4 / 3600.0,
        "cooling_capacity [W]": 276.0,
        "shaft_power [W]": 120.0,
        "motor_electrical_power [W]": 120.0,
        "COP [-]": 2.3,
        "isentropic_efficiency [-]": 0.9156,
        "volumetric_efficiency [-]": 0.7732,
        "revolutions [-]": 5,
        "cycle_residual [-]": 3.8e-5,
        "converged [-]": True,
        **dict.fromkeys(LOSS_COLUMNS, 0.0),
        "loss_suction_valve [W]": 4.7,
        "loss_discharge_valve [W]": 3.5,
        "loss_leakage [W]": 6.0,
        "loss_mufflers [W]": 1.0,
    }
    return {**row, **changes}


def _figures(row):
    return {name: (value, unit) for name, value, unit in key_figures(row)}


def test_values_are_in_the_units_an_engineer_reads():
    figures = _figures(_row())
    assert figures["evaporating temperature"] == ("-23.3", "C")
    assert figures["suction pressure"] == ("1.148", "bar")
    assert figures["discharge pressure"] == ("14.70", "bar")
    assert figures["mass flow"] == ("5.400", "kg/h")
    assert figures["speed"] == ("3500", "rpm")
    assert figures["discharge temperature"] == ("124.6", "C")
    assert figures["COP, shaft power"] == ("2.30", "-")  # 276 W / 120 W
    assert figures["periodic state"][0] == "converged"


def test_without_a_motor_model_only_the_shaft_power_is_given():
    figures = _figures(_row())
    assert figures["electrical power"][0] == "-"
    assert "shaft power only" in figures["electrical power"][1]
    assert "COP, electrical" not in figures
    with_motor = _figures(_row(motor="catalogue", **{"motor_electrical_power [W]": 150.0}))
    assert with_motor["electrical power"] == ("150.0", "W")
    assert with_motor["COP, electrical"] == ("2.30", "-")  # the row's COP [-], as computed


def test_the_three_largest_losses_come_largest_first_with_their_share():
    names = [name for name, _, _ in key_figures(_row()) if name.startswith("loss: ")]
    assert names == ["loss: leakage", "loss: suction valve", "loss: discharge valve"]
    assert _figures(_row())["loss: leakage"] == ("6.0", "W (5.0 % of the input)")  # of 120 W


def test_a_tabulated_pressure_has_no_gas_figures():
    row = _row(pressure="tabulated", **dict.fromkeys(LOSS_COLUMNS, math.nan))
    figures = _figures(row)
    assert "cooling capacity" not in figures and "mass flow" not in figures
    assert not any(name.startswith("loss: ") for name in figures)
    assert figures["shaft power"] == ("120.0", "W")


def test_console_and_markdown_carry_the_same_figures():
    text, markdown = summary_text(_row()), summary_markdown(_row())
    for name, value, _ in key_figures(_row()):
        line = next(line for line in text.splitlines() if line.startswith(name + " "))
        assert value in line
        assert f"| {name} | {value} |" in markdown


def test_summary_csv_keeps_si_values_written_to_read_back(tmp_path):
    evaporating = to_si("-23.3 degC", "K", "case.toml", "operating_point.evaporating_temperature")
    row = _row(**{"evaporating_temperature [K]": evaporating, "cooling_capacity [W]": 1 / 3})
    write_tables(tmp_path, row, pd.DataFrame({"crank_angle [deg]": [0.0]}))
    text = (tmp_path / "summary.csv").read_text()
    assert ",249.85," in text  # the exact SI value of -23.3 C, no conversion noise
    read = pd.read_csv(tmp_path / "summary.csv")
    assert read["cooling_capacity [W]"].iloc[0] == 1 / 3  # every digit kept
    assert "| evaporating temperature | -23.3 | C |" in (tmp_path / "summary.md").read_text()
