"""``recipsim bench-system``: the overhead model and its extrapolation (closed forms),
and one run of the stages of ``recipsim run`` in a child interpreter."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from recipsim.cli.bench_system import format_system
from recipsim.studies.bench.system_time import extrapolate, measure_run_stages, overhead_model


def test_overhead_model_recovers_serial_and_parallel_parts() -> None:
    """Times made by T(J) = 3 + 8 / J give S = 3 s and P = 8 s back (to rounding)."""
    walls = {1: 3.0 + 8.0, 2: 3.0 + 4.0, 4: 3.0 + 2.0}
    model = overhead_model(walls)
    assert model["serial [s]"] == pytest.approx(3.0, abs=1e-12)
    assert model["parallel [s]"] == pytest.approx(8.0, abs=1e-12)
    assert overhead_model({2: 5.0}) == {}


def test_extrapolation_is_amdahls_law() -> None:
    """Efficiency at J workers = (S + P) / (J (S + P / J)); 10x points scale P only."""
    model = {"serial [s]": 1.0, "parallel [s]": 9.0}
    at16 = extrapolate(model, 16)
    assert at16["wall [s]"] == pytest.approx(1.0 + 9.0 / 16)
    assert at16["efficiency [-]"] == pytest.approx(10.0 / (16 * (1.0 + 9.0 / 16)))
    big = extrapolate(model, 16, 10.0)
    assert big["efficiency [-]"] == pytest.approx(91.0 / (16 * (1.0 + 90.0 / 16)))
    assert extrapolate(model, 1)["efficiency [-]"] == pytest.approx(1.0)


def test_run_stages_cover_the_command() -> None:
    """Every stage of the run path is timed, wall and CPU, each figure on its own."""
    result = measure_run_stages("reference_r134a_lbp", [], repeats=1)
    stages = result["stages"]
    for name in ("import", "case_loading", "model_build", "solve_first", "tables"):
        assert stages[name]["wall [s]"] >= 0.0 and stages[name]["cpu [s]"] >= 0.0
    assert {f"figure_{n}" for n in ("p_V", "torque", "valves", "bearing_loads")} <= set(stages)
    assert "numba_cache_load" in stages
    # the real command's phases, from its timeline: the parent's in order, and the report
    # process that wrote the tables and drew the figures meanwhile
    for label in ("with_figures", "no_plots"):
        parent = result["phases"][label]["parent"]
        assert list(parent)[0] == "imports" and list(parent)[-1] == "exit"
        assert {"numba started", "case loaded", "solved", "report renamed into place"} <= set(
            parent
        )
        assert list(parent.values()) == sorted(parent.values())
        assert parent["exit"] == pytest.approx(result["run"][label]["wall [s]"])
        if hasattr(os, "fork"):
            child = result["phases"][label]["report process"]
            assert child["job done"] <= parent["report processes done"]
    text = format_system({"machine": {"load_average": [0, 0, 0]}, "run": result})
    assert "recipsim run, with_figures" in text
    assert "recipsim run, no_plots: phase ends" in text


def test_warmup_refuses_an_unknown_refrigerant(capsys: pytest.CaptureFixture[str]) -> None:
    from recipsim.cli.main import main

    assert main(["warmup", "--refrigerants", "R134a,R999", "--quiet"]) == 2
    assert "unknown refrigerant 'R999'" in capsys.readouterr().err


def test_warmup_solves_one_revolution_of_each_case(capsys: pytest.CaptureFixture[str]) -> None:
    from recipsim.cli.main import main

    assert main(["warmup", "reference_r134a_lbp", "--refrigerants", "R134a"]) == 0
    err = capsys.readouterr().err
    assert "property table of R134a ready" in err
    assert "reference_r134a_lbp: solver compiled for its scene (pinned crank" in err
    # its solver.method "dopri5_stiff" hands over to the W-step where a stretch turns
    # stiff: warmup compiles that entry too, which one revolution need not reach
    assert "with the Rosenbrock-W step" in err
    from recipsim.solve import scene_entries

    assert scene_entries.ENTRY_SIGNATURE in scene_entries.integrate_cylinder_w.signatures


def test_both_overhead_ratios_are_printed() -> None:
    """End to end and after start-up, each with its definition's inputs."""
    after = {
        "no_plots": {"wall [s]": 1.5, "cpu [s]": 1.5, "solve_sum [s]": 0.6},
        "with_plots": {"wall [s]": 2.1, "cpu [s]": 2.1, "solve_sum [s]": 0.6},
    }
    for t in after.values():
        t["overhead_ratio [-]"] = (t["wall [s]"] - t["solve_sum [s]"]) / t["solve_sum [s]"]
    result = {
        "machine": {"load_average": [0, 0, 0]},
        "run": {"stages": {}, "run": {}},
        "map": {
            "sweep": "s",
            "points": 100,
            "solve_sum [s]": 0.6,
            "runs": {"1": {"wall [s]": 3.0, "cpu [s]": 3.0, "efficiency [-]": 1.0}},
            "overhead_ratio [-]": 4.0,
            "model": {},
            "after_startup": after,
        },
    }
    text = format_system(result)
    assert "overhead / solves (1 worker, end to end): 4.00" in text
    assert "after start-up, no_plots): 1.50 (1.50 s, solves 0.60 s)" in text
    assert "after start-up, with_plots): 2.50 (2.10 s, solves 0.60 s)" in text


