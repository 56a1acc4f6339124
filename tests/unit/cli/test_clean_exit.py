"""A command ends cleanly: nothing on standard error after recipsim's own lines, and no
leak report from CoolProp's bindings (``nanobind: leaked ...``) when the property states
of a run on HEOS properties are released at the interpreter's exit."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from helpers import REFERENCE

_SHORT = ["--set", "solver.max_revolutions=2", "--set", "solver.min_revolutions=1"]


@pytest.mark.parametrize("properties", ["heos", "table"])
def test_a_run_exits_without_a_leak_report(tmp_path: Path, properties: str) -> None:
    command = [sys.executable, "-m", "recipsim", "run", str(REFERENCE), "--no-plots", "--quiet"]
    command += [*_SHORT, "--set", f"options.properties={properties}", "--out", str(tmp_path)]
    out = subprocess.run(command, capture_output=True, text=True, timeout=600, cwd=tmp_path)
    assert out.returncode in (0, 1), out.stderr  # 1: not converged in 2 revolutions
    assert "nanobind" not in out.stderr
    assert "leaked" not in out.stderr
    lines = [line for line in out.stderr.splitlines() if line.strip()]
    assert all(line.startswith("recipsim: ") for line in lines), out.stderr


def test_the_api_in_a_script_exits_without_a_leak_report(tmp_path: Path) -> None:
    script = (
        "import recipsim\n"
        f"case = recipsim.load_case({str(REFERENCE)!r}, {{'options.properties': 'heos',"
        " 'solver.max_revolutions': 2, 'solver.min_revolutions': 1})\n"
        "result = recipsim.simulate(case)\n"
        "print(result.summary['cooling_capacity [W]'] > 0)\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=600, cwd=tmp_path
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "True"
    assert "nanobind" not in out.stderr


@pytest.mark.parametrize("value", ["-5", "0", "two"])
def test_paper_refuses_a_count_of_revolutions_below_one(capsys, value: str) -> None:
    from recipsim.cli.main import main

    with pytest.raises(SystemExit) as info:
        main(["paper", "--undamped-revolutions", value])
    assert info.value.code == 2
    err = capsys.readouterr().err
    assert "--undamped-revolutions" in err and "Traceback" not in err
