"""``recipsim check hard --fast``: every hard case meets its expectation; the check's
table logic (reed openings, judging, expectations file, CSV, exit status).

The suite run (one module-scoped fixture, about 20 s on one core) is the CI run of the
stability suite: each case must end as the hard cases' expectations.toml says, converged
cases with finite results and closures within the tolerances of recipsim.studies.check.metrics
(mass 1e-3, energy 5e-3 of the swept mass and its isentropic work; drive 5e-3). The
unit tests use synthetic rows and refused cases only (nothing is integrated).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from helpers import CASES, REFERENCE
from recipsim.cli.main import main
from recipsim.errors import CaseError
from recipsim.studies.check.expectations import Expectation, find_cases, load_expectations
from recipsim.studies.check.judge import CheckRow, judge
from recipsim.studies.check.metrics import ORBIT_METRIC, reed_openings
from recipsim.studies.check.run import run_check
from recipsim.studies.check.table import format_table, write_check_csv

HARD = CASES / "hard"

#: The hard cases issue 5 asks for (a renamed or deleted case must fail here).
REQUIRED = {
    "bearings_stiff_x100",
    "bearings_stiff_x1000",
    "bearings_undamped",
    "speed_1500rpm",
    "speed_6000rpm",
    "near_zero_delivery",
    "r744_transcritical_90bar",
    "soft_suction_reed_flutter",
    "clearance_0p2pct",
    "suction_near_saturation",
    "wet_suction",
    "startup_induction_motor",
}


@pytest.fixture(scope="module")
def suite(tmp_path_factory: pytest.TempPathFactory) -> dict[str, CheckRow]:
    """``recipsim check hard --fast`` through the Python API, rows by case."""
    rows = run_check([HARD], fast=True)
    write_check_csv(rows, tmp_path_factory.mktemp("check"))
    return {r.case: r for r in rows}


def test_every_required_hard_case_is_shipped_with_an_expectation() -> None:
    _, listed = load_expectations(HARD / "expectations.toml")
    stems = {p.stem for p in find_cases([HARD])}
    assert REQUIRED <= stems
    assert stems == set(listed), "every hard case states its expectation explicitly"


def test_every_hard_case_meets_its_expectation(suite: dict[str, CheckRow]) -> None:
    unexpected = {name: (r.outcome, r.note) for name, r in suite.items() if not r.matches}
    assert not unexpected


def test_converged_hard_cases_are_finite_and_closed(suite: dict[str, CheckRow]) -> None:
    # the closures asserted directly, independently of judge(): the gas closures apply
    # where a gas is simulated (not under a tabulated pressure), the drive closure always
    converged = [r for r in suite.values() if r.outcome == "converged"]
    assert len(converged) >= 10
    for r in converged:
        assert r.finite, (r.case, r.non_finite)
        if r.case != "bearings_undamped_tabulated":
            assert r.mass_closure is not None and r.mass_closure <= 1e-3, r.case
            assert r.energy_closure is not None and r.energy_closure <= 5e-3, r.case
        assert r.drive_closure is not None and r.drive_closure <= 5e-3, r.case


def test_lubricated_hard_cases_keep_every_orbit_inside_its_clearance(
    suite: dict[str, CheckRow],
) -> None:
    """Issue 15: on the hard cases with oil films (6000 rpm; films at 120 C) the largest
    eccentricity ratio of every journal stays below 1, and measurably above the
    reference's (0.62 on the eccentric at 60 C, 3500 rpm) where the oil is thin."""
    fast = suite["lubricated_6000rpm"].metrics[ORBIT_METRIC]
    thin = suite["lubricated_thin_oil"].metrics[ORBIT_METRIC]
    assert 0.3 < fast < 1.0
    assert 0.75 < thin < 1.0


def test_shooting_finds_the_undamped_periodic_response(suite: dict[str, CheckRow]) -> None:
    # zero damping, tabulated pressure, constant speed: revolutions cannot settle it,
    # shooting does; no dissipation, so drive work = gas work almost exactly
    row = suite["bearings_undamped_tabulated"]
    assert row.outcome == "converged"
    assert row.drive_closure is not None and row.drive_closure < 1e-5


