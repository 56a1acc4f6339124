"""Time to answer: what ``recipsim run`` and ``recipsim sweep`` spend around the solver.

Everything runs in fresh interpreters, as a user meets it, with warm caches (one
unmeasured run fills them first), and is reported as the median over repeats of both
wall time and CPU time (the CPU time is the steadier figure on a shared machine):

- :func:`measure_run_stages`: the stages of one ``recipsim run`` in a child that does
  what the command does, step by step: imports, case loading, model build, solve
  (the first solve of a process also loads numba's cache: ``numba_cache_load``), tables,
  each figure, report writing; and the command itself end to end;
- :func:`measure_map`: a sweep with 1..J workers; its solves (the points'
  ``wall_time [s]``), overhead ratio (everything but the solves, over the solves, with
  one worker), parallel efficiency ``T(1) / (J T(J))`` and the serial/parallel split of
  the overhead model ``T(J) = S + P / J`` fitted to the first and last worker counts;
- :func:`measure_map_after_startup`: the same sweep on one worker inside an interpreter
  that has already imported recipsim and loaded numba's cache, with and without map
  plots: the overhead ratio without process start-up, beside the end-to-end one;
- :func:`measure_first_run`: ``recipsim run`` with empty caches (numba, property table,
  fluid constants, pint) in a temporary directory.
"""

from __future__ import annotations

import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from recipsim.errors import RecipsimError

# runs in the child: the steps of `recipsim run`, timed one by one (the figures that
# apply to the case each on its own)
_CHILD = r"""
import json, sys, time
from pathlib import Path
marks = {}
last = [time.perf_counter(), time.process_time()]
def lap(name):
    now = [time.perf_counter(), time.process_time()]
    marks[name] = [now[0] - last[0], now[1] - last[1]]
    last[:] = [time.perf_counter(), time.process_time()]
import recipsim.cli.main
from recipsim.case.load import load_case
from recipsim.results.provenance import provenance
from recipsim.results.tables import cycle_table, summary
from recipsim.solve.drive import build_model_for
from recipsim.solve.periodic import solve_periodic
from recipsim.report.case_report import report_dir, run_title, write_case_report
lap("import")
case = load_case(sys.argv[1], sys.argv[3:])
lap("case_loading")
model = build_model_for(case)
lap("model_build")
solution = solve_periodic(model)
lap("solve_first")
solution = solve_periodic(build_model_for(case))
lap("build_and_solve_warm")
cycle = cycle_table(solution)
row = summary(solution, cycle, case)
meta = provenance(solution, [])
lap("tables")
from recipsim.results.run import CaseRun
run = CaseRun(case, solution, cycle, row, meta)
out = Path(sys.argv[2])
write_case_report(run, report_dir(out, case.name, case.overrides), list(case.overrides), False)
lap("report_writing")
from recipsim.report import plotting
lap("plot_import")
op = case.operating_point
plenum = (op.suction_pressure, op.discharge_pressure)
for name, kind, make in plotting._figure_makers(cycle, plenum):
    fig = make()
    if kind is not None:
        plotting.fixed_margins(fig, kind)
    fig.suptitle(run_title(row), fontsize="medium")
    fig.savefig(out / f"{name}.png", dpi=110, pil_kwargs=plotting.PNG_OPTIONS)
    lap("figure_" + name)
print(json.dumps(marks))
"""


# runs in the child: the sweep after start-up (recipsim's modules imported, numba's cache
# loaded by one solve of the base case), one worker, with and without the map plots
_MAP_CHILD = r"""
import json, sys, tempfile, time
import recipsim.report.plotting, recipsim.studies.sweep.plots
from recipsim.case.load import load_case
from recipsim.results.run import simulate_case
from recipsim.studies.sweep.engine import run_sweep
from recipsim.studies.sweep.spec import load_sweep
spec = load_sweep(sys.argv[1])
simulate_case(load_case(str(spec.base), []), [])
result = {}
with tempfile.TemporaryDirectory() as out:
    for label, plots in (("no_plots", False), ("with_plots", True)):
        start, cpu = time.perf_counter(), time.process_time()
        outcome = run_sweep(spec, jobs=1, out=out, plots=plots, fresh=True)
        wall = time.perf_counter() - start
        solves = outcome.solve_seconds
        result[label] = [wall, time.process_time() - cpu, solves]
print(json.dumps(result))
"""


