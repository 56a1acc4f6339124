"""``recipsim sweep``: failures recorded, resume after a kill, Dask = process pool, trends.

Each test runs a small sweep written to ``tmp_path`` (the trends test runs the shipped
LBP map, 48 points). Tables are compared without the timing columns, which are the
only ones that may differ from run to run.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest

from helpers import CASES, REFERENCE, ROOT, solve_case, stored_points
from recipsim.cli.main import main
from recipsim.errors import RecipsimError
from recipsim.results.tables import summary
from recipsim.studies.sweep.engine import TIMING_COLUMNS, SweepInterrupted, run_sweep

EVAPORATING = "evaporating_temperature [K]"


def write(tmp_path: Path, body: str, name: str = "small") -> Path:
    path = tmp_path / f"{name}.toml"
    path.write_text(f'name = "{name}"\nbase = "{REFERENCE.as_posix()}"\n{body}')
    return path


def read_table(path: Path) -> pd.DataFrame:
    return pd.read_csv(path, keep_default_na=False, na_values=[""])


def comparable(table: pd.DataFrame) -> pd.DataFrame:
    return table.drop(columns=[c for c in TIMING_COLUMNS if c in table]).reset_index(drop=True)


def test_failed_points_are_recorded_and_the_others_finish(tmp_path, capsys):
    sweep = write(
        tmp_path,
        """
