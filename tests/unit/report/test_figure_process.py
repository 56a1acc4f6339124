"""Report figures drawn in forked processes (``recipsim run``): the same files, byte for
byte, as those drawn in-process, and a child's failure raised in the parent."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from helpers import REFERENCE

pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="forks (POSIX only)")


@pytest.fixture(scope="module")
def run():
    from recipsim.case.load import load_case
    from recipsim.results.run import simulate_case

    return simulate_case(load_case(REFERENCE), [])


def _serial_and_forked(
    run, tmp_path: Path
) -> tuple[tuple[float, float], Path, Path, tuple[str, ...]]:
    """The plenum, two empty report directories and the names of the figures that apply."""
    from recipsim.report.report_figures import report_figure_names

    op = run.case.operating_point
    serial, forked = tmp_path / "serial", tmp_path / "forked"
    serial.mkdir()
    forked.mkdir()
    plenum = (op.suction_pressure, op.discharge_pressure)
    return plenum, serial, forked, report_figure_names(run.cycle, run.row)


def test_forked_figures_are_the_in_process_files(run, tmp_path: Path) -> None:
    """Every figure that applies (the in-process drawer's own choice, loss chain
    included) is written by the children, and the PNG bytes are identical: the
    children draw with the same code from an exact copy of the cycle table."""
    from recipsim.report.figure_process import FigureProcesses
    from recipsim.report.report_figures import draw_report_figures

    plenum, serial, forked, names = _serial_and_forked(run, tmp_path)
    draw_report_figures(serial, run.cycle, run.row, plenum, names)

    figures = FigureProcesses(2)
    figures.draw(forked, run.cycle, run.row, plenum, names)
    figures.wait()

    names = sorted(p.name for p in serial.glob("*.png"))
    assert names == sorted(p.name for p in forked.glob("*.png"))
    assert len(names) == 7  # p-V (2), pressure, torque, valves, bearing loads, loss chain
    for name in names:
        assert (serial / name).read_bytes() == (forked / name).read_bytes(), name


def test_a_childs_failure_is_raised_in_the_parent(run, tmp_path: Path) -> None:
    from recipsim.report.figure_process import FigureProcesses

    figures = FigureProcesses(1)
    broken = run.cycle.drop(columns=["cylinder_pressure [Pa]"])
    figures.draw(tmp_path, broken, run.row, None, ("p_theta",))
    with pytest.raises(KeyError, match="cylinder_pressure"):
        figures.wait()


def test_children_without_a_job_exit_cleanly() -> None:
    from recipsim.report.figure_process import FigureProcesses

    figures = FigureProcesses(2)
    pids = [pid for pid, _job, _result in figures._children]
    figures.wait()
    for pid in pids:  # reaped: no such child any more
        with pytest.raises(ChildProcessError):
            os.waitpid(pid, os.WNOHANG)


def test_run_command_writes_the_same_report_with_and_without_forking(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from recipsim.cli.main import main

    for label, setting in (("forked", "2"), ("serial", "0")):
        monkeypatch.setenv("RECIPSIM_FIGURE_PROCESSES", setting)
        assert main(["run", str(REFERENCE), "--out", str(tmp_path / label), "--quiet"]) == 0
    forked = tmp_path / "forked" / "reference_r134a_lbp"
    serial = tmp_path / "serial" / "reference_r134a_lbp"
    names = sorted(p.name for p in serial.glob("*.png"))
    assert names == sorted(p.name for p in forked.glob("*.png")) and len(names) == 7
    for name in [*names, "cycle.csv"]:
        assert (serial / name).read_bytes() == (forked / name).read_bytes(), name


def test_forked_map_plots_are_the_in_process_files(tmp_path: Path) -> None:
    """The sweep's map plots shared between two children: the same files, in the same
    order, byte for byte, as :func:`save_map_plots` draws in-process."""
    from recipsim.report.figure_process import FigureProcesses
    from recipsim.studies.sweep.plots import MAP_PRELOAD, save_map_plots, submit_map_plots
    from unit.studies.sweep.test_sweep_plots import AXES, synthetic

    table = synthetic(bearings=True)
    serial, forked = tmp_path / "serial", tmp_path / "forked"
    serial.mkdir()
    forked.mkdir()
    in_process = save_map_plots(table, AXES, serial)
    figures = FigureProcesses(2, MAP_PRELOAD)
    submit_map_plots(figures, table, AXES, forked)
    shares = figures.wait()
    assert len(shares) == 2 and all(shares)  # both children drew
    names = sorted(p.name for share in shares for p in share)
    assert names == sorted(p.name for p in in_process) and len(names) == 6
    for name in names:
        assert (serial / name).read_bytes() == (forked / name).read_bytes(), name


def test_map_plots_fan_out_one_process_per_plot(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """At the end of a sweep on a machine with many idle cores, the two figure processes
    fork for the other map plots: six processes, one plot each (not four, the bound of a
    case report's fan-out), and the same files, byte for byte, as in-process."""
    from recipsim.report.figure_process import FigureProcesses
    from recipsim.studies.sweep.plots import MAP_PRELOAD, save_map_plots, submit_map_plots
    from unit.studies.sweep.test_sweep_plots import AXES, synthetic

    _fan_out_to(monkeypatch, cores=16)
    table = synthetic(bearings=True)
    serial, forked = tmp_path / "serial", tmp_path / "forked"
    serial.mkdir()
    forked.mkdir()
    in_process = save_map_plots(table, AXES, serial)
    figures = FigureProcesses(2, MAP_PRELOAD, fan_out=True)
    submit_map_plots(figures, table, AXES, forked)
    shares = figures.wait()
    assert sorted(len(share) for share in shares) == [1] * 6
    names = sorted(p.name for share in shares for p in share)
    assert names == sorted(p.name for p in in_process) and len(names) == 6
    for name in names:
        assert (serial / name).read_bytes() == (forked / name).read_bytes(), name


@pytest.mark.parametrize(("running", "expected"), [(1, 2), (2, 1), (3, 0)])
def test_children_only_on_idle_cores(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, running: int, expected: int
) -> None:
    """Two usable cores less the tasks runnable besides this one
    (:mod:`recipsim.machine_load`): the children never compete with other work for a
    busy core."""
    from recipsim import machine_load
    from recipsim.report import figure_process

    load_file = tmp_path / "loadavg"
    load_file.write_text(f"1.90 1.50 1.20 {running}/123 4567\n")
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0, 1}, raising=False)
    monkeypatch.setattr(machine_load, "LOADAVG", str(load_file))
    monkeypatch.setattr(machine_load, "_own_running_tasks", lambda: 1)
    monkeypatch.delenv("RECIPSIM_FIGURE_PROCESSES", raising=False)
    started = figure_process.start_figure_processes()
    assert (started is None) == (expected == 0)
    if started is not None:
        assert len(started.pids) == expected
        started.wait()


