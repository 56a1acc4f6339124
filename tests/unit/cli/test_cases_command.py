"""``recipsim cases`` lists what is shipped; a mistyped case or sweep name is refused
with one line that suggests the closest names (exit status 2)."""

from __future__ import annotations

import pytest

import recipsim
from helpers import CASES
from recipsim.cli.main import main


def _listed(out: str) -> dict[str, str]:
    """Name to kind, from the printed table (its columns start where the header's do)."""
    header, *rows = out.splitlines()
    kind, description = header.index("kind"), header.index("description")
    return {row[:kind].strip(): row[kind:description].strip() for row in rows}


def test_cases_lists_every_shipped_case_file(capsys):
    assert main(["cases"]) == 0
    out = capsys.readouterr().out
    assert out.splitlines()[0].split() == ["name", "kind", "description"]
    listed = _listed(out)
    expected = {p.stem: "case" for p in CASES.glob("*.toml")}
    expected |= {p.stem: "sweep" for p in (CASES / "sweeps").glob("*.toml")}
    hard = (CASES / "hard").glob("*.toml")
    expected |= {p.stem: "hard case" for p in hard if p.name != "expectations.toml"}
    assert listed == expected
    assert sorted(listed) == sorted(recipsim.cases()["name"])
    assert "Reference 7 cm3 household compressor, R134a, ASHRAE LBP" in out


@pytest.mark.parametrize(("kind", "shown"), [("sweeps", "sweep"), ("hard", "hard case")])
def test_cases_lists_one_kind(kind, shown, capsys):
    assert main(["cases", "--kind", kind]) == 0
    listed = _listed(capsys.readouterr().out)
    assert listed and set(listed.values()) == {shown}


def test_a_mistyped_case_name_exits_2_with_a_suggestion(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    status = main(["run", "reference_r134a_lbq", "--no-plots", "--out", str(tmp_path)])
    err = capsys.readouterr().err
    assert status == 2
    assert len(err.strip().splitlines()) == 1, err
    assert "reference_r134a_lbq" in err and "did you mean reference_r134a_lbp" in err
    assert not any(tmp_path.iterdir())  # nothing written


def test_a_mistyped_sweep_name_exits_2_with_a_suggestion(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    status = main(["sweep", "lbp_mapp", "--out", str(tmp_path)])
    err = capsys.readouterr().err
    assert status == 2
    assert len(err.strip().splitlines()) == 1, err
    assert "lbp_mapp" in err and "did you mean lbp_map?" in err