[axes]
solver.max_revolutions = [2, 60]
operating_point.evaporating_temperature = ["-30 degC", "70 degC"]
""",
    )
    out = tmp_path / "out"
    argv = ["sweep", str(sweep), "--out", str(out), "--jobs", "2", "--parquet", "--reports"]
    argv += ["--no-plots"]
    status = main(argv)
    captured = capsys.readouterr()
    assert status == 1  # some point is not ok
    assert captured.err == ""  # no progress bar when standard error is not a terminal
    assert "4 points: 1 ok, 3 failed (2 invalid, 1 not_converged)" in captured.out

    table = read_table(out / "small" / "summary.csv")
    assert list(table["point"]) == [0, 1, 2, 3]
    assert list(table["max_revolutions [-]"]) == [2, 2, 60, 60]
    assert list(table["status"]) == ["not_converged", "invalid", "ok", "invalid"]
    invalid = table[table["status"] == "invalid"]
    assert all("operating_point.condensing_temperature" in m for m in invalid["message"])
    assert all("must be above the evaporating temperature" in m for m in invalid["message"])
    assert invalid["cooling_capacity [W]"].isna().all()
    assert "not converged after 2 revolutions" in table.loc[0, "message"]
    assert table.loc[0, "revolutions [-]"] == 2

    # the ok point holds the real solution of that case, to the last digit
    ok = table.loc[2]
    assert pd.isna(ok["message"])
    direct = summary(
        solve_case(
            REFERENCE,
            ["solver.max_revolutions=60", 'operating_point.evaporating_temperature="-30 degC"'],
        )
    )
    for column in ("cooling_capacity [W]", "shaft_power [W]", "COP [-]", "revolutions [-]"):
        assert ok[column] == direct[column], column
    assert ok["cooling_capacity [W]"] > 50.0
    assert ok[EVAPORATING] == pytest.approx(243.15, abs=1e-9)

    # one record per finished point, per-point report for the solved ones, Parquet = CSV
    root = out / "small"
    assert len(stored_points(root / "points")) == 4
    assert (root / "reports" / ok["point_id"] / "summary.csv").is_file()
    assert (root / "reports" / table.loc[0, "point_id"] / "cycle.csv").is_file()
    meta = json.loads((root / "provenance.json").read_text())
    assert meta["points"] == 4 and meta["status_counts"] == {
        "not_converged": 1,
        "invalid": 2,
        "ok": 1,
    }

    # rerun: recorded failures are kept, nothing is computed; --retry-failed redoes them
    again = run_sweep(sweep, out=out, jobs=1, plots=False)
    assert again.computed == [] and len(again.reused) == 4
    parquet = pd.read_parquet(root / "summary.parquet")
    pd.testing.assert_frame_equal(parquet, again.table)
    # summary.csv is the table: invalid points' empty cells, a message column with gaps
    assert (root / "summary.csv").read_text(encoding="utf-8") == again.table.to_csv(index=False)
    retry = run_sweep(sweep, out=out, jobs=1, plots=False, retry_failed=True)
    assert sorted(retry.computed) == sorted(table.loc[[0, 1, 3], "point_id"])
    pd.testing.assert_frame_equal(comparable(retry.table), comparable(again.table))


def _failing_solver(monkeypatch, how: dict[float, str]) -> None:
    """Make the solver fail for chosen evaporating temperatures [K] (inherited by forks)."""
    import recipsim.pipeline as pipeline
    from recipsim.errors import SolverError

    real = pipeline.solve_periodic

    def solve(model):
        t_evap = round(model.case.operating_point.evaporating_temperature, 6)
        if how.get(t_evap) == "solver":
            raise SolverError("step size underflow at crank angle 12.3 deg (test)")
        if how.get(t_evap) == "bug":
            raise KeyError("a missing key (test)")
        if how.get(t_evap) == "arithmetic":  # a library's error: failed, with its stage
            raise ZeroDivisionError("division by zero (test)")
        if how.get(t_evap) == "kill":
            os.kill(os.getpid(), signal.SIGKILL)
        if how.get(t_evap) == "interrupt":  # Ctrl-C while this point is being solved
            os.kill(os.getpid(), signal.SIGINT)
        return real(model)

    monkeypatch.setattr(pipeline, "solve_periodic", solve)


def test_point_warnings_go_to_the_message_column_not_the_log(tmp_path, capsys, caplog):
    """A point whose discharge reed lets more than 3 % flow back (the soft reed of
    tests/physics/test_valves.py) keeps its warning in its ``message`` (status still
    ``ok``) instead of logging a line per point; the closing lines count such points.
    The same in the worker processes (``--jobs 2``) as in-process, and ``recipsim run``
    of one case still logs it."""
    import logging

    soft = [
        'valves.discharge.reed_thickness = "0.153 mm"',
        'valves.discharge.reed_length = "18 mm"',
        'valves.discharge.port_position = "14 mm"',
        'valves.discharge.stop_height = "1.8 mm"',
    ]
    sweep = write(
        tmp_path,
        "[set]\n" + "\n".join(soft) + "\n[axes]\n"
        'operating_point.evaporating_temperature = ["-30 degC", "-20 degC"]\n',
    )
    tables = []
    for jobs in ("1", "2"):
        out = tmp_path / f"out{jobs}"
        with caplog.at_level(logging.WARNING, logger="recipsim"):
            status = main(["sweep", str(sweep), "--out", str(out), "--jobs", jobs, "--no-plots"])
        assert status == 0
        assert not [r for r in caplog.records if "flows back" in r.getMessage()]
        captured = capsys.readouterr()
        assert "flows back" not in captured.err
        assert "2 ok points with warnings (see the message column)" in captured.out
        table = read_table(out / "small" / "summary.csv")
        assert list(table["status"]) == ["ok", "ok"]
        for _, row in table.iterrows():
            fraction = row["discharge_backflow_fraction [-]"]
            assert fraction > 0.03
            assert (
                f"{fraction:.1%} of the gas through the discharge valve flows back"
                in (row["message"])
            )
        tables.append(comparable(table))
    pd.testing.assert_frame_equal(tables[0], tables[1])

    with caplog.at_level(logging.WARNING, logger="recipsim"):  # outside a sweep: logged
        summary_row = summary(solve_case(REFERENCE, [s.replace(" = ", "=") for s in soft]))
    assert summary_row["discharge_backflow_fraction [-]"] > 0.03
    assert [r for r in caplog.records if "flows back" in r.getMessage()]


def test_solver_failures_and_bugs_are_recorded_and_the_sweep_goes_on(tmp_path, monkeypatch):
    sweep = write(
        tmp_path,
        '[axes]\noperating_point.evaporating_temperature = ["-30 degC", "-25 degC", "-20 degC"]\n',
    )
    _failing_solver(monkeypatch, {243.15: "solver", 248.15: "bug", 253.15: "arithmetic"})
    outcome = run_sweep(sweep, out=tmp_path, jobs=1, plots=False)
    assert list(outcome.table["status"]) == ["failed", "error", "failed"]
    assert outcome.n_ok == 0 and outcome.n_failed == 3
    messages = list(outcome.table["message"])
    assert messages[0].endswith("step size underflow at crank angle 12.3 deg (test)")
    assert messages[1] == "KeyError: 'a missing key (test)'"
    # issue 18: no ZeroDivisionError (or CoolProp ValueError) escapes as 'error'
    assert messages[2] == (
        "ZeroDivisionError while integrating the periodic state: division by zero (test)"
    )


@pytest.mark.skipif(sys.platform != "linux", reason="the patched solver reaches forked workers")
def test_killed_worker_stops_the_sweep_and_a_rerun_resumes(tmp_path, monkeypatch, capsys):
    evaporating = ["-35 degC", "-30 degC", "-25 degC", "-20 degC", "-15 degC", "-10 degC"]
    sweep = write(
        tmp_path,
        f"[axes]\noperating_point.evaporating_temperature = {evaporating!r}\n".replace("'", '"'),
    )
    _failing_solver(monkeypatch, {263.15: "kill"})  # the last point kills its worker
    status = main(["sweep", str(sweep), "--out", str(tmp_path), "--jobs", "2", "--no-plots"])
    assert status == 1
    err = capsys.readouterr().err
    assert "a worker process died" in err and "to resume" in err
    finished = stored_points(tmp_path / "small" / "points")
    assert 1 <= len(finished) < 6
    assert not (tmp_path / "small" / "summary.csv").exists()
    monkeypatch.undo()
    resumed = run_sweep(sweep, out=tmp_path, jobs=2, plots=False)
    assert sorted(resumed.reused) == sorted(finished)
    assert len(resumed.computed) == 6 - len(finished)
    assert list(resumed.table["status"]) == ["ok"] * 6


def test_ctrl_c_in_process_finishes_the_point_then_stops(tmp_path, monkeypatch):
    sweep = write(
        tmp_path,
        '[axes]\noperating_point.evaporating_temperature = ["-30 degC", "-25 degC", "-20 degC"]\n',
    )
    _failing_solver(monkeypatch, {248.15: "interrupt"})
    with pytest.raises(SweepInterrupted, match="2 of 3 points are finished"):
        run_sweep(sweep, out=tmp_path / "a", jobs=1, plots=False)
    monkeypatch.undo()
    resumed = run_sweep(sweep, out=tmp_path / "a", jobs=1, plots=False)
    assert len(resumed.reused) == 2 and len(resumed.computed) == 1
    clean = run_sweep(sweep, out=tmp_path / "b", jobs=1, plots=False)
    pd.testing.assert_frame_equal(comparable(resumed.table), comparable(clean.table))


def test_parquet_without_pyarrow_is_a_clear_error(tmp_path, monkeypatch):
    sweep = write(tmp_path, '[axes]\nrefrigerant = ["R134a"]\n')
    monkeypatch.setitem(sys.modules, "pyarrow", None)
    with pytest.raises(RecipsimError, match="pip install pyarrow"):
        run_sweep(sweep, out=tmp_path / "out", jobs=1, parquet=True)
    assert not (tmp_path / "out").exists()  # checked before anything is computed


def test_killed_sweep_resumes_with_only_the_missing_points(tmp_path):
    body = """
