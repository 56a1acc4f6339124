"""``recipsim sweep --set``: the output directory is named like ``recipsim run``'s report
(``<name>+<digest>`` with overrides), and a sweep never resumes into a directory that
recorded other overrides (issue 14).

The points stop after 2 or 3 revolutions (``not_converged``, 0.1 s each): what is checked
is where they go and which are reused, not the physics.
"""

from __future__ import annotations

import json
from pathlib import Path

import pandas as pd
import pytest

from helpers import REFERENCE
from recipsim.cli.main import main
from recipsim.errors import CaseError
from recipsim.report.case_report import overrides_digest
from recipsim.studies.sweep.engine import run_sweep

TWO = ["solver.max_revolutions=2"]
THREE = ["solver.max_revolutions=3"]


@pytest.fixture()
def sweep(tmp_path: Path) -> Path:
    path = tmp_path / "tiny.toml"
    path.write_text(
        f'name = "tiny"\nbase = "{REFERENCE.as_posix()}"\n'
        '[axes]\noperating_point.evaporating_temperature = ["-30 degC"]\n'
    )
    return path


def run(sweep: Path, out: Path, sets: list[str], *extra: str) -> int:
    argv = ["sweep", str(sweep), "--out", str(out), "--jobs", "1", "--no-plots", "--quiet"]
    for text in sets:
        argv += ["--set", text]
    return main([*argv, *extra])


def revolutions(directory: Path) -> list[int]:
    return list(pd.read_csv(directory / "summary.csv")["revolutions [-]"])


def test_overrides_name_the_directory(sweep: Path, tmp_path: Path) -> None:
    """Two sweeps with other --set values write two directories, each with its own
    points; no --set keeps the plain name; the same values spelled otherwise go to
    their own directory (point files match their overrides' text, so the point is
    recomputed there, with the same result); the same text reuses it."""
    out = tmp_path / "out"
    assert run(sweep, out, TWO) == 1  # the point stops unconverged after 2 revolutions
    assert run(sweep, out, THREE) == 1
    two = out / f"tiny+{overrides_digest(TWO)}"
    three = out / f"tiny+{overrides_digest(THREE)}"
    assert overrides_digest(TWO) != overrides_digest(THREE)
    assert sorted(p.name for p in out.iterdir()) == sorted([two.name, three.name])
    assert revolutions(two) == [2] and revolutions(three) == [3]
    for directory, sets in ((two, TWO), (three, THREE)):
        recorded = json.loads((directory / "overrides.json").read_text())
        assert recorded == {"overrides": sets, "digest": overrides_digest(sets)}
    spelled = run_sweep(
        sweep, out=out, overrides=["solver.max_revolutions = 2"], jobs=1, plots=False
    )
    assert spelled.directory == two and revolutions(two) == [2]
    again = run_sweep(sweep, out=out, overrides=["solver.max_revolutions = 2"], jobs=1, plots=False)
    assert again.directory == two and again.computed == [] and len(again.reused) == 1
    plain = run_sweep(sweep, out=out, overrides=[], jobs=1, plots=False)
    assert plain.directory == out / "tiny"
    assert json.loads((out / "tiny" / "overrides.json").read_text())["overrides"] == []


def test_refuses_to_resume_into_other_overrides(sweep: Path, tmp_path: Path, capsys) -> None:
    """A directory that recorded other overrides (here copied by hand under the name of
    these) is refused (exit 2, nothing written), unless --fresh recomputes every point."""
    out = tmp_path / "out"
    assert run(sweep, out, TWO) == 1
    two = out / f"tiny+{overrides_digest(TWO)}"
    three = out / f"tiny+{overrides_digest(THREE)}"
    two.rename(three)
    before = {p.name: p.read_bytes() for p in three.rglob("*") if p.is_file()}
    with pytest.raises(CaseError, match="other overrides"):
        run_sweep(sweep, out=out, overrides=THREE, jobs=1, plots=False)
    capsys.readouterr()
    assert run(sweep, out, THREE) == 2
    assert "refusing to resume" in capsys.readouterr().err
    after = {p.name: p.read_bytes() for p in three.rglob("*") if p.is_file()}
    assert after == before
    assert run(sweep, out, THREE, "--fresh") == 1
    assert revolutions(three) == [3]
    assert json.loads((three / "overrides.json").read_text())["overrides"] == THREE
