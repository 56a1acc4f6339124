"""What a user waiting on a first run is told (recipsim.progress): a line before every
step that takes seconds, from the command line and from the Python API alike, with the
duration measured last time on this machine, and nothing when asked for silence."""

from __future__ import annotations

import json
import logging
import os
import subprocess
import sys

import pytest

from recipsim import progress

# The child stops as numba starts compiling the solver (os._exit from a compile listener
# registered after recipsim's, so recipsim's own note is out by then): what is checked is
# what the user saw up to there, without paying for the solver's compilation.
_FIRST_SIMULATE = r"""
import os, sys
import recipsim
from numba.core import event

class StopAtSolver(event.Listener):
    def on_start(self, ev):
        function = ev.data["dispatcher"].py_func
        if function.__module__ == "recipsim.solve.integrator":
            print("STOPPED BEFORE COMPILING " + function.__name__, file=sys.stderr, flush=True)
            os._exit(0)
    def on_end(self, ev):
        pass

event.register("numba:compile", StopAtSolver())
case = recipsim.load_case("reference_r134a_lbp")
recipsim.simulate(case)
print("NOT STOPPED", file=sys.stderr)
"""


def _child_env(tmp_path):
    env = {**os.environ, "RECIPSIM_CACHE": str(tmp_path / "cache")}
    for name in ("NUMBA_CACHE_DIR", "NUMBA_DISABLE_JIT"):
        env.pop(name, None)
    return env


def test_simulate_on_empty_caches_says_what_it_does_before_doing_it(tmp_path):
    """From the API, without any logging configured: the property table and the
    solver's compilation are each announced on standard error before they start; the
    steps done are timed into durations.json."""
    done = subprocess.run(
        [sys.executable, "-c", _FIRST_SIMULATE],
        env=_child_env(tmp_path),
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    lines = [line for line in done.stderr.splitlines() if line.strip()]
    notes = [line for line in lines if line.startswith("recipsim: ")]
    stop = lines.index("STOPPED BEFORE COMPILING integrate_scene")
    table = next(i for i, line in enumerate(lines) if "building the R134a property table" in line)
    solver = next(i for i, line in enumerate(lines) if "compiling the solver" in line)
    assert table < solver < stop
    # nothing was measured before: no number is quoted
    assert not any("last time" in line for line in notes), notes
    durations = json.loads((tmp_path / "cache" / "durations.json").read_text())
    assert durations["property table R134a"] > 0.0
    solver_key = progress.compile_key("recipsim.solve.integrator.integrate_scene")
    assert solver_key not in durations  # stopped before it finished: nothing recorded


@pytest.fixture
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("RECIPSIM_CACHE", str(tmp_path))
    return tmp_path


def test_the_estimate_is_the_duration_measured_last_time(cache, caplog):
    caplog.set_level(logging.INFO, logger="recipsim")
    with progress.timed_step("a step", "doing it"):
        pass
    assert caplog.messages[-1] == "doing it (once per installation)"
    progress.record_duration("a step", 12.34)
    with progress.timed_step("a step", "doing it", "once"):
        pass
    assert caplog.messages[-1] == "doing it (once; 12.3 s last time on this machine)"
    assert progress.last_duration("a step") < 12.0  # replaced by this run's measurement
    # a step never measured borrows a similar one's measurement, else says no number
    assert progress.estimate("other fluid", fallback="a step").startswith("; ")
    assert progress.estimate("other fluid") == ""


def test_a_compilation_is_noted_with_its_last_duration(cache, caplog):
    caplog.set_level(logging.DEBUG, logger="recipsim")
    solver = "recipsim.solve.integrator.integrate_scene_w"
    progress._note_compilation(solver)
    assert caplog.records[-1].levelno == logging.INFO  # known to be slow: said even unmeasured
    assert caplog.messages[-1] == "compiling the solver (integrate_scene_w; once per installation)"
    progress.record_duration(progress.compile_key(solver), 9.5)
    progress._note_compilation(solver)
    assert caplog.messages[-1].endswith("; 9.5 s last time on this machine)")
    small = "recipsim.physics.motor.kloss"
    progress._note_compilation(small)
    assert caplog.records[-1].levelno == logging.DEBUG  # not known to take a second
    progress.record_duration(progress.compile_key(small), 1.5)
    progress._note_compilation(small)
    assert caplog.records[-1].levelno == logging.INFO  # measured above the threshold


def test_an_unreadable_durations_file_means_no_estimate(cache):
    progress.durations_file().write_text("{not json")
    assert progress.last_duration("a step") is None
    progress.durations_file().write_text(json.dumps({"a step": "fast", "b": -1.0, "c": 2}))
    assert progress.last_duration("a step") is None and progress.last_duration("b") is None
    assert progress.last_duration("c") == 2.0
    progress.record_duration("a step", 3.0)  # rewritten whole, the valid entries kept
    assert progress.last_duration("a step") == 3.0 and progress.last_duration("c") == 2.0


def test_api_notes_show_unless_silenced_or_logging_is_configured(monkeypatch, capsys):
    logger = logging.getLogger("recipsim")
    monkeypatch.setattr(logging.getLogger(), "handlers", [])  # as in a fresh interpreter
    monkeypatch.setattr(logger, "handlers", [])
    monkeypatch.setattr(logger, "level", logging.NOTSET)
    with progress.notes_shown(True):
        logger.info("step one")
    with progress.notes_shown(False):
        logger.info("step two")
    assert capsys.readouterr().err == "recipsim: step one\n"
    assert logger.handlers == [] and logger.level == logging.NOTSET  # left as found
    configured = logging.StreamHandler(sys.stdout)
    monkeypatch.setattr(logging.getLogger(), "handlers", [configured])
    with progress.notes_shown(True):
        logger.info("step three")  # the program's own logging decides: WARNING and up
    assert capsys.readouterr().err == ""


def test_a_run_says_it_draws_the_figures_and_not_without_them(tmp_path, caplog):
    """Drawing the figures takes seconds of a warm run: a note before it, none with
    ``--no-plots``."""
    from recipsim.pipeline import run_case

    caplog.set_level(logging.INFO, logger="recipsim")
    case = "reference_r134a_lbp"
    run_case(case, ["solver.max_revolutions=2"], tmp_path, plots=False)
    assert not any("figures" in message for message in caplog.messages)
    _, target = run_case(case, ["solver.max_revolutions=2"], tmp_path, plots=("p_V",))
    assert f"drawing the report's figures into {target}" in caplog.messages