def test_children_ignore_ctrl_c_and_leave_it_to_the_parent() -> None:
    """A SIGINT sent to a waiting child (as Ctrl-C reaches the whole process group) does
    not end it: it exits cleanly when the parent says that no job comes."""
    import signal
    import time

    from recipsim.report.figure_process import FigureProcesses

    figures = FigureProcesses(1, preload=())
    pid = figures.pids[0]
    status = Path(f"/proc/{pid}/status")
    for _ in range(500):  # until the child ignores SIGINT (Linux shows it in /proc)
        if not status.exists():
            time.sleep(0.5)
            break
        ignored = next(ln for ln in status.read_text().splitlines() if ln.startswith("SigIgn"))
        if int(ignored.split()[1], 16) & (1 << (signal.SIGINT - 1)):
            break
        time.sleep(0.01)
    os.kill(pid, signal.SIGINT)
    assert figures.wait() == []


def test_run_leaves_pandas_and_matplotlib_to_the_report_processes(tmp_path: Path) -> None:
    """``recipsim run`` hands the tables and the figures to report processes (with and
    without figures): the command's own process imports neither pandas nor matplotlib
    (0.5 s between them), and the report is the one written in-process."""
    import subprocess
    import sys

    import pandas as pd

    child = (
        "import sys\n"
        "from recipsim.cli.main import main\n"
        f"for extra in ([], ['--no-plots']):\n"
        f"    out = {str(tmp_path)!r} + '/forked' + ''.join(extra)\n"
        f"    assert main(['run', {str(REFERENCE)!r}, '--out', out, '--quiet', *extra]) == 0\n"
        "print(sorted(m for m in ('pandas', 'matplotlib') if m in sys.modules))\n"
    )
    env = dict(os.environ, RECIPSIM_FIGURE_PROCESSES="1")
    out = subprocess.run(
        [sys.executable, "-c", child], capture_output=True, text=True, check=True, env=env
    )
    assert out.stdout.strip() == "[]"
    from recipsim.cli.main import main

    os.environ["RECIPSIM_FIGURE_PROCESSES"] = "0"
    try:
        assert main(["run", str(REFERENCE), "--out", str(tmp_path / "serial"), "--quiet"]) == 0
    finally:
        del os.environ["RECIPSIM_FIGURE_PROCESSES"]
    serial = tmp_path / "serial" / "reference_r134a_lbp"
    for forked in (tmp_path / "forked", tmp_path / "forked--no-plots"):
        report = forked / "reference_r134a_lbp"
        assert (report / "cycle.csv").read_bytes() == (serial / "cycle.csv").read_bytes()
        ours, theirs = (pd.read_csv(r / "summary.csv") for r in (report, serial))
        pd.testing.assert_frame_equal(
            ours.drop(columns="wall_time [s]"), theirs.drop(columns="wall_time [s]")
        )
        has_figures = forked.name == "forked"
        assert bool(list(report.glob("*.png"))) == has_figures