[set]
solver.min_revolutions = 12
[axes]
operating_point.condensing_temperature = ["45 degC", "55 degC"]
operating_point.evaporating_temperature = [
    "-35 degC", "-30 degC", "-25 degC", "-20 degC", "-15 degC", "-10 degC", "-5 degC",
]
"""
    sweep = write(tmp_path, body, "killed")
    out = tmp_path / "out"
    points = out / "killed" / "points"
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT / "src"), env.get("PYTHONPATH")]))
    cmd = [sys.executable, "-m", "recipsim.cli.main", "sweep", str(sweep), "--out", str(out)]
    proc = subprocess.Popen(
        [*cmd, "--jobs", "2", "--quiet", "--no-plots"],
        env=env,
        start_new_session=True,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
    )
    deadline = time.monotonic() + 60.0
    try:
        while len(stored_points(points)) < 3:
            assert proc.poll() is None, proc.stderr.read() if proc.stderr else ""
            assert time.monotonic() < deadline, "no point finished within 60 s"
            time.sleep(0.005)
    finally:
        os.killpg(proc.pid, signal.SIGKILL)  # the sweep and its workers, no clean-up
        proc.wait()
    before = stored_points(points)
    assert 3 <= len(before) < 14, "the kill did not land midway"

    resumed = run_sweep(sweep, out=out, jobs=2, plots=False)
    assert sorted(resumed.reused) == sorted(before)
    assert sorted(resumed.computed) == sorted(set(resumed.table["point_id"]) - set(before))
    after = stored_points(points)
    assert len(after) == 14
    assert {k: after[k] for k in before} == before  # finished points kept, not rewritten
    assert list(resumed.table["status"]) == ["ok"] * 14

    fresh = run_sweep(sweep, out=tmp_path / "uninterrupted", jobs=1, plots=False)
    assert len(fresh.computed) == 14
    pd.testing.assert_frame_equal(comparable(resumed.table), comparable(fresh.table))
    pd.testing.assert_frame_equal(
        comparable(read_table(out / "killed" / "summary.csv")),
        comparable(read_table(tmp_path / "uninterrupted" / "killed" / "summary.csv")),
    )


def test_lbp_map_trends_are_physical(tmp_path):
    outcome = run_sweep(CASES / "sweeps" / "lbp_map.toml", out=tmp_path, jobs=2)
    table = outcome.table
    assert len(table) == 48
    statuses = set(table["status"])
    assert statuses <= {"ok", "not_converged"}, table[table["status"] != "ok"]["message"]
    groups = table.groupby(["refrigerant", "condensing_temperature [K]"])
    assert groups.ngroups == 8
    for (refrigerant, condensing), rows in groups:
        ok = rows[rows["status"] == "ok"].sort_values(EVAPORATING)
        assert len(ok) >= 5, (refrigerant, condensing)
        for column in ("cooling_capacity [W]", "COP [-]"):
            values = ok[column].to_numpy()
            assert (values[1:] > values[:-1]).all(), (refrigerant, condensing, column, values)
    # a higher condensing temperature costs capacity and COP at every evaporating point
    ok = table[table["status"] == "ok"]
    pivot = ok.pivot_table(
        index=["refrigerant", EVAPORATING], columns="condensing_temperature [K]", values="COP [-]"
    ).dropna()
    assert (pivot.iloc[:, 0] > pivot.iloc[:, 1]).all()
    for name in ("cooling_capacity", "shaft_power", "COP", "volumetric_efficiency"):
        assert (outcome.directory / f"map_{name}.png").stat().st_size > 10_000
    assert (outcome.directory / "map_isentropic_efficiency.png").is_file()


def test_dask_local_cluster_gives_the_process_pool_table(tmp_path):
    import distributed  # a test dependency (pyproject [test]): this test must run in CI

    sweep = write(
        tmp_path,
        """