def test_shooting_finds_the_coupled_undamped_periodic_response(
    suite: dict[str, CheckRow],
) -> None:
    # zero damping on the coupled scene: revolution iteration cannot settle the free
    # vibration ('auto' hands over to shooting after revolutions stall); the periodic
    # response closes mass and energy as tightly as a damped case (1e-4: ten times the
    # damped cases' typical 1e-5, the cycle tolerance) and, with no bearing dissipation,
    # the drive work equals the gas work
    row = suite["bearings_undamped"]
    assert row.outcome == "converged" and row.finite
    assert row.revolutions is not None and row.revolutions > 20  # not by revolutions alone
    assert row.mass_closure is not None and row.mass_closure < 1e-4
    assert row.energy_closure is not None and row.energy_closure < 1e-4
    assert row.drive_closure is not None and row.drive_closure < 1e-5


def test_refusals_name_the_key(suite: dict[str, CheckRow]) -> None:
    wet = suite["wet_suction"]
    assert wet.outcome == "refused"
    assert "operating_point.suction_temperature" in wet.message and "dome" in wet.message


def test_near_zero_delivery_closes_its_balances_on_the_suction_mass(
    suite: dict[str, CheckRow],
) -> None:
    # the summary's closures divide the imbalance by the suction mass, the volumetric
    # efficiency (1.8 %) times the swept mass, the check's by the swept mass: the two
    # differ by that factor (to the suction back-flow). Both are below 1e-3 because the
    # cycle residual includes the closures (solve/residual.py): revolution iteration
    # stopped at a state change of 4.7e-5 left a mass closure of 2.0e-3 here.
    row = suite["near_zero_delivery"]
    assert row.volumetric_efficiency is not None and row.volumetric_efficiency < 0.03
    assert row.mass_balance_residual is not None and row.mass_closure is not None
    assert row.energy_balance_residual is not None
    assert abs(row.mass_balance_residual) < 1e-3
    assert abs(row.energy_balance_residual) < 1e-3
    ratio = row.mass_closure / abs(row.mass_balance_residual)
    assert ratio == pytest.approx(row.volumetric_efficiency, rel=0.1)


def test_soft_reed_flutters_and_stiff_bearings_reach_the_rigid_limit(
    suite: dict[str, CheckRow],
) -> None:
    assert suite["soft_suction_reed_flutter"].metrics["suction_reed_openings"] >= 4
    # bearings 1000x stiffer than the reference: the flexible crank train's volumetric
    # efficiency within 1e-3 of the rigid crank's (pinned run of the same case); the
    # reference bearings move it by 6 % (the crank train's compliance adds clearance)
    from recipsim.case.load import load_case
    from recipsim.pipeline import simulate_case

    rigid = simulate_case(
        load_case(HARD / "bearings_stiff_x1000.toml", ["options.mechanics=pinned"])
    )
    ve_rigid = rigid.row["volumetric_efficiency [-]"]
    stiff = suite["bearings_stiff_x1000"].volumetric_efficiency
    assert stiff == pytest.approx(ve_rigid, rel=1e-3)


# ------------------------------------------------------------------ unit tests


def _hump(n: int, centre: float, width: float) -> np.ndarray:
    x = np.arange(n) / n
    return np.clip(1.0 - ((x - centre) / width) ** 2, 0.0, None)