@pytest.mark.parametrize(("cores", "expected"), [(2, 1), (3, 2), (16, 2), (1, 1)])
def test_a_solving_parent_keeps_one_idle_core(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, cores: int, expected: int
) -> None:
    """``recipsim run`` solves while its report processes start: they take the idle
    cores besides one (at least one child, at most two)."""
    from recipsim import machine_load
    from recipsim.report import figure_process

    load_file = tmp_path / "loadavg"
    load_file.write_text("1.90 1.50 1.20 1/123 4567\n")
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: set(range(cores)), raising=False)
    monkeypatch.setattr(machine_load, "LOADAVG", str(load_file))
    monkeypatch.setattr(machine_load, "_own_running_tasks", lambda: 1)
    monkeypatch.delenv("RECIPSIM_FIGURE_PROCESSES", raising=False)
    started = figure_process.start_figure_processes(at_least=1, busy_parent=True)
    assert started is not None
    try:
        assert len(started.pids) == expected
    finally:
        started.wait()


def _fan_out_to(monkeypatch: pytest.MonkeyPatch, cores: int, running: int = 0) -> None:
    """Make :meth:`FigureProcesses.drawing_processes` see ``cores`` usable cores and
    ``running`` tasks runnable elsewhere."""
    from recipsim.report import figure_process

    monkeypatch.setattr(figure_process, "usable_cores", lambda: cores)
    monkeypatch.setattr(figure_process, "busy_cores", lambda: float(running))
    monkeypatch.setattr(figure_process, "runnable", lambda pid: False)