def test_system_timing_keeps_a_sweep_with_failed_points():
    """``recipsim sweep`` exits 1 when points failed (they are rows of the map, timed like
    the others); any other failure, or a sweep that stopped with an error message, is
    reported with its status and last line instead of a bare CalledProcessError."""
    import sys

    from recipsim.errors import RecipsimError
    from recipsim.studies.bench.system_time import _timed

    failed_points = [sys.executable, "-c", "import sys; print('7 points: 1 failed'); sys.exit(1)"]
    wall, cpu, out = _timed(failed_points, sweep=True)
    assert wall > 0.0 and cpu >= 0.0 and "1 failed" in out
    with pytest.raises(RecipsimError, match="exited with 1"):
        _timed(failed_points)
    lost = [
        sys.executable,
        "-c",
        "import sys; sys.stderr.write('recipsim: worker lost\\n'); sys.exit(1)",
    ]
    with pytest.raises(RecipsimError, match="worker lost"):
        _timed(lost, sweep=True)


def test_worker_counts_of_bench_system() -> None:
    """``--jobs J`` is 1..J; a list is taken as given (sorted, each once); anything else
    is refused with the allowed forms."""
    import argparse

    from recipsim.cli.options import worker_counts

    assert worker_counts("3") == [1, 2, 3]
    assert worker_counts("16,1,4,2,8,4") == [1, 2, 4, 8, 16]
    for bad in ("0", "1,x", "", "2,-1"):
        with pytest.raises(argparse.ArgumentTypeError, match="comma-separated"):
            worker_counts(bad)


def test_scaling_after_start_up_measures_each_worker_count(tmp_path) -> None:
    """A 6-point sweep on 1 and 2 workers inside one started interpreter: every point
    solved in each run, efficiency T(1) / (J T(J)) with T(1) as its own reference."""
    from helpers import REFERENCE
    from recipsim.studies.bench.map_scaling import measure_map_scaling

    sweep = tmp_path / "tiny.toml"
    sweep.write_text(
        f'name = "tiny"\nbase = "{REFERENCE.as_posix()}"\n[axes]\n'
        'operating_point.evaporating_temperature = ["-30 degC", "-25 degC", "-20 degC"]\n'
        'operating_point.shaft_speed = ["3000 rpm", "3500 rpm"]\n'
    )
    result = measure_map_scaling(str(sweep), [1, 2])
    assert result["points"] == 6
    one, two = result["runs"]["1"], result["runs"]["2"]
    assert one["ok"] == two["ok"] == 6
    assert one["efficiency [-]"] == 1.0
    assert two["efficiency [-]"] == pytest.approx(one["wall [s]"] / (2 * two["wall [s]"]))
    assert two["points_per_second"] == pytest.approx(6 / two["wall [s]"])
    # the solves' own slow-down with more workers, and the efficiency it alone allows
    assert one["solve_slowdown [-]"] == one["efficiency_ceiling [-]"] == 1.0
    slowdown = two["solve_sum [s]"] / one["solve_sum [s]"]
    assert two["solve_slowdown [-]"] == pytest.approx(slowdown)
    assert two["efficiency_ceiling [-]"] == pytest.approx(1.0 / slowdown)


def test_timed_runs_write_into_the_scratch_directory_then_it_is_removed(tmp_path) -> None:
    """Inside scratch_directory this process's temporary files and those of the
    commands it starts (TMPDIR) go under the scratch directory; afterwards the
    environment is as before and the scratch directory is gone."""
    import subprocess
    import sys
    import tempfile

    from recipsim.cli.bench_system import scratch_directory

    scratch = tmp_path / "out" / "system" / "scratch"
    before = os.environ.get("TMPDIR"), tempfile.gettempdir()
    with scratch_directory(scratch) as work:
        assert work.parent == scratch
        with tempfile.TemporaryDirectory() as inside:
            assert Path(inside).parent == work
        child = subprocess.run(
            [sys.executable, "-c", "import tempfile; print(tempfile.gettempdir())"],
            capture_output=True,
            text=True,
            check=True,
        )
        assert Path(child.stdout.strip()) == work
        (work / "left-over.json").write_text("{}")  # a run's files are removed too
    assert (os.environ.get("TMPDIR"), tempfile.gettempdir()) == before
    assert not scratch.exists()
