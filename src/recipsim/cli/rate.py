"""``recipsim rate CASE [--standard S] [--evaporating=A:B:STEP] [--condensing=A:B:STEP]
[--catalogue FILE] [--coefficients FILE] [--jobs N] [--scheduler ADDRESS] ...``.

Rates a compressor as its maker does (:mod:`recipsim.studies.rate`): runs the case over a
grid of evaporating and condensing temperatures at a standard's conditions, in parallel
and resumable as a sweep, fits the ten coefficients of capacity, power input, current
and mass flow, and writes ``<out>/<case>_<standard>/`` (default ``--out``:
``reports/rate``): ``ratings.csv``, ``rating_table.csv``, ``coefficients.csv``,
``residuals.csv``, figures and, with ``--catalogue`` / ``--coefficients``, the comparison
with the maker's figures. Exit status: 0 rated (failed points are reported and left out),
1 fewer than ten good points or a worker lost, 2 invalid input, 130 interrupted (finished
points are kept: rerun to resume).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path
from typing import Any

from recipsim.case.load import load_case
from recipsim.cli.options import add_common_options, exit_status, positive_float, positive_int
from recipsim.cli.sweep import _command_line
from recipsim.report.case_report import report_dir
from recipsim.studies.rate.grid import APPLICATIONS, standard_of
from recipsim.studies.rate.polynomial import TEMPERATURE_UNITS
from recipsim.studies.rate.report import write_rating
from recipsim.studies.rate.run import Rating, rate_case
from recipsim.studies.rate.tables import rating_table
from recipsim.studies.sweep.engine import SweepInterrupted
from recipsim.studies.sweep.runner import WorkerLost


def add_rate_parser(sub: Any) -> None:
    """Register the ``rate`` subcommand."""
    p = sub.add_parser(
        "rate",
        help="rating table and EN 12900 / AHRI 540 ten-coefficient polynomials of a case",
        description=(
            "Run a case over a grid of evaporating and condensing temperatures at a rating "
            "standard's conditions (in parallel, resumable), fit the ten-coefficient "
            "polynomials of capacity, power input, current and mass flow, and compare with "
            "a catalogue or a maker's coefficients. Give negative temperatures with '=': "
            "--evaporating=-35:-10:5."
        ),
    )
    p.add_argument("case", type=Path, help="case file (TOML) or a shipped case name")
    p.add_argument(
        "--standard",
        choices=tuple(TEMPERATURE_UNITS),
        default=None,
        help="rating standard (default: the case's own or its rating point's, else EN12900); "
        "EN12900 in degC, AHRI_540 and ASHRAE_LBP in degF",
    )
    for axis, example in (("evaporating", "-35:-10:5"), ("condensing", "35:65:10")):
        p.add_argument(
            f"--{axis}",
            default=None,
            metavar="START:STOP:STEP|A,B,..",
            help=f"{axis} (dew-point) temperatures in the standard's unit, e.g. "
            f"--{axis}={example} (default: the standard's grid for the case's application)",
        )
    p.add_argument(
        "--application",
        choices=tuple(APPLICATIONS),
        default=None,
        help="the default grid's application (default: from the case's evaporating temperature)",
    )
    p.add_argument("--catalogue", type=Path, help="catalogue CSV to run and compare with")
    p.add_argument("--coefficients", type=Path, help="a maker's coefficient CSV to compare with")
    p.add_argument(
        "-j", "--jobs", type=positive_int, default=None, metavar="N",
        help="worker processes (default: the number of CPUs); 1 runs in this process",
    )  # fmt: skip
    p.add_argument("--scheduler", metavar="ADDRESS", help="a Dask distributed scheduler")
    p.add_argument(
        "--scheduler-timeout", type=positive_float, default=10.0, metavar="SECONDS",
        help="give up on a Dask scheduler that does not answer within this time (default 10)",
    )  # fmt: skip
    p.add_argument("--retry-failed", action="store_true", help="recompute failed points")
    p.add_argument("--fresh", action="store_true", help="forget finished points")
    p.add_argument("--quiet", action="store_true", help="no progress bar and no tables")
    add_common_options(
        p,
        Path("reports/rate"),
        "parent directory of the rating: OUT/<case>_<standard>/ (+<digest> with --set) "
        "(default: reports/rate/)",
    )
    p.set_defaults(handler=run_rate_command)


def run_rate_command(args: argparse.Namespace, argv: list[str] | None = None) -> int:
    """Run the ``rate`` subcommand; returns the exit status."""
    return exit_status(lambda: _rate(args, argv, time.perf_counter()), str(args.case))


def _rate(args: argparse.Namespace, argv: list[str] | None, started: float) -> int:
    case = load_case(args.case, args.overrides, allow_external_paths=args.allow_external_paths)
    standard = standard_of(case, args.standard)
    directory = report_dir(args.out, f"{case.name}_{standard}", args.overrides)
    command = ["recipsim", *(argv if argv is not None else sys.argv[1:])]
    options = {
        "jobs": args.jobs,
        "scheduler": args.scheduler,
        "scheduler_timeout": args.scheduler_timeout,
        "retry_failed": args.retry_failed,
        "fresh": args.fresh,
        "progress": not args.quiet,
        "argv": command,
        "started": started,
    }
    try:
        rating = rate_case(
            case, directory, standard=standard, evaporating=args.evaporating,
            condensing=args.condensing, application=args.application,
            catalogue=args.catalogue, coefficients=args.coefficients, sweep_options=options,
        )  # fmt: skip
    except (SweepInterrupted, WorkerLost) as exc:
        resume = f"rerun `{_command_line(argv)}` to resume (finished points are not recomputed)"
        print(f"recipsim: {exc}; {resume}", file=sys.stderr)
        return 130 if isinstance(exc, SweepInterrupted) else 1
    write_rating(rating, plots=not args.no_plots, argv=command)
    if not args.quiet:
        print(format_rating(rating, time.perf_counter() - started))
    return 0


def format_rating(rating: Rating, wall_time: float) -> str:
    """The closing lines: the rating table of capacity and power, the residuals, the
    catalogue comparison, the notes, where the files are and how long it took."""
    grid = rating.grid
    table = rating_table(rating.ratings, grid)
    shown = table[table["quantity"].isin(("cooling_capacity", "power_input"))]
    lines = [
        f"{rating.case.name}: {grid.standard} rating, {len(rating.ratings)} points "
        f"({(rating.ratings['status'] == 'ok').sum()} ok)",
        shown.to_string(index=False, float_format=lambda v: f"{v:.4g}"),
        "",
        "fit residuals:",
        rating.residuals.to_string(index=False, float_format=lambda v: f"{v:.3g}"),
    ]
    if rating.catalogue is not None and len(rating.catalogue):
        columns = ["row", "point", "quantity", "catalogue", "model", "polynomial",
                   "error_model [-]", "error_polynomial [-]"]  # fmt: skip
        lines += ["", "against the catalogue:"]
        lines.append(rating.catalogue[columns].to_string(index=False, float_format=_g))
    lines += [""] + [f"note: {n}" for n in rating.notes]
    lines.append(
        f"{wall_time:.1f} s ({rating.sweep.jobs or 'Dask'} workers, "
        f"{len(rating.sweep.computed)} computed, {len(rating.sweep.reused)} reused) "
        f"-> {rating.directory}"
    )
    return "\n".join(lines)


def _g(value: float) -> str:
    return f"{value:.4g}"
