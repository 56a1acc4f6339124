"""``recipsim bench-system [CASE] [--sweep SWEEP] [--jobs J|LIST] [--repeats N] [--first-run]``.

Time to answer, around the solver (:mod:`recipsim.studies.bench.system_time`): the stages
of ``recipsim run`` (imports, case loading, model build, solve, tables, each figure,
report writing) and the command end to end; a sweep on 1..J workers (or a list of worker
counts) with its overhead ratio (end to end, and after start-up: modules imported, numba
cache loaded, where it is also split by stage: case, model build, sampled outputs,
summary, record, plan, tables) and its parallel efficiency, end to end and after
start-up; optionally the first run with empty caches. Writes
``<out>/system/system.json`` (default ``--out``: ``reports/bench``) and prints a table.
The timed runs write their files under ``--scratch`` (default ``<out>/system/scratch``),
removed after.

A subcommand of its own rather than ``bench --system``: ``bench`` ranks solver settings
on one case (its options choose rungs, tolerances and a time budget), this one times the
program around a fixed solver; they share no option but ``--out``.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import shutil
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from recipsim.cli.options import exit_status, positive_int, worker_counts


def add_bench_system_parser(sub: Any) -> argparse.ArgumentParser:
    """Add the ``bench-system`` subcommand to the subparsers ``sub``."""
    parser: argparse.ArgumentParser = sub.add_parser(
        "bench-system",
        help="time to answer: the stages of a run and a sweep on 1..J workers",
        description=__doc__.split("\n\n")[1] if __doc__ else None,
    )
    parser.add_argument("case", nargs="?", default="reference_r134a_lbp", help="case to run")
    parser.add_argument("--sweep", default="throughput_100", help="sweep to map")
    parser.add_argument(
        "--jobs",
        type=worker_counts,
        default=[1, 2],
        metavar="J",
        help="worker counts: J for 1..J, or a list such as 1,2,4,8,16 (default 2)",
    )
    parser.add_argument("--repeats", type=positive_int, default=3, metavar="N")
    parser.add_argument("--map-repeats", type=positive_int, default=1, metavar="N")
    parser.add_argument("--no-map", action="store_true", help="skip the sweep")
    parser.add_argument(
        "--first-run", action="store_true", help="also time a run with empty caches (~1 min)"
    )
    parser.add_argument("--out", type=Path, default=Path("reports/bench"))
    parser.add_argument(
        "--scratch",
        type=Path,
        default=None,
        metavar="DIR",
        help="where the timed runs write their reports and point records "
        "(default: <out>/system/scratch, on the disk the reports go to; removed after)",
    )
    parser.set_defaults(handler=run_bench_system_command)
    return parser


def run_bench_system_command(args: argparse.Namespace, argv: list[str] | None) -> int:
    """Handler of ``recipsim bench-system``."""
    return exit_status(lambda: _bench_system(args), str(args.case))


def _bench_system(args: argparse.Namespace) -> int:
    from recipsim.atomic import atomic_file, mark_output
    from recipsim.studies.bench.system import machine_info

    target = Path(args.out) / "system"
    mark_output(target)  # refused before anything is timed; the scratch goes inside
    with scratch_directory(args.scratch or target / "scratch"):
        result = _measure(args)
    result["machine"]["load_average_after"] = machine_info()["load_average"]
    with atomic_file(target / "system.json") as handle:
        json.dump(result, handle, indent=2)
    print(format_system(result))
    print(f"-> {target / 'system.json'}")
    return 0


@contextlib.contextmanager
def scratch_directory(directory: Path) -> Iterator[Path]:
    """Make ``directory`` the temporary directory of this process and of the commands it
    times (``TMPDIR``), then remove it: the timed runs create their files on the disk the
    reports go to. On the 2-core machine, creating a file in some directories under
    ``/tmp`` took 0.1-1 ms against 0.02 ms on the project's disk, which a map's point
    records measured as overhead."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix="recipsim-bench-", dir=directory))
    saved_env, saved_dir = os.environ.get("TMPDIR"), tempfile.tempdir
    os.environ["TMPDIR"] = str(work)
    tempfile.tempdir = str(work)
    try:
        yield work
    finally:
        tempfile.tempdir = saved_dir
        if saved_env is None:
            os.environ.pop("TMPDIR", None)
        else:
            os.environ["TMPDIR"] = saved_env
        shutil.rmtree(work, ignore_errors=True)
        with contextlib.suppress(OSError):
            directory.rmdir()  # only if nothing else is in it


