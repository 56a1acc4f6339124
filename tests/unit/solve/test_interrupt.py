"""Ctrl-C takes effect within about a second even inside the compiled solve, which never
returns to Python on its own: the integrator asks the property callback every
``SIGNAL_CHECK_STEPS`` accepted steps, and the solve raises KeyboardInterrupt."""

from __future__ import annotations

import signal
import subprocess
import sys
import time

import pytest

from helpers import REFERENCE

_CHILD = f"""
import sys, time
from recipsim.case.load import load_case
from recipsim.solve.drive import build_model_for
from recipsim.solve.periodic import solve_periodic
case = load_case({str(REFERENCE)!r}, {{"solver.max_revolutions": 1, "solver.min_revolutions": 1}})
solve_periodic(build_model_for(case))  # compiled (or loaded from the cache) before timing
slow = case.with_({{"solver.max_step": "1e-6 rad"}})  # millions of steps a revolution
model = build_model_for(slow)
print("solving", flush=True)
start = time.perf_counter()
try:
    solve_periodic(model)
except KeyboardInterrupt:
    print("interrupted", flush=True)
    sys.exit(130)
print("finished", time.perf_counter() - start, flush=True)
"""


@pytest.mark.parametrize("properties", ["table", "heos"])
@pytest.mark.skipif(sys.platform == "win32", reason="SIGINT to a child process")
def test_ctrl_c_stops_a_long_compiled_solve_within_a_second(properties: str) -> None:
    child = _CHILD.replace('"solver.min_revolutions": 1}', '"solver.min_revolutions": 1, '
                           f'"options.properties": "{properties}"}}')  # fmt: skip
    proc = subprocess.Popen(
        [sys.executable, "-c", child], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    assert proc.stdout is not None
    assert proc.stdout.readline().strip() == "solving"
    time.sleep(1.0)  # well inside the solve (it takes a minute or more)
    sent = time.perf_counter()
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=60)
    waited = time.perf_counter() - sent
    assert proc.returncode == 130, err
    assert out.strip() == "interrupted"
    assert waited < 5.0  # about a second; generous for a loaded machine


def test_a_max_step_that_needs_too_many_steps_is_refused_with_an_estimate(capsys) -> None:
    """``solver.max_step = "1e-7 rad"`` (the smallest allowed) needs 62.8 million steps a
    revolution: refused before anything runs, one line, exit 1, naming the budget."""
    from recipsim.cli.main import main

    status = main(["run", str(REFERENCE), "--set", 'solver.max_step="1e-7 rad"', "--no-plots"])
    err = capsys.readouterr().err.strip().splitlines()[-1]
    assert status == 1
    assert "solver.max_step = 1e-07 rad needs at least 125,663,708 steps" in err
    assert "solver.step_budget = 20,000,000" in err and "h at" in err


def test_a_solve_over_its_step_budget_stops_between_revolutions() -> None:
    from recipsim.case.load import load_case
    from recipsim.errors import SolverError
    from recipsim.solve.drive import build_model_for
    from recipsim.solve.periodic import solve_periodic

    case = load_case(REFERENCE, {"solver.step_budget": 1000, "solver.cycle_tolerance": 1e-9})
    with pytest.raises(SolverError, match=r"over solver.step_budget = 1,000"):
        solve_periodic(build_model_for(case))
