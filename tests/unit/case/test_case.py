"""Case loading: units to SI once, overrides, extends, and bad input refused clearly."""

import math
from pathlib import Path

import pytest

from helpers import ALL_CASES, REFERENCE, REFRIGERANTS
from recipsim.case.load import load_case
from recipsim.case.overrides import parse_override
from recipsim.cli.main import main
from recipsim.errors import CaseError


def test_reference_case_in_si():
    case = load_case(REFERENCE)
    op = case.operating_point
    assert op.shaft_speed == pytest.approx(3500 * 2 * math.pi / 60)
    assert op.evaporating_temperature == pytest.approx(249.85)
    assert op.suction_temperature == pytest.approx(305.35)
    # saturation pressures of R134a at -23.3 C and 54.4 C (thermo-notes V2: 1.148 / 14.7 bar)
    assert op.suction_pressure == pytest.approx(1.148e5, rel=2e-3)
    assert op.discharge_pressure == pytest.approx(14.7e5, rel=2e-3)
    assert case.geometry.bore == pytest.approx(0.022)
    assert case.geometry.clearance_volume == pytest.approx(0.02 * case.geometry.swept_volume)
    # reed of the PDSim example (thermo-notes 1.4): k = 309.8 N/m with E = 193 GPa and a
    # 0.1532 mm reed; k scales with the cube of the thickness (0.153 mm here)
    assert case.valves.suction.stiffness == pytest.approx(309.8 * (0.153 / 0.1532) ** 3, rel=1e-3)


@pytest.mark.parametrize("path", ALL_CASES, ids=[p.stem for p in ALL_CASES])
def test_every_shipped_case_loads(path):
    case = load_case(path)
    assert case.operating_point.discharge_pressure > case.operating_point.suction_pressure


def test_overrides_are_validated_like_the_file():
    case = load_case(
        REFERENCE,
        ["solver.rtol=1e-9", 'operating_point.shaft_speed="3000 rpm"', "options.valves=ideal"],
    )
    assert case.solver.rtol == 1e-9
    assert case.operating_point.shaft_speed == pytest.approx(3000 * 2 * math.pi / 60)
    assert case.options.valves == "ideal"
    assert parse_override("a.b=ideal") == (["a", "b"], "ideal")
    assert parse_override("a=1e-3") == (["a"], 1e-3)


@pytest.mark.parametrize(
    "override,key,fragment",
    [
        ("geometry.bore=-0.01", "geometry.bore", "out of range"),
        ('geometry.bore="22 kg"', "geometry.bore", "wrong dimension"),
        ("geometry.boer=0.02", "geometry.boer", "did you mean 'bore'"),
        ("options.valves=magic", "options.valves", "choose one of"),
        ("refrigerant=R999", "refrigerant", "unknown refrigerant"),
        (
            'operating_point.suction_temperature="-30 degC"',
            "operating_point.suction_temperature",
            "two-phase dome",
        ),
        (
            'operating_point.condensing_temperature="-30 degC"',
            "operating_point.condensing_temperature",
            "must be above the evaporating",
        ),
        ("solver.rtol=1", "solver.rtol", "allowed"),
        (
            'operating_point.liquid_temperature="70 degC"',
            "operating_point.liquid_temperature",
            "bubble point",
        ),
    ],
)
def test_bad_input_names_file_key_and_allowed(override, key, fragment):
    """A bad value set by an override is blamed on the override (where the value came
    from), with the key and what is allowed; the same value in a file names the file."""
    with pytest.raises(CaseError) as err:
        load_case(REFERENCE, [override])
    assert err.value.key == key
    assert err.value.file == f"override {override}"
    assert fragment in str(err.value)


def test_missing_required_key(tmp_path: Path):
    text = REFERENCE.read_text().replace('bore = "22.0 mm"\n', "")
    bad = tmp_path / "bad.toml"
    bad.write_text(text)
    (tmp_path / "refrigerants").symlink_to(REFRIGERANTS)
    with pytest.raises(CaseError) as err:
        load_case(bad)
    assert err.value.key == "geometry.bore"
    assert "missing required key" in str(err.value)


def test_cli_refuses_bad_input_with_exit_2_and_no_traceback(capsys):
    status = main(["run", str(REFERENCE), "--set", "geometry.stroke=5", "--no-plots"])
    err = capsys.readouterr().err
    assert status == 2
    assert "geometry.stroke" in err and "override geometry.stroke=5" in err
    assert "Traceback" not in err


def test_extends_merges_tables():
    case = load_case(REFERENCE.parent / "r32_ac.toml")
    assert case.name == "r32_ac"
    assert case.valves.suction.reed_thickness == pytest.approx(0.25e-3)
    assert case.valves.suction.port_diameter == pytest.approx(5.9e-3)  # inherited


def test_reference_case_carries_the_reference_mechanism():
    """One source of mechanism data: the case tables equal the library's reference spec."""
    from recipsim.case.reference_mechanism import reference_mechanism

    case = load_case(REFERENCE)
    assert case.mechanism == reference_mechanism()
    # the leakage length and the default liner come from the piston
    assert case.geometry.liner_length == pytest.approx(
        case.geometry.stroke + 0.020 + case.geometry.clearance_volume / case.geometry.piston_area
    )


def test_a_base_cases_pressure_curve_is_found_from_an_extending_case(tmp_path):
    """[pressure_curve] file is relative to the file that names it, not to the child."""
    from helpers import CASES

    child = tmp_path / "child.toml"
    child.write_text(f'extends = "{(CASES / "paper_tabulated.toml").as_posix()}"\n')
    case = load_case(child)
    assert case.pressure_curve is not None
    assert case.pressure_curve.pressure.max() > 1e6