def measure_map_after_startup(sweep: str) -> dict[str, Any]:
    """The sweep on one worker in an interpreter already started (modules imported, numba's
    cache loaded), with and without its map plots: the overhead that start-up does not
    explain.

    Parameters
    ----------
    sweep : str
        Sweep file or shipped sweep name.

    Returns
    -------
    dict
        For ``no_plots`` and ``with_plots``: ``wall [s]``, ``cpu [s]``, ``solve_sum [s]``
        and ``overhead_ratio [-]`` = (wall - solves) / solves.
    """
    _timed([sys.executable, "-c", _MAP_CHILD, sweep])  # fill the caches
    measured = json.loads(_timed([sys.executable, "-c", _MAP_CHILD, sweep])[2].splitlines()[-1])
    return {
        label: {
            "wall [s]": wall,
            "cpu [s]": cpu,
            "solve_sum [s]": solves,
            "overhead_ratio [-]": (wall - solves) / solves if solves > 0 else None,
        }
        for label, (wall, cpu, solves) in measured.items()
    }


def _child_seconds() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _timed(
    command: list[str], env: dict[str, str] | None = None, sweep: bool = False
) -> tuple[float, float, str]:
    """Wall and CPU time [s] of a command and its waited-for children; its stdout.

    ``sweep``: the command is ``recipsim sweep``, whose exit status 1 without an error
    message says that some points failed: they are rows of the map, timed like the rest.

    Raises
    ------
    RecipsimError
        If the command failed, with its exit status and the last line it printed.
    """
    cpu0, start = _child_seconds(), time.perf_counter()
    out = subprocess.run(command, capture_output=True, text=True, env=env)
    failed_points = sweep and out.returncode == 1 and "recipsim:" not in out.stderr
    if out.returncode != 0 and not failed_points:
        last = (out.stderr.strip() or out.stdout.strip() or "no output").splitlines()[-1]
        raise RecipsimError(f"{' '.join(command[1:4])} ... exited with {out.returncode}: {last}")
    return time.perf_counter() - start, _child_seconds() - cpu0, out.stdout


def _median_pairs(runs: list[dict[str, list[float]]]) -> dict[str, dict[str, float]]:
    return {
        key: {
            "wall [s]": statistics.median(r[key][0] for r in runs),
            "cpu [s]": statistics.median(r[key][1] for r in runs),
        }
        for key in runs[0]
    }


def measure_run_stages(case: str, overrides: list[str], repeats: int = 3) -> dict[str, Any]:
    """Stages of one ``recipsim run`` and the command end to end, medians over repeats.

    Parameters
    ----------
    case : str
        Case file or shipped case name.
    overrides : list of str
        ``KEY=VALUE`` overrides.
    repeats : int
        Timed interpreters per measurement (after one that warms the caches).

    Returns
    -------
    dict
        ``stages``: stage name to ``{"wall [s]", "cpu [s]"}`` (``numba_cache_load`` is the
        first solve minus a warm build and solve); ``run``: the command with its figures
        and with ``--no-plots``, each ``{"wall [s]", "cpu [s]"}`` (CPU of the command and
        its report processes); ``phases``: for each of the two, the real command's
        timeline (:func:`median_timeline`): when each phase ended, seconds after the
        command was started, in the parent and in its report processes.
    """
    with tempfile.TemporaryDirectory(prefix="recipsim-system-") as tmp:
        child = [sys.executable, "-c", _CHILD, case, tmp, *overrides]
        _timed(child)  # fill the caches
        runs = [json.loads(_timed(child)[2].strip().splitlines()[-1]) for _ in range(repeats)]
        stages = _median_pairs(runs)
        first, warm = stages["solve_first"], stages["build_and_solve_warm"]
        stages["numba_cache_load"] = {
            k: max(first[k] + stages["model_build"][k] - warm[k], 0.0) for k in first
        }
        command = [sys.executable, "-m", "recipsim", "run", case, "--out", tmp, "--quiet"]
        command += [a for o in overrides for a in ("--set", o)]
        result: dict[str, Any] = {"stages": stages, "run": {}, "phases": {}}
        for label, extra in (("with_figures", []), ("no_plots", ["--no-plots"])):
            timings, timelines = [], []
            for _ in range(repeats):
                wall, cpu, timeline = _timed_with_timeline(command + extra, Path(tmp))
                timings.append((wall, cpu))
                timelines.append(timeline)
            result["run"][label] = {
                "wall [s]": statistics.median(t[0] for t in timings),
                "cpu [s]": statistics.median(t[1] for t in timings),
            }
            result["phases"][label] = median_timeline(timelines)
    return result