def test_reed_openings_counts_with_hysteresis() -> None:
    stop = 1.0
    n = 720
    one = 0.9 * _hump(n, 0.3, 0.15)
    assert reed_openings(np.zeros(n), stop) == 0
    assert reed_openings(one, stop) == 1
    # open across the end of the revolution: still one opening (periodic)
    assert reed_openings(np.roll(one, n // 2 + 50), stop) == 1
    two_humps = 0.9 * (_hump(n, 0.25, 0.08) + _hump(n, 0.45, 0.08))
    assert reed_openings(two_humps, stop) == 2
    # a dip to 5 % of the stop (between the 2 % close and 10 % open thresholds) is not
    # a closure; a dip to 1 % is
    dip = one.copy()
    dip[200:206] = 0.05
    assert reed_openings(dip, stop) == 1
    dip[200:206] = 0.01
    assert reed_openings(dip, stop) == 2


def _row(**kw: object) -> CheckRow:
    base: dict[str, object] = dict(
        case="c",
        file="c.toml",
        expected="converged",
        outcome="converged",
        mass_closure=1e-5,
        energy_closure=1e-5,
        drive_closure=1e-9,
    )
    base.update(kw)
    return CheckRow(**base)  # type: ignore[arg-type]


def test_judge() -> None:
    conv = Expectation()
    assert judge(_row(), conv) == (True, "")
    ok, note = judge(_row(mass_closure=2e-3), conv)
    assert not ok and "mass closure" in note
    assert not judge(_row(energy_closure=math.nan), conv)[0]  # NaN closure fails
    assert judge(_row(mass_closure=None, energy_closure=None), conv)[0]  # not applicable
    assert not judge(_row(non_finite=("COP [-]",)), conv)[0]
    ok, note = judge(_row(outcome="not_converged"), conv)
    assert not ok and "expected converged" in note
    # an unconverged run expected so: closures are not required, finiteness is
    nc = Expectation(expected="not_converged")
    assert judge(_row(outcome="not_converged", mass_closure=0.1), nc)[0]
    assert not judge(_row(outcome="not_converged", non_finite=("x",)), nc)[0]
    assert not judge(_row(), nc)[0]  # converging when it should not is reported too
    refused = Expectation(expected="refused", message=r"suction_temperature: .*dome")
    msg = "f.toml: operating_point.suction_temperature: 249 K is inside the two-phase dome"
    assert judge(_row(outcome="refused", message=msg), refused)[0]
    ok, note = judge(_row(outcome="refused", message="f.toml: geometry.bore: bad"), refused)
    assert not ok and "does not match" in note
    flutter = Expectation(minimum={"suction_reed_openings": 4})
    assert judge(_row(metrics={"suction_reed_openings": 4.0}), flutter)[0]
    assert not judge(_row(metrics={"suction_reed_openings": 3.0}), flutter)[0]
    assert not judge(_row(), flutter)[0]  # metric missing
    # a journal at its sleeve fails whatever the expectation (issue 15: orbits inside)
    assert judge(_row(metrics={ORBIT_METRIC: 0.95}), conv)[0]
    ok, note = judge(_row(metrics={ORBIT_METRIC: 1.0}), conv)
    assert not ok and "left its clearance" in note
    assert not judge(_row(outcome="not_converged", metrics={ORBIT_METRIC: 1.2}), nc)[0]


def _write(directory: Path, name: str, text: str) -> Path:
    path = directory / name
    path.write_text(text)
    return path


def test_expectations_file_is_validated(tmp_path: Path) -> None:
    _write(tmp_path, "a.toml", "")
    path = _write(
        tmp_path,
        "expectations.toml",
        '[defaults]\nfast = ["solver.max_step=\\"1 deg\\""]\n'
        '[cases.a]\nexpected = "refused"\nfast = ["solver.rtol=1e-6"]\n',
    )
    default, cases = load_expectations(path)
    assert cases["a"].expected == "refused"
    # fast overrides accumulate: built-in, defaults, then the case's own (last wins)
    assert cases["a"].fast[-2:] == ('solver.max_step="1 deg"', "solver.rtol=1e-6")
    assert default.fast[-1] == 'solver.max_step="1 deg"'
    for body, key in (
        ('[cases.a]\nexpected = "passed"\n', "cases.a.expected"),
        ("[cases.a]\nmass_tol = 1e-3\n", "cases.a.mass_tol"),
        ("[cases.b]\n", "cases.b"),
        ("[cases.a]\nminimum = { openings = 2 }\n", "cases.a.minimum.openings"),
        ('[cases.a]\nmessage = "("\n', "cases.a.message"),
    ):
        path.write_text(body)
        with pytest.raises(CaseError, match=re.escape(key)):
            load_expectations(path)


def test_find_cases_refuses_missing_paths(tmp_path: Path) -> None:
    with pytest.raises(CaseError, match="no such case file"):
        find_cases([tmp_path / "nothing"])
    with pytest.raises(CaseError, match="no case files"):
        find_cases([tmp_path])


def test_table_and_csv(tmp_path: Path) -> None:
    rows = [
        _row(case="good", revolutions=6, wall_time=0.25, solve_time=0.2, matches=True),
        _row(
            case="bad",
            outcome="refused",
            message="bad.toml: geometry.bore: out of range",
            file="bad.toml",
            mass_closure=None,
            energy_closure=None,
            drive_closure=None,
            matches=False,
            note="expected converged",
        ),
    ]
    table = format_table(rows)
    lines = table.splitlines()
    assert lines[0].split()[:3] == ["case", "expected", "outcome"]
    assert re.search(r"^good\s+converged\s+converged\s+yes\s+6\s+0\.25", table, re.M)
    assert re.search(
        r"^bad .*NO .*expected converged \(geometry\.bore: out of range\)", table, re.M
    )
    assert lines[-1] == "1 of 2 cases as expected"
    path = write_check_csv(rows, tmp_path / "out")
    frame = pd.read_csv(path)
    assert list(frame["case"]) == ["good", "bad"]
    assert {"mass_closure [-]", "energy_closure [-]", "wall_time [s]", "matches"} <= set(
        frame.columns
    )
    assert not list((tmp_path / "out").glob(".*tmp"))  # nothing left of the atomic write


def test_cli_exit_status_follows_the_expectations(tmp_path: Path) -> None:
    # two refused cases (nothing integrated): as expected -> 0; expected to converge -> 1
    base = REFERENCE.as_posix()
    wet = f'extends = "{base}"\n[operating_point]\nsuction_temperature = "-40 degC"\n'
    _write(tmp_path, "wet.toml", wet)
    _write(tmp_path, "typo.toml", f'extends = "{base}"\n[geometry]\nbroe = "22 mm"\n')
    expectations = _write(
        tmp_path,
        "expectations.toml",
        '[cases.wet]\nexpected = "refused"\nmessage = "two-phase dome"\n'
        '[cases.typo]\nexpected = "refused"\nmessage = "geometry\\\\.broe: unknown key"\n',
    )
    out = tmp_path / "out"
    assert main(["check", str(tmp_path), "--out", str(out), "--quiet"]) == 0
    written = out / tmp_path.name / "check.csv"  # --out is the parent of <folder name>/
    assert pd.read_csv(written)["matches"].all()
    expectations.write_text('[cases.typo]\nexpected = "refused"\n')  # wet: default converged
    assert main(["check", str(tmp_path), "--out", str(out), "--quiet"]) == 1
    frame = pd.read_csv(written).set_index("case")
    assert not frame.loc["wet", "matches"] and frame.loc["typo", "matches"]
    assert main(["check", str(tmp_path / "missing"), "--out", str(out)]) == 2


def test_a_failing_case_is_a_row(monkeypatch: pytest.MonkeyPatch) -> None:
    # a solver failure and an internal error both become "failed" rows, never exceptions
    import recipsim.studies.check.judge as judge
    from recipsim.errors import SolverError
    from recipsim.studies.check.judge import check_case

    def solver_failure(case: object) -> None:
        raise SolverError("integration failed at crank angle 12.000 deg: state ...")

    def bug(case: object) -> None:
        raise ZeroDivisionError("float division by zero")

    expect_failure = Expectation(expected="failed", message=r"crank angle \d+")
    monkeypatch.setattr(judge, "simulate_case", solver_failure)
    row = check_case(REFERENCE, expect_failure)
    assert (row.outcome, row.matches) == ("failed", True)
    monkeypatch.setattr(judge, "simulate_case", bug)
    row = check_case(REFERENCE, Expectation())
    assert row.outcome == "failed" and not row.matches
    assert row.message.startswith("internal error ZeroDivisionError")
