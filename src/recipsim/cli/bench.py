"""``recipsim bench CASE [--out DIR] [--repeats N] [--quick] [--set KEY=VALUE ...]``.

Runs the ladder of :mod:`recipsim.studies.bench.ladder` on one case against its
tight-tolerance reference and writes ``work_precision.csv``, ``work_precision.png`` and
``bench.json`` to ``<out>/<case>/`` (``<case>+<digest>`` when ``--set`` is given, see
:func:`recipsim.report.case_report.report_name`; default ``--out``: ``reports/bench``),
then names the cheapest rung within 1e-3 and its speed-up over the pure-Python baseline.

Exit status: 0 done (whatever the rungs' statuses); 1 the reference failed or did not
converge; 2 invalid case or option.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from recipsim.case.load import load_case
from recipsim.cli.options import add_common_options, exit_status, positive_int
from recipsim.errors import SolverError
from recipsim.report.case_report import report_dir
from recipsim.studies.bench.baseline import run_baseline
from recipsim.studies.bench.errors import error_columns
from recipsim.studies.bench.ladder import (
    Rung,
    build_ladder,
    reference_overrides,
    select_rungs,
    self_check_overrides,
)
from recipsim.studies.bench.measure import OK, run_rung
from recipsim.studies.bench.report import (
    CPU,
    WALL,
    console_table,
    outcome_row,
    speedup,
    table,
    write_bench,
)
from recipsim.studies.bench.system import machine_info

DEFAULT_OUT = Path("reports/bench")
#: Baseline rungs repeat at most this often (each takes seconds to minutes).
BASELINE_REPEATS = 3
#: Fast rungs repeat until their timed solves add up to this [s] (at most 50 repeats).
MIN_TIME = 1.0


def add_bench_parser(sub: Any) -> argparse.ArgumentParser:
    """Add the ``bench`` subcommand to the subparsers ``sub`` of the ``recipsim`` parser."""
    parser: argparse.ArgumentParser = sub.add_parser(
        "bench",
        help="speed against error: a ladder of solver settings against a tight reference",
        description=(
            "Run a ladder of integrator x tolerance x property backend x periodic solver x "
            "fidelity settings (and a pure-Python solve_ivp baseline) on CASE, compare each "
            "with a tight-tolerance reference and write work_precision.csv, "
            "work_precision.png and bench.json. See the README, 'Speed against error'."
        ),
    )
    parser.add_argument("case", type=Path, help="case file (TOML)")
    add_common_options(
        parser,
        DEFAULT_OUT,
        "parent directory of the bench: it goes to OUT/<case name>/ "
        "(OUT/<case name>+<digest of the --set values>/ with --set) (default: reports/bench/)",
        False,
    )
    parser.add_argument(
        "--repeats",
        type=positive_int,
        default=5,
        metavar="N",
        help="timed solves per rung, median reported (default 5; baseline at most 3)",
    )
    parser.add_argument("--quick", action="store_true", help="a reduced ladder (tests, CI)")
    parser.add_argument("--no-baseline", action="store_true", help="skip the pure-Python rungs")
    parser.add_argument(
        "--rungs",
        metavar="REGEX",
        default=None,
        help="run only the rungs whose name matches this regular expression (searched, "
        "e.g. 'dopri5_stiff' or 'rtol=1e-05'); the reference always runs",
    )
    parser.add_argument(
        "--budget",
        type=float,
        default=60.0,
        metavar="SECONDS",
        help="stop repeating a rung once its timed solves took this long (default 60)",
    )
    parser.add_argument(
        "--rank-by",
        choices=("wall", "cpu"),
        default="wall",
        help="time that ranks the rungs and sets the plot's x axis: median wall time "
        "(default) or CPU time of the solve (steadier on a machine shared with other jobs)",
    )
    parser.add_argument("--quiet", action="store_true", help="print only the result")
    parser.set_defaults(handler=run_bench_command)
    return parser


def default_out(case_name: str, overrides: list[str], parent: Path = DEFAULT_OUT) -> Path:
    """``<parent>/<case>`` or, with overrides, ``<parent>/<case>+<digest>``, checked to be
    replaceable (:func:`recipsim.report.case_report.report_dir`)."""
    return report_dir(parent, case_name, overrides)


def run_bench_command(args: argparse.Namespace, argv: list[str] | None) -> int:
    """Handler of ``recipsim bench``."""
    return exit_status(lambda: _bench(args, argv), str(args.case))


def _bench(args: argparse.Namespace, argv: list[str] | None) -> int:

    say = (lambda *a: None) if args.quiet else (lambda *a: print(*a, flush=True))
    base = load_case(args.case, args.overrides)
    out_dir = default_out(base.name, args.overrides, args.out)
    ladder = select_rungs(build_ladder(base, args.quick, not args.no_baseline), args.rungs)
    started = time.time()
    meta = _meta(args, argv, base.name)
    warmed: set[tuple[str, ...]] = set()
    ref = _reference(args, base, warmed, meta, say)
    if not args.quick:
        _self_check(args, base, warmed, ref, meta, say)
    frame = table(_run_ladder(args, base, ladder, warmed, ref, say))
    by = CPU if args.rank_by == "cpu" else WALL
    result = speedup(frame, by=by)
    meta["result"] = result
    meta["machine_end"] = machine_info()
    meta["elapsed [s]"] = time.time() - started
    title = f"recipsim bench {base.name} {' '.join(args.overrides)}".strip()
    where = write_bench(Path(out_dir), frame, meta, title, plots=not args.no_plots, by=by)
    if not args.quiet:
        print()
        print(console_table(frame))
        print()
    print(_verdict(result) + f"\n-> {where}")
    return 0


def _meta(args: argparse.Namespace, argv: list[str] | None, case_name: str) -> dict[str, Any]:
    """What ``bench.json`` records of the command and the machine before the rungs run."""
    return {
        "case": str(args.case),
        "case_name": case_name,
        "overrides": list(args.overrides),
        "command": argv if argv is not None else sys.argv,
        "quick": bool(args.quick),
        "rungs": args.rungs,
        "repeats": args.repeats,
        "machine_start": machine_info(),
        "timing": (
            "median over repeats of the wall (and CPU) time of the periodic solve, from the "
            "model's initial state to the converged revolution, in one process on one core, "
            "after imports, case loading, model building and an untimed warm-up run per kind "
            "of rung (numba load/compile); the pure-Python baseline runs in its own process "
            "with NUMBA_DISABLE_JIT=1, timed the same way"
        ),
    }


def _reference(
    args: argparse.Namespace,
    base: Any,
    warmed: set[tuple[str, ...]],
    meta: dict[str, Any],
    say: Callable[..., None],
) -> Any:
    """The tight-tolerance reference every rung is compared with, recorded in ``meta``."""
    say(f"reference: {' '.join(reference_overrides())}")
    ref = run_rung(
        args.case,
        args.overrides,
        Rung("reference", overrides=reference_overrides()),
        base,
        repeats=1,
        warmed=warmed,
    )
    if ref.status != OK or ref.trace is None:
        raise SolverError(f"the reference did not converge ({ref.status}): {ref.message}")
    meta["reference"] = {
        "overrides": list(reference_overrides()),
        "revolutions": ref.revolutions,
        "cycle_residual": ref.residual,
        "rhs_evaluations": ref.rhs_evaluations,
        "periodic_used": ref.periodic_used,
        "wall_time [s]": ref.wall_time,
        "quantities": ref.quantities,
    }
    say(f"  {ref.revolutions} revolutions, residual {ref.residual:.1e}, {ref.wall_time:.2f} s")
    return ref


def _self_check(
    args: argparse.Namespace,
    base: Any,
    warmed: set[tuple[str, ...]],
    ref: Any,
    meta: dict[str, Any],
    say: Callable[..., None],
) -> None:
    """The reference against a tighter one still: how far its own error goes."""
    check = run_rung(
        args.case,
        args.overrides,
        Rung("self-check", overrides=self_check_overrides()),
        base,
        repeats=1,
        warmed=warmed,
    )
    if check.usable:
        errs = error_columns(check.quantities, ref.quantities, check.trace, ref.trace)
        meta["reference"]["self_check"] = {
            "overrides": list(self_check_overrides()),
            "revolutions": check.revolutions,
            "status": check.status,
            "errors": errs,
        }
        say(
            f"  against {' '.join(self_check_overrides())} ({check.status}, "
            f"{check.revolutions} revolutions): max error {errs['max_error [-]']:.1e}"
        )
    else:
        meta["reference"]["self_check"] = {"status": check.status, "message": check.message}


def _run_ladder(
    args: argparse.Namespace,
    base: Any,
    ladder: list[Any],
    warmed: set[tuple[str, ...]],
    ref: Any,
    say: Callable[..., None],
) -> list[dict[str, Any]]:
    """One row per rung: its timings and its errors against the reference."""
    min_time = 0.0 if args.quick else MIN_TIME
    rows = []
    for rung in ladder:
        if rung.baseline:
            outcome = run_baseline(
                args.case,
                args.overrides,
                rung,
                base,
                min(args.repeats, BASELINE_REPEATS),
                budget=2 * args.budget,
            )
        else:
            outcome = run_rung(
                args.case,
                args.overrides,
                rung,
                base,
                args.repeats,
                budget=args.budget,
                warmed=warmed,
                min_time=min_time,
            )
        row = outcome_row(outcome, ref.quantities, ref.trace)
        rows.append(row)
        say(
            f"{rung.name:48s} {outcome.status:11s} {row['median_wall_time [s]']:9.4f} s  "
            f"max error {row['max_error [-]']:.2e}"
            + (f"  ({outcome.message[:100]})" if outcome.message else "")
        )
    return rows


def _verdict(result: dict[str, Any]) -> str:
    limit = result["error_limit"]
    best = result["cheapest"]
    if best is None:
        return f"no rung of the case's own fidelity is within {limit:g}"
    wall, cpu = "median_wall_time [s]", "median_cpu_time [s]"
    text = (
        f"cheapest within {limit:g} (by {result['ranked_by']}): {best['rung']} "
        f"(wall {best[wall]:.4f} s, CPU {best[cpu]:.4f} s, max error {best['max_error [-]']:.1e})"
    )
    base = result["baseline"]
    if base is None:
        return text + "; no baseline rung within the limit"
    return text + (
        f"\npure-Python solve_ivp baseline within {limit:g}: {base['rung']} (wall "
        f"{base[wall]:.3f} s, CPU {base[cpu]:.3f} s): {result['speedup_wall']:.0f}x faster in "
        f"wall time, {result['speedup_cpu']:.0f}x in CPU time"
    )
