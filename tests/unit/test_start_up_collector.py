"""The command line pauses the garbage collector during its start-up and resumes it,
with the start-up's objects frozen, once numba has started (or its report process has
imported what it draws with); a library caller's collector is left as it was."""

from __future__ import annotations

import gc
import importlib
import subprocess
import sys

import pytest

from recipsim import start_up_collector
from recipsim.report.figure_process import FigureProcesses

cli_main = importlib.import_module("recipsim.cli.main")


@pytest.fixture
def collector(monkeypatch):
    """The module's state reset, the collector on, and left as found."""
    monkeypatch.setattr(start_up_collector, "_paused", False)
    monkeypatch.setattr(start_up_collector, "_frozen", False)
    was_enabled = gc.isenabled()
    gc.enable()
    yield start_up_collector
    gc.unfreeze()
    if was_enabled:
        gc.enable()
    else:
        gc.disable()


def test_pause_stops_and_resume_freezes_and_restarts(collector):
    collector.pause()
    assert not gc.isenabled()
    before = gc.get_freeze_count()
    collector.resume()
    assert gc.isenabled()
    assert gc.get_freeze_count() > before  # what existed then is frozen


def test_objects_are_frozen_at_the_first_resume_only(collector):
    collector.pause()
    collector.resume()
    gc.unfreeze()  # as if none: a second pause and resume must not freeze again
    collector.pause()
    collector.resume()
    assert gc.get_freeze_count() == 0 and gc.isenabled()


def test_a_caller_that_disabled_the_collector_keeps_it_disabled(collector):
    """pause() finds it off: resume() must not turn it on (nor freeze anything)."""
    gc.disable()
    collector.pause()
    collector.resume()
    assert not gc.isenabled() and gc.get_freeze_count() == 0


def test_resume_without_pause_does_nothing(collector):
    collector.resume()
    assert gc.isenabled() and gc.get_freeze_count() == 0


def test_a_report_process_forked_while_paused_draws_with_the_collector_on(collector):
    collector.pause()
    processes = FigureProcesses(1, preload=())
    collector.resume()
    gc.unfreeze()
    processes.submit("gc", "isenabled", [{}])
    assert processes.wait() == [True]


def test_main_resumes_the_collector_whatever_the_command_does(collector, tmp_path, capsys):
    """A command that fails before numba starts still ends with the collector on."""
    missing = tmp_path / "missing.toml"
    assert cli_main.main(["run", str(missing), "--quiet", "--out", str(tmp_path)]) == 2
    assert gc.isenabled()
    assert "missing.toml" in capsys.readouterr().err


_CLI_START = """
import gc
from recipsim import start_up_collector
from recipsim.physics import compiled_runtime
compiled_runtime.allow_stand_in()
start_up_collector.pause()
from recipsim.case.load import load_case
load_case("reference_r134a_lbp")
print(gc.isenabled(), gc.get_freeze_count())
"""


def test_the_collector_runs_again_once_numba_has_started():
    """As the command line starts: paused, then on again with numba's objects frozen as
    soon as a case is loaded (the first thing any solving command does)."""
    done = subprocess.run(
        [sys.executable, "-c", _CLI_START], capture_output=True, text=True, timeout=300
    )
    assert done.returncode == 0, done.stderr
    enabled, frozen = done.stdout.split()
    assert enabled == "True"
    assert int(frozen) > 100_000  # numba's registries among them