def _timed_with_timeline(
    command: list[str], tmp: Path
) -> tuple[float, float, dict[str, list[tuple[str, float]]]]:
    """:func:`_timed` of ``recipsim run`` with ``RECIPSIM_TIMELINE`` set: its wall and CPU
    time [s] and its marks (:mod:`recipsim.timeline`) by process role, each as the time
    since the command was started [s]."""
    path = tmp / "timeline.jsonl"
    path.unlink(missing_ok=True)
    start = time.time()
    wall, cpu, _ = _timed(command, dict(os.environ, RECIPSIM_TIMELINE=str(path)))
    marks: dict[str, list[tuple[str, float]]] = {}
    for line in path.read_text().splitlines() if path.exists() else []:
        entry = json.loads(line)
        role = entry["role"] if entry["role"] not in marks else f"{entry['role']} {entry['pid']}"
        marks[role] = [(name, at - start) for name, at, _cpu in entry["marks"]]
    marks["parent"] = [*marks.get("parent", []), ("exit", wall)]
    return wall, cpu, marks


def median_timeline(
    timelines: list[dict[str, list[tuple[str, float]]]],
) -> dict[str, dict[str, float]]:
    """Median over runs of the time each mark of each process role is reached [s, since
    the command started] (``parent``, ``report process``; a role missing from some runs,
    e.g. a second report process, is given over the runs that have it).

    Parameters
    ----------
    timelines : list of dict
        Per run, role to ``[(mark, seconds), ...]`` (:func:`_timed_with_timeline`).

    Returns
    -------
    dict
        Role to ``{mark: median seconds}``, marks in the order reached.
    """
    result: dict[str, dict[str, float]] = {}
    roles = dict.fromkeys(role for t in timelines for role in t)
    for role in roles:
        names = dict.fromkeys(name for t in timelines for name, _ in t.get(role, []))
        result[role] = {
            name: statistics.median(
                at for t in timelines for mark, at in t.get(role, []) if mark == name
            )
            for name in names
        }
    return result


