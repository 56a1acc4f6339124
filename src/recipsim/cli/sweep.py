"""``recipsim sweep SWEEP [--jobs N] [--scheduler ADDRESS] [--out DIR] ...``.

Exit status: 0 every point converged; 1 some point did not (the table is written and
says which), a worker died or the Dask cluster failed; 2 invalid sweep file or
option; 130 interrupted with Ctrl-C (finished points are kept: rerun to resume).
"""

from __future__ import annotations

import argparse
import shlex
import sys
import time
from pathlib import Path
from typing import Any

from recipsim.cli.options import add_common_options, exit_status, positive_float, positive_int
from recipsim.studies.sweep.engine import SweepInterrupted, run_sweep
from recipsim.studies.sweep.outputs import SweepOutcome
from recipsim.studies.sweep.runner import WorkerLost

_MAX_LISTED = 8

_SWITCHES = (
    ("--reports", "also write a full report for every point"),
    ("--parquet", "also write summary.parquet (needs pyarrow)"),
    ("--retry-failed", "recompute points recorded as not ok (by default they are kept)"),
    ("--fresh", "forget finished points and compute every point"),
    ("--quiet", "no progress bar and no summary, errors only"),
)


def add_sweep_parser(sub: Any) -> argparse.ArgumentParser:
    """Add the ``sweep`` subcommand to the subparsers ``sub`` of the ``recipsim`` parser."""
    parser: argparse.ArgumentParser = sub.add_parser(
        "sweep",
        help="run an operating map (a sweep file) in parallel, resumable",
        description=(
            "Run every point of a sweep file (a base case, axes combined as a grid, "
            "explicit points) and write <out>/<name>/summary.csv (<out>/<name>+<digest>/ "
            "with --set) and map plots. Each "
            "finished point is kept on disk: rerunning an interrupted sweep computes "
            "only the missing points. See docs/sweeps.md."
        ),
    )
    parser.add_argument(
        "sweep", type=Path, help="sweep file (TOML) or a shipped sweep by name, e.g. lbp_map"
    )
    parser.add_argument(
        "-j",
        "--jobs",
        type=positive_int,
        default=None,
        metavar="N",
        help="worker processes (default: the number of CPUs); 1 runs in this process",
    )
    parser.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        help="run on an existing Dask distributed cluster, e.g. tcp://127.0.0.1:8786",
    )
    parser.add_argument(
        "--scheduler-timeout",
        type=positive_float,
        default=10.0,
        metavar="SECONDS",
        help="give up on a Dask scheduler that does not answer within this time (default 10)",
    )
    parser.add_argument(
        "--max-points",
        type=positive_int,
        default=None,
        metavar="N",
        help="refuse sweeps of more points (default: the sweep file's max_points, else 100000)",
    )
    add_common_options(
        parser,
        Path("reports/sweeps"),
        "parent directory of the sweep: it goes to OUT/<sweep name>/ "
        "(OUT/<sweep name>+<digest of the --set values>/ with --set) (default: reports/sweeps/)",
    )
    parser.add_argument(
        "--plots",
        type=lambda text: tuple(n.strip() for n in text.split(",") if n.strip()),
        default=None,
        metavar="NAMES",
        help=(
            "draw only these map plots, comma-separated (cooling_capacity, shaft_power, COP, "
            "volumetric_efficiency, isentropic_efficiency, bearing_loads)"
        ),
    )
    for flag, help_text in _SWITCHES:
        parser.add_argument(flag, action="store_true", help=help_text)
    parser.set_defaults(handler=run_sweep_command)
    return parser


def _command_line(argv: list[str] | None) -> str:
    args = argv if argv is not None else sys.argv[1:]
    return " ".join(shlex.quote(a) for a in ["recipsim", *args])


def run_sweep_command(args: argparse.Namespace, argv: list[str] | None = None) -> int:
    """Run the ``sweep`` subcommand; returns the exit status."""
    return exit_status(lambda: _run_sweep(args, argv, time.perf_counter()), str(args.sweep))


def _run_sweep(args: argparse.Namespace, argv: list[str] | None, started: float) -> int:
    resume = f"rerun `{_command_line(argv)}` to resume (finished points are not recomputed)"
    try:
        outcome = run_sweep(
            args.sweep,
            jobs=args.jobs,
            scheduler=args.scheduler,
            out=args.out,
            overrides=args.overrides,
            reports=args.reports,
            plots=False if args.no_plots else (True if args.plots is None else args.plots),
            parquet=args.parquet,
            retry_failed=args.retry_failed,
            fresh=args.fresh,
            progress=not args.quiet,
            argv=["recipsim", *(argv if argv is not None else sys.argv[1:])],
            started=started,
            max_points=args.max_points,
            scheduler_timeout=args.scheduler_timeout,
            allow_external_paths=args.allow_external_paths,
        )
    except (SweepInterrupted, WorkerLost) as exc:
        print(f"recipsim: {exc}; {resume}", file=sys.stderr)
        return 130 if isinstance(exc, SweepInterrupted) else 1
    if not args.quiet:
        print(format_outcome(outcome))
    return 0 if outcome.n_failed == 0 else 1


def format_outcome(outcome: SweepOutcome) -> str:
    """The closing lines: counts, timing and the points that did not converge."""
    table = outcome.table
    counts = outcome.counts
    bad = {k: v for k, v in sorted(counts.items()) if k != "ok"}
    detail = f" ({', '.join(f'{v} {k}' for k, v in bad.items())})" if bad else ""
    computed = len(outcome.computed)
    rate = f", {computed / outcome.wall_time:.1f} points/s" if computed else ""
    if outcome.scheduler:
        where = f", Dask cluster {outcome.scheduler}"
    elif outcome.jobs:
        where = f", {outcome.jobs} process{'es' if outcome.jobs > 1 else ''}"
    else:
        where = ""
    lines = [
        f"{outcome.spec.name}: {outcome.n_points} points: {outcome.n_ok} ok, "
        f"{outcome.n_failed} failed{detail}; {computed} computed, {len(outcome.reused)} "
        f"reused; {outcome.wall_time:.1f} s{rate}{where}",
        f"  -> {outcome.directory / 'summary.csv'}",
    ]
    status, messages, points = (table[c].tolist() for c in ("status", "message", "point"))
    failed = [i for i, s in enumerate(status) if s != "ok"]
    for i in failed[:_MAX_LISTED]:
        values = ", ".join(f"{c}={_short(table[c].iloc[i])}" for c in outcome.axes)
        message = _clipped(str(messages[i]))
        lines.append(f"  point {points[i]} [{status[i]}] {values}: {message}")
    if len(failed) > _MAX_LISTED:
        lines.append(f"  ... and {len(failed) - _MAX_LISTED} more (see the status column)")
    warned = [i for i, s in enumerate(status) if s == "ok" and _text(messages[i])]
    if warned:
        first = warned[0]
        lines.append(
            f"  {len(warned)} ok point{'s' if len(warned) > 1 else ''} with warnings (see the "
            f"message column), the first: point {points[first]}: " + _clipped(str(messages[first]))
        )
    return "\n".join(lines)


def _text(value: Any) -> str:
    """A message cell as text: empty where it is missing (None or NaN)."""
    if value is None or (isinstance(value, float) and value != value):
        return ""
    return str(value)


def _clipped(message: str, most: int = 200) -> str:
    """``message``, cut to ``most`` characters with an ellipsis if longer."""
    return message if len(message) <= most else message[: most - 3] + "..."


def _short(value: Any) -> str:
    return f"{value:.6g}" if isinstance(value, float) else str(value)
