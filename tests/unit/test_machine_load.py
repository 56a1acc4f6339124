"""Idle cores from the runnable tasks now, not from the lagging load average."""

from __future__ import annotations

import os

import pytest

from recipsim import machine_load


def _load_file(tmp_path, running: int, load: float = 1.9) -> str:
    path = tmp_path / "loadavg"
    path.write_text(f"{load:.2f} 1.50 1.20 {running}/123 4567\n")
    return str(path)


@pytest.mark.parametrize(("running", "expected"), [(1, 2), (2, 1), (3, 0), (9, 0)])
def test_idle_cores_count_the_tasks_runnable_now(tmp_path, monkeypatch, running, expected):
    """The reader is one of the runnable tasks (here its only runnable thread); a
    one-minute load of 1.9 left by the previous command does not count."""
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0, 1}, raising=False)
    monkeypatch.setattr(machine_load, "_own_running_tasks", lambda: 1)
    monkeypatch.setattr(machine_load, "LOADAVG", _load_file(tmp_path, running))
    assert machine_load.busy_cores() == running - 1
    assert machine_load.idle_cores(2) == expected
    assert machine_load.idle_cores(1) == min(expected, 1)


@pytest.mark.parametrize(("load", "expected"), [(0.0, 2), (0.4, 2), (0.6, 1), (1.6, 0)])
def test_the_load_average_where_the_kernel_says_nothing(tmp_path, monkeypatch, load, expected):
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0, 1}, raising=False)
    monkeypatch.setattr(machine_load, "LOADAVG", str(tmp_path / "missing"))
    monkeypatch.setattr(os, "getloadavg", lambda: (load, 0.0, 0.0))
    assert machine_load.idle_cores(2) == expected


def test_unknown_load(tmp_path, monkeypatch):
    def no_load():
        raise OSError("no load average")

    monkeypatch.setattr(machine_load, "LOADAVG", str(tmp_path / "missing"))
    monkeypatch.setattr(os, "getloadavg", no_load)
    assert machine_load.idle_cores(2) == 2
    assert machine_load.idle_cores(2, unknown=0) == 0


def test_this_machine_reads_its_own_load():
    """On Linux the kernel's file is read (at least this process is runnable)."""
    if not os.path.exists(machine_load.LOADAVG):
        pytest.skip("no /proc/loadavg")
    assert machine_load._own_running_tasks() >= 1  # the thread reading it
    assert machine_load._runnable_elsewhere(machine_load.LOADAVG) >= 0
    assert 0 <= machine_load.idle_cores(64) <= machine_load.usable_cores()


def test_this_process_own_spinning_threads_do_not_count(tmp_path, monkeypatch):
    """Three runnable tasks, two of them this process's (numpy's BLAS thread spins for a
    few ms after its import): one core is busy elsewhere."""
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0, 1}, raising=False)
    monkeypatch.setattr(machine_load, "LOADAVG", _load_file(tmp_path, 3))
    monkeypatch.setattr(machine_load, "_own_running_tasks", lambda: 2)
    assert machine_load.busy_cores() == 1
    assert machine_load.idle_cores(2) == 1