def measure_map(
    sweep: str, jobs: list[int], repeats: int = 1, plots: bool = True
) -> dict[str, Any]:
    """A sweep with each worker count of ``jobs``, from scratch each time.

    Parameters
    ----------
    sweep : str
        Sweep file or shipped sweep name (e.g. ``throughput_100``).
    jobs : list of int
        Worker counts, e.g. ``[1, 2]``.
    repeats : int
        Runs per worker count (median).
    plots : bool
        Draw the map plots (as ``recipsim sweep`` does by default).

    Returns
    -------
    dict
        ``points``; ``solve_sum [s]`` (sum of the points' solve times, one worker);
        ``runs``: worker count to ``{"wall [s]", "cpu [s]", "efficiency [-]"}``;
        ``overhead_ratio [-]`` (one worker: wall minus solves, over solves);
        ``model``: ``serial [s]`` and ``parallel [s]`` of ``T(J) = S + P / J``.
    """
    import pandas as pd

    runs: dict[int, dict[str, float]] = {}
    solve_sum = 0.0
    points = 0
    with tempfile.TemporaryDirectory(prefix="recipsim-system-map-") as tmp:
        base = [sys.executable, "-m", "recipsim", "sweep", sweep, "--fresh", "--quiet"]
        base += ["--out", tmp] + ([] if plots else ["--no-plots"])
        _timed(base + ["--jobs", "1"], sweep=True)  # fill the caches
        for count in jobs:
            command = base + ["--jobs", str(count)]
            timings = [_timed(command, sweep=True)[:2] for _ in range(repeats)]
            runs[count] = {
                "wall [s]": statistics.median(t[0] for t in timings),
                "cpu [s]": statistics.median(t[1] for t in timings),
            }
            if count == min(jobs):
                table = pd.read_csv(next(Path(tmp).glob("*/summary.csv")))
                points = len(table)
                solve_sum = float(table["wall_time [s]"].fillna(0.0).sum())
    one = runs[min(jobs)]["wall [s]"] * min(jobs)
    for count, timing in runs.items():
        timing["efficiency [-]"] = one / (count * timing["wall [s]"])
    low = min(jobs)
    model = overhead_model({count: timing["wall [s]"] for count, timing in runs.items()})
    return {
        "sweep": sweep,
        "points": points,
        "solve_sum [s]": solve_sum,
        "runs": {str(k): v for k, v in runs.items()},
        "overhead_ratio [-]": (runs[low]["wall [s]"] - solve_sum) / solve_sum
        if low == 1 and solve_sum > 0
        else None,
        "model": model,
    }


def overhead_model(walls: dict[int, float]) -> dict[str, float]:
    """Serial and parallel parts of ``T(J) = S + P / J`` through the fewest and the most
    workers measured.

    Parameters
    ----------
    walls : dict
        Worker count to wall time [s].

    Returns
    -------
    dict
        ``serial [s]`` (S) and ``parallel [s]`` (P); empty with one worker count only.
    """
    low, high = min(walls), max(walls)
    if high == low:
        return {}
    parallel = (walls[low] - walls[high]) / (1.0 / low - 1.0 / high)
    return {"serial [s]": walls[low] - parallel / low, "parallel [s]": parallel}


def extrapolate(model: dict[str, float], workers: int, scale: float = 1.0) -> dict[str, float]:
    """Wall time and efficiency of ``T(J) = S + scale P / J`` at ``workers``.

    Parameters
    ----------
    model : dict
        ``serial [s]`` and ``parallel [s]`` from :func:`measure_map`.
    workers : int
        Worker count J.
    scale : float
        Ratio of the point counts (10 for 1000 points from a 100-point fit); the serial
        part is kept as measured, so the efficiency is an upper bound when it grows with
        the points.

    Returns
    -------
    dict
        ``wall [s]`` and ``efficiency [-]`` (against one worker).
    """
    serial, parallel = model["serial [s]"], model["parallel [s]"] * scale
    wall = serial + parallel / workers
    return {"wall [s]": wall, "efficiency [-]": (serial + parallel) / (workers * wall)}


def measure_first_run(case: str) -> dict[str, float]:
    """``recipsim run CASE --no-plots`` and then with figures, with every cache empty.

    ``RECIPSIM_CACHE`` and ``NUMBA_CACHE_DIR`` point into a new temporary directory, so
    the solver is compiled, the property table built and pint's definitions parsed as
    on a fresh machine.

    Returns
    -------
    dict
        ``wall [s]`` and ``cpu [s]`` of the first run (empty caches, with figures) and
        ``second_wall [s]`` of the run after it.
    """
    with tempfile.TemporaryDirectory(prefix="recipsim-first-run-") as tmp:
        env = dict(os.environ, RECIPSIM_CACHE=str(Path(tmp) / "cache"))
        env["NUMBA_CACHE_DIR"] = str(Path(tmp) / "cache" / "numba")
        command = [sys.executable, "-m", "recipsim", "run", case, "--out", tmp, "--quiet"]
        wall, cpu, _ = _timed(command, env)
        second, _, _ = _timed(command, env)
    return {"wall [s]": wall, "cpu [s]": cpu, "second_wall [s]": second}
