"""Where a case, a sweep or a refrigerant given by name is found, and what is shipped.

A name is looked up in the working directory first (``./cases/NAME.toml``,
``./cases/sweeps/NAME.toml``, ``./refrigerants/NAME.toml``), then among the shipped files
(the top-level ``cases/`` and ``refrigerants/``); an existing file path wins over both.
The tests change one physical value in the local copy and check that the loaded case
carries it.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

import recipsim
from helpers import CASES, REFERENCE, REFERENCE_REAL, REFRIGERANTS
from recipsim.case.files import case_dirs, find_case_file, shipped_dir
from recipsim.case.load import load_case
from recipsim.case.shipped import describe, shipped_cases
from recipsim.errors import CaseError
from recipsim.studies.sweep.spec import load_sweep

RPM = 2 * math.pi / 60  # [rad/s] per rpm


def _shipped_files() -> dict[str, set[str]]:
    """The stems of the shipped case files, by kind, read from the source tree."""
    return {
        "case": {p.stem for p in CASES.glob("*.toml")},
        "sweep": {p.stem for p in (CASES / "sweeps").glob("*.toml")},
        "hard case": {p.stem for p in (CASES / "hard").glob("*.toml")} - {"expectations"},
    }


def test_shipped_folders_are_the_top_level_folders_of_the_source_tree():
    assert shipped_dir("cases") == CASES
    assert shipped_dir("refrigerants") == REFRIGERANTS
    assert load_case("reference_r134a_lbp").path == str(REFERENCE_REAL)


def test_a_local_case_shadows_the_shipped_case_of_the_same_name(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    local = tmp_path / "cases" / "reference_r134a_lbp.toml"
    local.parent.mkdir()
    local.write_text(REFERENCE.read_text().replace('"3500 rpm"', '"3000 rpm"', 1))
    assert case_dirs() == [local.parent, CASES]
    case = load_case("reference_r134a_lbp")
    assert case.path == str(local)
    assert case.operating_point.shaft_speed == pytest.approx(3000 * RPM)
    # an existing file given by its path wins over both
    assert load_case(REFERENCE).operating_point.shaft_speed == pytest.approx(3500 * RPM)
    (tmp_path / "reference_r134a_lbp").write_text(
        REFERENCE.read_text().replace('"3500 rpm"', '"2000 rpm"', 1)
    )
    case = load_case("reference_r134a_lbp")
    assert case.path == "reference_r134a_lbp"
    assert case.operating_point.shaft_speed == pytest.approx(2000 * RPM)


def test_a_case_extending_a_name_finds_the_local_case_first(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "cases").mkdir()
    (tmp_path / "cases" / "reference_r134a_lbp.toml").write_text(
        REFERENCE.read_text().replace('"3500 rpm"', '"3000 rpm"', 1)
    )
    child = tmp_path / "elsewhere" / "child.toml"
    child.parent.mkdir()
    child.write_text('extends = "reference_r134a_lbp"\nname = "child"\n')
    assert load_case(child).operating_point.shaft_speed == pytest.approx(3000 * RPM)


def test_a_local_sweep_shadows_the_shipped_sweep_of_the_same_name(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    local = tmp_path / "cases" / "sweeps" / "lbp_map.toml"
    local.parent.mkdir(parents=True)
    text = (CASES / "sweeps" / "lbp_map.toml").read_text()
    local.write_text(text.replace('description = "', 'description = "local copy: ', 1))
    sweep = load_sweep("lbp_map")
    assert sweep.path == local
    assert sweep.description.startswith("local copy: ")
    assert sweep.base == REFERENCE  # its base, by name, is still the shipped case


def test_a_local_refrigerant_file_shadows_the_shipped_one(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    local = tmp_path / "refrigerants" / "R134a.toml"
    local.parent.mkdir()
    text = (REFRIGERANTS / "R134a.toml").read_text()
    assert 'max_temperature = "180 degC"' in text
    local.write_text(text.replace('max_temperature = "180 degC"', 'max_temperature = "170 degC"'))
    # also for a shipped case, whose folder's parent holds the shipped refrigerants
    case = load_case("reference_r134a_lbp")
    assert case.refrigerant.path == str(local)
    assert case.refrigerant.max_temperature == pytest.approx(273.15 + 170)
    monkeypatch.chdir(tmp_path.parent)
    shipped = load_case("reference_r134a_lbp").refrigerant
    assert shipped.path == str(REFRIGERANTS / "R134a.toml")
    assert shipped.max_temperature == pytest.approx(273.15 + 180)


@pytest.mark.parametrize(
    ("name", "folder", "kind", "meant"),
    [
        ("reference_r134a_lbq", "", "case", "reference_r134a_lbp"),
        ("reference_r134a_lbq.toml", "", "case", "reference_r134a_lbp"),
        ("lbp_mapp", "sweeps", "sweep", "lbp_map"),
    ],
)
def test_an_unknown_name_suggests_the_closest_names(name, folder, kind, meant, tmp_path):
    with pytest.raises(CaseError) as err:
        find_case_file(name, folder, kind)
    message = str(err.value)
    assert "\n" not in message
    assert message.startswith(f"{name}: no such {kind} file: {name}")
    assert f"did you mean {meant}" in message


def test_an_unknown_name_without_close_names_points_to_the_listing():
    with pytest.raises(CaseError, match="`recipsim cases` lists them"):
        find_case_file("xyzzy")


def test_extends_naming_an_unknown_case_suggests_the_closest_names(tmp_path):
    child = tmp_path / "child.toml"
    child.write_text('extends = "reference_r134a_lbq"\n')
    with pytest.raises(CaseError, match="did you mean reference_r134a_lbp") as err:
        load_case(child)
    assert err.value.key == "extends"


def test_shipped_cases_lists_every_shipped_file_with_its_description():
    listed = shipped_cases()
    expected = _shipped_files()
    for kind, names in expected.items():
        assert {c.name for c in listed if c.kind == kind} == names, kind
    assert len(listed) == sum(len(names) for names in expected.values())
    for case in listed:
        assert case.path.is_file() and case.path.is_relative_to(CASES)
        assert case.description and "\n" not in case.description, case.name
    reference = next(c for c in listed if c.name == "reference_r134a_lbp")
    assert reference.description == load_case(REFERENCE_REAL).description
    assert [c.kind for c in shipped_cases(("sweep",))] == ["sweep"] * len(expected["sweep"])
    with pytest.raises(ValueError, match="unknown kind"):
        shipped_cases(("sweeps",))


def test_the_api_lists_the_same_names():
    table = recipsim.cases()
    assert list(table.columns) == ["name", "kind", "description", "path"]
    assert sorted(table["name"]) == sorted(c.name for c in shipped_cases())
    assert set(recipsim.cases("hard case")["name"]) == _shipped_files()["hard case"]


def test_describe_falls_back_to_the_first_comment_line(tmp_path: Path):
    path = tmp_path / "case.toml"
    path.write_text("#\n# A short case: what it is.\n# More.\nrefrigerant = 'R134a'\n")
    assert describe(path) == "A short case: what it is."
    path.write_text('# comment\ndescription = "  The key   wins "\n')
    assert describe(path) == "The key wins"
