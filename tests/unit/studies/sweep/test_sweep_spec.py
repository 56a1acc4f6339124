"""Sweep files: grid expansion, axis columns in SI, and errors that name file and key."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from helpers import CASES, REFERENCE
from recipsim.case.load import load_case
from recipsim.cli.main import main
from recipsim.errors import CaseError
from recipsim.studies.sweep.engine import run_sweep
from recipsim.studies.sweep.plan import axis_column_names, plan_sweep
from recipsim.studies.sweep.spec import load_sweep

SWEEPS = CASES / "sweeps"


def write(tmp_path: Path, body: str, name: str = "s.toml") -> Path:
    path = tmp_path / name
    path.write_text(f'base = "{REFERENCE.as_posix()}"\n{body}')
    return path


def test_grid_order_points_and_si_columns(tmp_path):
    path = write(
        tmp_path,
        """
name = "small"
[set]
solver.max_revolutions = 80
[axes]
refrigerant = ["R134a", "R600a"]
operating_point.shaft_speed = ["3000 rpm", 350]
[[points]]
operating_point.evaporating_temperature = "-30 degC"
[[points]]
operating_point.evaporating_temperature = 248.15
""",
    )
    spec = load_sweep(path)
    assert spec.name == "small"
    points = list(spec.expand())
    assert len(points) == spec.size == 2 * 2 * 2
    # first axis slowest, explicit points fastest
    assert [dict(p.values)["refrigerant"] for p in points] == ["R134a"] * 4 + ["R600a"] * 4
    assert dict(points[1].values)["operating_point.evaporating_temperature"] == 248.15
    planned = plan_sweep(spec)
    assert [p.index for p in planned] == list(range(8))
    first = planned[0]
    assert list(first.columns) == [
        "refrigerant",
        "shaft_speed [rad/s]",
        "evaporating_temperature [K]",
    ]
    assert first.columns["refrigerant"] == "R134a"
    assert math.isclose(
        first.columns["shaft_speed [rad/s]"], 3000 * 2 * math.pi / 60, rel_tol=1e-12
    )
    assert math.isclose(first.columns["evaporating_temperature [K]"], 243.15, rel_tol=1e-12)
    assert planned[2].columns["shaft_speed [rad/s]"] == 350.0  # bare number: SI
    assert "solver.max_revolutions=80" in first.overrides
    # identifiers: distinct per case, stable from one planning to the next
    assert len({p.point_id for p in planned}) == 8
    assert [p.point_id for p in plan_sweep(load_sweep(path))] == [p.point_id for p in planned]


def test_same_case_same_id_whatever_the_sweep(tmp_path):
    a = write(tmp_path, '[axes]\nrefrigerant = ["R600a", "R134a"]\n', "a.toml")
    b = write(
        tmp_path, '[set]\nrefrigerant = "R134a"\n[[points]]\nname = "reference_r134a_lbp_ideal"\n'
    )
    ids_a = {p.columns["refrigerant"]: p.point_id for p in plan_sweep(load_sweep(a))}
    (only,) = plan_sweep(load_sweep(b))
    assert only.point_id == ids_a["R134a"]


def test_axis_column_names_units_and_clashes():
    names = axis_column_names(
        [
            "operating_point.condensing_temperature",
            "geometry.clearance_ratio",
            "valves.suction.reed_thickness",
            "valves.discharge.reed_thickness",
            "options.valves",
            "mechanism.piston.mass",
            "bearings.primary.stiffness",
        ]
    )
    assert names == {
        "operating_point.condensing_temperature": "condensing_temperature [K]",
        "geometry.clearance_ratio": "clearance_ratio [-]",
        "valves.suction.reed_thickness": "valves.suction.reed_thickness [m]",
        "valves.discharge.reed_thickness": "valves.discharge.reed_thickness [m]",
        "options.valves": "valves",
        "mechanism.piston.mass": "mass [kg]",
        "bearings.primary.stiffness": "stiffness [N/m]",
    }


def test_unknown_axis_key_fails_fast_naming_sweep_and_key(tmp_path, capsys):
    path = write(tmp_path, '[axes]\ngeometry.bore_typo = ["20 mm", "22 mm"]\n')
    with pytest.raises(CaseError) as info:
        plan_sweep(load_sweep(path))
    assert info.value.file == str(path)
    assert info.value.key == "axes.geometry.bore_typo"
    assert "unknown key" in info.value.message and "bore" in info.value.message
    # the command says so and exits 2 before computing anything
    status = main(["sweep", str(path), "--out", str(tmp_path / "out"), "--jobs", "1"])
    assert status == 2
    err = capsys.readouterr().err
    assert "axes.geometry.bore_typo" in err and str(path) in err
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize(
    ("body", "key", "words"),
    [
        ('[axes]\nrefrigerant = "R134a"\n', "axes.refrigerant", "non-empty list"),
        ("[axes]\nrefrigerant = []\n", "axes.refrigerant", "non-empty list"),
        ('[axes]\nrefrigerant = ["R134a", "R134a"]\n', "axes.refrigerant", "repeated"),
        (
            '[set]\nrefrigerant = "R600a"\n[axes]\nrefrigerant = ["R134a"]\n',
            "set.refrigerant",
            "also an axis",
        ),
        ('[axes]\nrefrigerant = [["R134a"]]\n', "axes.refrigerant", "not allowed"),
        ("name = 'a/b'\n[axes]\nrefrigerant = ['R134a']\n", "name", "directory name"),
        ("stray = 1\n[axes]\nrefrigerant = ['R134a']\n", "stray", "unknown key"),
        ("[set]\nsolver.rtol = 1e-7\n", "axes", "needs [axes] or [[points]]"),
        # the top level is read by the shared schema: the key and its allowed range
        ("max_points = 0\n[axes]\nrefrigerant = ['R134a']\n", "max_points", "allowed [1, inf]"),
        ("max_points = 2.5\n[axes]\nrefrigerant = ['R134a']\n", "max_points", "whole number"),
        ("description = 3\n[axes]\nrefrigerant = ['R134a']\n", "description", "a string"),
    ],
)
def test_sweep_file_errors_name_the_key(tmp_path, body, key, words):
    path = write(tmp_path, body)
    with pytest.raises(CaseError) as info:
        load_sweep(path)
    assert info.value.file == str(path)
    assert info.value.key == key
    assert words in info.value.message


def test_missing_base_case(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text('base = "nowhere.toml"\n[axes]\nrefrigerant = ["R134a"]\n')
    with pytest.raises(CaseError) as info:
        load_sweep(path)
    assert info.value.key == "base" and "no such case file" in info.value.message
    path.write_text('[axes]\nrefrigerant = ["R134a"]\n')
    with pytest.raises(CaseError) as info:
        load_sweep(path)
    assert info.value.key == "base" and "missing required key" in info.value.message
    assert "a shipped case by name" in info.value.message  # what base is, from SWEEP_SPEC


def test_top_level_defaults(tmp_path):
    spec = load_sweep(
        write(tmp_path, "max_points = 7\n[axes]\nrefrigerant = ['R134a']\n", "my map.toml")
    )
    assert spec.name == "my_map" and spec.description == ""
    assert spec.max_points == 7 and isinstance(spec.max_points, int)


def test_command_line_set_may_not_name_an_axis(tmp_path):
    path = write(tmp_path, '[axes]\nrefrigerant = ["R134a"]\n')
    with pytest.raises(CaseError, match="is an axis"):
        plan_sweep(load_sweep(path), ["refrigerant=R600a"])


def test_invalid_values_become_invalid_points_not_errors(tmp_path):
    """Invalid values do not stop the plan; each such point is validated where it runs and
    becomes an ``invalid`` row naming the key, while the valid point is computed."""
    path = write(
        tmp_path,
        "[set]\nsolver.max_revolutions = 3\nsolver.min_revolutions = 1\n"
        '[axes]\nrefrigerant = ["R134a", "R999"]\n'
        'operating_point.evaporating_temperature = ["-30 degC", "60 degC"]\n',
    )
    planned = plan_sweep(load_sweep(path))
    assert len(planned) == 4
    outcome = run_sweep(path, jobs=1, out=tmp_path / "out", plots=False)
    rows = {
        (r["refrigerant"], r["evaporating_temperature [K]"]): r for _, r in outcome.table.iterrows()
    }
    assert rows[("R134a", 243.15)]["status"] in ("ok", "not_converged")
    assert rows[("R134a", 333.15)]["status"] == "invalid"
    assert "condensing_temperature" in rows[("R134a", 333.15)]["message"]
    assert rows[("R999", 243.15)]["status"] == "invalid"
    assert "unknown refrigerant 'R999'" in rows[("R999", 243.15)]["message"]


def test_shipped_sweeps_are_valid():
    sizes = {"lbp_map": 48, "ac_map": 20, "throughput_100": 100}
    for name, size in sizes.items():
        spec = load_sweep(SWEEPS / f"{name}.toml")
        planned = plan_sweep(spec)
        assert len(planned) == size == spec.size, name
        for point in planned:  # every point is a valid case
            load_case(spec.base, list(point.overrides))
        assert len({p.point_id for p in planned}) == size, name
    lbp = plan_sweep(load_sweep(SWEEPS / "lbp_map.toml"))
    evaporating = sorted({round(p.columns["evaporating_temperature [K]"] - 273.15, 9) for p in lbp})
    assert evaporating == [-35.0, -30.0, -25.0, -20.0, -15.0, -10.0]
    assert {p.columns["refrigerant"] for p in lbp} == {"R134a", "R600a", "R290", "R1234yf"}
    ac = plan_sweep(load_sweep(SWEEPS / "ac_map.toml"))
    assert {p.columns["refrigerant"] for p in ac} == {"R32", "R410A"}
    # condensing and liquid temperature move together (8.3 K subcooling)
    for p in ac:
        sub = p.columns["condensing_temperature [K]"] - p.columns["liquid_temperature [K]"]
        assert math.isclose(sub, 8.3, abs_tol=1e-9)


def test_dotted_nested_and_quoted_keys_are_the_same(tmp_path):
    forms = {
        "dotted": '[axes]\noperating_point.shaft_speed = ["3000 rpm", "3600 rpm"]\n',
        "nested": '[axes.operating_point]\nshaft_speed = ["3000 rpm", "3600 rpm"]\n',
        "quoted": '[axes]\n"operating_point.shaft_speed" = ["3000 rpm", "3600 rpm"]\n',
    }
    ids = {}
    for form, body in forms.items():
        spec = load_sweep(write(tmp_path, body, f"{form}.toml"))
        assert spec.axes == (("operating_point.shaft_speed", ("3000 rpm", "3600 rpm")),)
        ids[form] = [p.point_id for p in plan_sweep(spec)]
    assert ids["dotted"] == ids["nested"] == ids["quoted"]
