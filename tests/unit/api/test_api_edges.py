"""The Python API at its edges: a wrong argument is a CaseError naming the function and
the argument, never a TypeError, AttributeError or a silent misreading (a string axis
swept character by character); an unusable cache directory costs a warning, not the
run; Ctrl-C ends a command with one line and exit status 130; a fitted parameter whose
lower bound is zero or below is written back into the case."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import recipsim
from helpers import REFERENCE
from recipsim.case.overrides import override, parse_override
from recipsim.errors import CaseError


@pytest.fixture(scope="module")
def case() -> recipsim.Case:
    return recipsim.load_case(REFERENCE)


@pytest.mark.parametrize(
    ("axes", "words"),
    [
        ({"operating_point.shaft_speed": "3000 rpm"}, "a list of values"),
        ({"operating_point.shaft_speed": []}, "at least one value"),
        ({"operating_point.shaft_speed": [[3000, 3500]]}, "not a number, text or boolean"),
        ({"operating_point.shaft_speed": [{"a": 1}]}, "not a number, text or boolean"),
        ({}, "non-empty mapping"),
        ([("operating_point.shaft_speed", [1.0])], "non-empty mapping"),
    ],
)
def test_a_malformed_sweep_axis_is_a_case_error(case, axes, words) -> None:
    with pytest.raises(CaseError, match=words) as info:
        recipsim.sweep(case, axes)
    assert info.value.file == "recipsim.sweep"


@pytest.mark.parametrize("jobs", [0, -3, 1.5, True, "2"])
def test_jobs_must_be_a_whole_number_of_workers(case, jobs) -> None:
    with pytest.raises(CaseError, match="jobs"):
        recipsim.sweep(case, {"operating_point.shaft_speed": ["3000 rpm"]}, jobs=jobs)


@pytest.mark.parametrize("function", ["simulate", "sweep", "calibrate"])
def test_a_name_where_a_case_is_due_is_a_case_error(function) -> None:
    call = {
        "simulate": lambda: recipsim.simulate("reference_r134a_lbp"),
        "sweep": lambda: recipsim.sweep("reference_r134a_lbp", {"a.b": [1]}),
        "calibrate": lambda: recipsim.calibrate("reference_r134a_lbp", "x.csv", ["a.b"]),
    }[function]
    with pytest.raises(CaseError, match="expected a Case") as info:
        call()
    assert info.value.file == f"recipsim.{function}" and info.value.key == "case"


def test_a_missing_calibration_file_is_a_case_error(case, tmp_path: Path) -> None:
    with pytest.raises(CaseError, match="no such"):
        recipsim.calibrate(case, tmp_path / "missing.csv", ["valves.suction.preload"])


@settings(max_examples=60, deadline=None)
@given(
    st.one_of(
        st.text(max_size=8),
        st.lists(st.one_of(st.none(), st.lists(st.integers(), max_size=2)), max_size=3),
        st.dictionaries(st.text(max_size=3), st.integers(), max_size=2),
        st.integers(),
    )
)
def test_any_malformed_axis_is_refused_before_anything_runs(case, values) -> None:
    with pytest.raises(CaseError):
        recipsim.sweep(case, {"operating_point.shaft_speed": values})


@pytest.mark.parametrize("value", [np.float64(0.0), np.float64(-0.25), np.int64(3), np.bool_(1)])
def test_numpy_scalars_are_written_back_as_overrides(value) -> None:
    """A fit's parameters are numpy scalars (a lower bound of 0 keeps them linear)."""
    text = override("thermal.direct_suction_fraction", value)
    assert parse_override(text)[1] == value


def test_an_unusable_cache_directory_is_a_warning_not_a_failure(tmp_path: Path) -> None:
    blocker = tmp_path / "a-file"
    blocker.write_text("not a directory")
    command = [sys.executable, "-m", "recipsim", "run", str(REFERENCE), "--no-plots", "--quiet"]
    command += ["--set", "solver.max_revolutions=2", "--out", str(tmp_path / "out")]
    env = {**os.environ, "RECIPSIM_CACHE": str(blocker)}
    out = subprocess.run(command, env=env, capture_output=True, text=True, timeout=600)
    assert out.returncode in (0, 1), out.stderr  # 1: not converged in 2 revolutions
    assert "Traceback" not in out.stderr
    warnings = [line for line in out.stderr.splitlines() if "warning" in line]
    assert warnings and all(line.startswith("recipsim: warning: ") for line in warnings)
    assert (tmp_path / "out").is_dir()


def test_ctrl_c_ends_a_command_with_one_line_and_130(monkeypatch, capsys, tmp_path) -> None:
    import importlib

    cli = importlib.import_module("recipsim.cli.main")  # the module, not its main()

    def interrupted(*args: object, **kwargs: object) -> None:
        raise KeyboardInterrupt

    monkeypatch.setattr(cli, "run_case", interrupted)
    assert cli.main(["run", str(REFERENCE), "--out", str(tmp_path)]) == 130
    err = capsys.readouterr().err.strip()
    assert err.startswith("recipsim: interrupted") and "\n" not in err