def _measure(args: argparse.Namespace) -> dict[str, Any]:
    from recipsim.studies.bench.map_overhead import measure_map_overhead
    from recipsim.studies.bench.map_scaling import measure_map_scaling
    from recipsim.studies.bench.system import machine_info
    from recipsim.studies.bench.system_time import (
        extrapolate,
        measure_first_run,
        measure_map,
        measure_map_after_startup,
        measure_run_stages,
    )

    result: dict[str, Any] = {"machine": machine_info()}
    result["run"] = measure_run_stages(args.case, [], args.repeats)
    if not args.no_map:
        result["map"] = measure_map(args.sweep, args.jobs, args.map_repeats)
        result["map"]["after_startup"] = measure_map_after_startup(args.sweep)
        result["map"]["overhead_stages"] = measure_map_overhead(args.sweep, args.repeats)
        result["map"]["scaling_after_startup"] = measure_map_scaling(
            args.sweep, args.jobs, args.map_repeats
        )
        model = result["map"]["model"]
        if model:
            result["map"]["extrapolated"] = {
                "16 workers": extrapolate(model, 16),
                "16 workers, 10x points": extrapolate(model, 16, 10.0),
            }
    if args.first_run:
        result["first_run"] = measure_first_run(args.case)
    return result


def format_system(result: dict[str, Any]) -> str:
    """The console table of a ``bench-system`` result."""
    lines = [f"load average {result['machine']['load_average']}", "stage: wall / CPU [s]"]
    for name, t in result["run"]["stages"].items():
        lines.append(f"  {name:28s} {t['wall [s]']:7.3f} / {t['cpu [s]']:7.3f}")
    for name, t in result["run"]["run"].items():
        lines.append(f"  recipsim run, {name:14s} {t['wall [s]']:7.3f} / {t['cpu [s]']:7.3f}")
    for name, roles in result["run"].get("phases", {}).items():
        lines.append(f"recipsim run, {name}: phase ends [s after start], medians")
        for role, marks in roles.items():
            lines.append(f"  {role}: " + ", ".join(f"{m} {t:.3f}" for m, t in marks.items()))
    if "map" in result:
        m = result["map"]
        lines.append(f"map {m['sweep']}: {m['points']} points, solves {m['solve_sum [s]']:.2f} s")
        for jobs, t in m["runs"].items():
            lines.append(
                f"  {jobs} worker(s): {t['wall [s]']:.2f} s wall, {t['cpu [s]']:.2f} s CPU, "
                f"efficiency {t['efficiency [-]']:.2f}"
            )
        if m["overhead_ratio [-]"] is not None:
            lines.append(
                f"  overhead / solves (1 worker, end to end): {m['overhead_ratio [-]']:.2f}"
            )
        for label, t in m.get("after_startup", {}).items():
            if t["overhead_ratio [-]"] is not None:
                lines.append(
                    f"  overhead / solves (1 worker, after start-up, {label}): "
                    f"{t['overhead_ratio [-]']:.2f} ({t['wall [s]']:.2f} s, "
                    f"solves {t['solve_sum [s]']:.2f} s)"
                )
        if "overhead_stages" in m:
            from recipsim.studies.bench.map_overhead import format_overhead_stages

            lines.extend(format_overhead_stages(m["overhead_stages"]))
        if m["model"]:
            serial, parallel = m["model"]["serial [s]"], m["model"]["parallel [s]"]
            lines.append(f"  T(J) = {serial:.2f} s + {parallel:.2f} s / J")
            for label, t in m.get("extrapolated", {}).items():
                lines.append(
                    f"  {label}: {t['wall [s]']:.2f} s, efficiency {t['efficiency [-]']:.2f}"
                )
        scaling = m.get("scaling_after_startup")
        if scaling:
            lines.append("  after start-up, no map plots:")
            for jobs, t in scaling["runs"].items():
                lines.append(
                    f"  {jobs} worker(s): {t['wall [s]']:.2f} s wall "
                    f"({t['points_per_second']:.0f} points/s, parent CPU "
                    f"{t['parent_cpu [s]']:.2f} s), efficiency {t['efficiency [-]']:.2f}; "
                    f"solves {t['solve_slowdown [-]']:.2f}x their time on the fewest "
                    f"workers: at most {t['efficiency_ceiling [-]']:.2f}"
                )
    if "first_run" in result:
        f = result["first_run"]
        lines.append(
            f"first run (empty caches): {f['wall [s]']:.1f} s wall, {f['cpu [s]']:.1f} s CPU; "
            f"second {f['second_wall [s]']:.1f} s"
        )
    return "\n".join(lines)
