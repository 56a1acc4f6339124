"""The first run's compiling child (:mod:`recipsim.results.compile_ahead`): started only
on a fresh numba cache, waited for before the solve, and it fills the cache with the
case's scene."""

from __future__ import annotations

import subprocess
import sys

import pytest

from recipsim.results import compile_ahead


@pytest.fixture
def fresh_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "numba"))
    monkeypatch.delenv("NUMBA_DISABLE_JIT", raising=False)
    monkeypatch.delenv("RECIPSIM_COMPILE_AHEAD", raising=False)
    monkeypatch.setattr(compile_ahead, "_idle_cores", lambda: 2.0)
    yield tmp_path / "numba"
    compile_ahead.wait_for_compile_ahead()


def test_nothing_starts_when_the_solver_is_cached_or_switched_off(fresh_cache, monkeypatch):
    monkeypatch.setenv("RECIPSIM_COMPILE_AHEAD", "0")
    assert not compile_ahead.start_compile_ahead("reference_r134a_lbp", [], False)
    monkeypatch.delenv("RECIPSIM_COMPILE_AHEAD")
    (fresh_cache / "x").mkdir(parents=True)
    (fresh_cache / "x" / "integrator.integrate_coupled-381.py311.nbi").write_text("")
    assert not compile_ahead.start_compile_ahead("reference_r134a_lbp", [], False)
    for f in fresh_cache.rglob("*.nbi"):
        f.unlink()
    monkeypatch.setattr(compile_ahead, "_idle_cores", lambda: 1.2)  # a busy machine
    assert not compile_ahead.start_compile_ahead("reference_r134a_lbp", [], False)


def test_the_wait_ends_every_started_child() -> None:
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    compile_ahead._pending.append(child)
    compile_ahead.wait_for_compile_ahead()
    assert child.returncode == 0 and not compile_ahead._pending
    compile_ahead.wait_for_compile_ahead()  # nothing pending: returns at once


@pytest.mark.slow
def test_the_child_compiles_the_cases_scene_into_the_cache(fresh_cache) -> None:
    assert compile_ahead.start_compile_ahead("reference_r134a_lbp", [], False)
    assert not compile_ahead.start_compile_ahead("reference_r134a_lbp", [], False)  # one
    compile_ahead.wait_for_compile_ahead()
    names = {p.name.split("-")[0] for p in fresh_cache.rglob("*.nbi")}
    assert "integrator.integrate_cylinder" in names
    # the entry alone, for the argument types every run passes (test below): not the
    # cycle table's outputs (the parent's), not the W-step (a stiff stretch's)
    assert "scene_outputs._cylinder_outputs" not in names
    assert "integrator.integrate_cylinder_w" not in names


def test_the_child_reads_which_entry_a_case_starts_with() -> None:
    """From the options and solver settings alone (that the entry is compiled for the
    types a run passes: tests/unit/solve/test_scene_entries.py)."""
    from recipsim.case.load import load_case_settings
    from recipsim.solve import scene_entries

    settings = load_case_settings("reference_r134a_lbp")  # dopri5_stiff
    assert scene_entries.entry_name(*settings) == "integrate_cylinder"
    settings = load_case_settings("reference_r134a_lbp", ['solver.method="ros34pw2"'])
    assert scene_entries.entry_name(*settings) == "integrate_cylinder_w"
    settings = load_case_settings("paper_tabulated")
    assert scene_entries.entry_name(*settings) == "integrate_mechanism"


def test_the_parent_builds_its_model_before_it_waits_for_the_child(monkeypatch) -> None:
    """The model build (the property table's compiled functions, which the child never
    compiles) runs beside the child: the parent waits only before it integrates."""
    from recipsim.case.load import load_case
    from recipsim.results import run
    from recipsim.solve import drive, periodic

    calls: list[str] = []

    class Stop(Exception):
        pass

    def solve(model: object) -> None:
        calls.append("solve")
        raise Stop

    monkeypatch.setattr(drive, "build_model_for", lambda case: calls.append("model"))
    monkeypatch.setattr(
        compile_ahead, "compile_outputs_while_waiting", lambda model: calls.append("outputs")
    )
    monkeypatch.setattr(compile_ahead, "wait_for_compile_ahead", lambda: calls.append("wait"))
    monkeypatch.setattr(periodic, "solve_periodic", solve)
    with pytest.raises(Stop):
        run._solve(load_case("reference_r134a_lbp"))
    assert calls == ["model", "outputs", "wait", "solve"]


_OUTPUTS_AHEAD = """
from recipsim.case.load import load_case
from recipsim.physics.mechanics.pinned import pinned_reactions_array
from recipsim.results import compile_ahead
from recipsim.results.cycle import cycle_columns
from recipsim.solve.drive import build_model_for
from recipsim.solve.periodic import solve_periodic
from recipsim.solve.scene_outputs import _cylinder_outputs

compiled = lambda: (len(_cylinder_outputs.signatures), len(pinned_reactions_array.signatures))
model = build_model_for(load_case("reference_r134a_lbp"))
compile_ahead.compile_outputs_while_waiting(model)
print(*compiled())  # nothing: no child pending
compile_ahead._pending.append(None)  # as if a child were compiling the solver
compile_ahead.compile_outputs_while_waiting(model)
compile_ahead._pending.clear()
print(*compiled())
cycle_columns(solve_periodic(model))
print(*compiled())
"""


def test_the_outputs_compiled_while_waiting_are_those_the_cycle_table_runs() -> None:
    """The sample outputs and pinned reactions compiled (or loaded) ahead have the
    argument types of the cycle table's calls: the cycle table adds no second
    specialisation (in a fresh process, numba's disk cache warm)."""
    done = subprocess.run(
        [sys.executable, "-c", _OUTPUTS_AHEAD], capture_output=True, text=True, timeout=600
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.split("\n")[:3] == ["0 0", "1 1", "1 1"]


def test_a_moment_of_load_does_not_keep_the_child_from_starting(monkeypatch) -> None:
    """A task runnable for a moment shows in one look, not in the next; work that keeps
    the cores busy shows in every look, and the child is not started."""
    from recipsim import machine_load

    looks = iter([1, 1, 2, 0])
    monkeypatch.setattr(machine_load, "idle_cores", lambda most, unknown=None: next(looks))
    assert compile_ahead._idle_cores() == 2.0
    calls = []
    monkeypatch.setattr(machine_load, "idle_cores", lambda most, unknown=None: calls.append(1) or 1)
    assert compile_ahead._idle_cores() == 1.0
    assert len(calls) == compile_ahead._LOOKS