[axes]
refrigerant = ["R134a", "R290"]
operating_point.evaporating_temperature = ["-30 degC", "-20 degC", "80 degC"]
""",
        "dask",
    )
    # the local pool first: its workers are forked before Dask starts any thread here
    local = run_sweep(sweep, out=tmp_path / "pool", jobs=2, plots=False)
    with distributed.LocalCluster(
        n_workers=2,
        threads_per_worker=1,
        processes=True,
        host="127.0.0.1",
        dashboard_address=None,
    ) as cluster:
        remote = run_sweep(
            sweep, out=tmp_path / "dask", scheduler=cluster.scheduler_address, plots=False
        )
    assert len(remote.computed) == 6 and remote.scheduler == cluster.scheduler_address
    assert list(remote.table["status"]) == ["ok", "ok", "invalid"] * 2
    pd.testing.assert_frame_equal(comparable(remote.table), comparable(local.table))
    pd.testing.assert_frame_equal(
        comparable(read_table(tmp_path / "dask" / "dask" / "summary.csv")),
        comparable(read_table(tmp_path / "pool" / "dask" / "summary.csv")),
    )


def test_unreachable_scheduler_is_a_clear_error(tmp_path):
    from recipsim.studies.sweep.dask_runner import run_dask

    with pytest.raises(RecipsimError, match="cannot reach the Dask scheduler"):
        run_dask([], "tcp://127.0.0.1:9", lambda task, result: None, connect_timeout=0.5)