def test_fanned_out_report_is_the_in_process_report(
    run, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """One report process that forks two more at the hand-over (three idle cores):
    the same figures and tables, byte for byte, as the in-process writer's."""
    from recipsim.report.figure_process import FigureProcesses
    from recipsim.report.report_figures import draw_report_figures, write_tables

    _fan_out_to(monkeypatch, cores=3)
    plenum, serial, forked, names = _serial_and_forked(run, tmp_path)
    write_tables(serial, run.row, run.cycle)
    draw_report_figures(serial, run.cycle, run.row, plenum, names)

    figures = FigureProcesses(1, fan_out=True)
    assert figures.drawing_processes() == 3
    figures.draw(forked, run.table, run.row, plenum, names, tables=True)
    assert figures.wait() == [None, None, None]  # three shares, each drawn

    files = sorted(p.name for p in serial.iterdir())
    assert files == sorted(p.name for p in forked.iterdir()) and len(files) == 9
    for name in files:
        assert (serial / name).read_bytes() == (forked / name).read_bytes(), name


def test_jobs_beyond_the_children_run_in_forks_of_them() -> None:
    """Five jobs for two children: each child runs its first job and forks one
    process per other job; the values come back in the order of the jobs."""
    from recipsim.report.figure_process import FigureProcesses

    figures = FigureProcesses(2, preload=())
    children = figures.pids
    figures.submit("os", "getpid", [{}] * 5)
    pids = figures.wait()
    assert pids[:2] == children  # jobs 0 and 1: the children themselves
    assert len(set(pids)) == 5  # jobs 2, 3 (child 0's forks) and 4 (child 1's)


def test_a_forks_failure_is_raised_in_the_parent() -> None:
    """A fork's exception reaches the parent as a child's does, once every process
    has ended; the values of the others are not returned."""
    import json

    from recipsim.report.figure_process import FigureProcesses

    figures = FigureProcesses(1, preload=())
    figures.submit("json", "loads", [{"s": "1"}, {"s": "{"}])  # the second: a fork's
    with pytest.raises(json.JSONDecodeError):
        figures.wait()


def _open_pipes() -> set[int]:
    """Inodes of the pipes this process has open."""
    import stat

    pipes = set()
    for fd in os.listdir("/proc/self/fd"):
        try:
            status = os.fstat(int(fd))
        except OSError:
            continue  # the directory listing's own descriptor
        if stat.S_ISFIFO(status.st_mode):
            pipes.add(status.st_ino)
    return pipes


@pytest.mark.skipif(not Path("/proc/self/fd").is_dir(), reason="Linux's /proc")
def test_forks_close_their_parents_pipes() -> None:
    """A fork keeps no end of the pipes between its parent (the report process) and the
    command: the command reads its result pipe to end-of-file."""
    from recipsim.report.figure_process import FigureProcesses

    figures = FigureProcesses(1, preload=())
    _pid, job, result = figures._children[0]
    theirs = {os.fstat(job).st_ino, os.fstat(result).st_ino}
    figures.submit(__name__, "_open_pipes", [{}, {}])
    child, fork = figures.wait()
    assert theirs <= child  # the child holds its own pipes
    assert not theirs & fork  # its fork does not


@pytest.mark.parametrize(
    ("cores", "running", "children_running", "expected"),
    [(2, 0, 0, 2), (2, 1, 0, 1), (2, 1, 1, 2), (3, 0, 0, 3), (16, 0, 0, 4), (1, 0, 0, 1)],
)
def test_fan_out_onto_the_idle_cores_at_the_hand_over(
    monkeypatch: pytest.MonkeyPatch, cores: int, running: int, children_running: int, expected: int
) -> None:
    """The processes that draw: the cores idle at the hand-over (the command's own
    included, it only waits; a child still importing counts as idle), at most four and
    at least the children."""
    from recipsim.report import figure_process

    _fan_out_to(monkeypatch, cores, running)
    monkeypatch.setattr(figure_process, "runnable", lambda pid: children_running > 0)
    figures = figure_process.FigureProcesses(1, preload=(), fan_out=True)
    try:
        assert figures.drawing_processes() == expected
    finally:
        figures.wait()


def test_an_explicit_count_of_figure_processes_does_not_fan_out(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """``RECIPSIM_FIGURE_PROCESSES`` is the number of processes that draw, as before the
    fan-out; without it the command line fans out."""
    from recipsim.report import figure_process

    _fan_out_to(monkeypatch, cores=4)
    for setting, expected in (("1", 1), ("2", 2), ("", 4)):
        monkeypatch.setenv("RECIPSIM_FIGURE_PROCESSES", setting)
        figures = figure_process.start_figure_processes(preload=(), at_least=1)
        assert figures is not None
        try:
            assert figures.drawing_processes() == expected
        finally:
            figures.wait()
