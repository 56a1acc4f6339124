"""Command line: ``recipsim run CASE... [--out DIR] [--set KEY=VALUE ...]``,
``recipsim sweep SWEEP [--jobs N] [--scheduler ADDRESS] [--out DIR]`` (see
:mod:`recipsim.cli.sweep`), ``compare``, ``paper``, ``bench``, ``check``.

``--out DIR`` means the same in every subcommand: the parent directory of the output
directory, ``DIR/<name>``, where ``<name>`` is the case's (``run``, ``paper``,
``bench``), the sweep's (``sweep``), ``<A>_vs_<B>`` (``compare``) or the checked
folder's (``check``), followed by ``+<digest>`` of the ``--set`` overrides when there
are any (:func:`recipsim.report.case_report.report_name`). Only the defaults differ:
``reports/`` for ``run``, ``reports/<subcommand>/`` for the others (``reports/sweeps/``).

Exit status: 0 success; 1 a simulation failed (message names crank angle and state), a
case did not reach its periodic state within ``solver.max_revolutions`` (its report is
written and says so) or the file system failed (disk full, read-only, no permission);
2 invalid input (message names file, key and what is allowed), no traceback.
"""

from __future__ import annotations

import argparse
import sys
import warnings
from pathlib import Path
from typing import Any

from recipsim.cli.bench import add_bench_parser
from recipsim.cli.calibrate import add_calibrate_parser
from recipsim.cli.cases import add_cases_parser
from recipsim.cli.check import add_check_parser
from recipsim.cli.compare import add_compare_parser
from recipsim.cli.options import add_common_options, exit_status
from recipsim.cli.paper import add_paper_parser
from recipsim.cli.rate import add_rate_parser
from recipsim.cli.sweep import add_sweep_parser
from recipsim.cli.warmup import add_warmup_parser
from recipsim.errors import CaseError
from recipsim.pipeline import run_case
from recipsim.progress import show_notes
from recipsim.report.figure_names import FIGURE_NAMES, check_figure_names
from recipsim.report.summary_text import summary_text
from recipsim.version import __version__

# Each registers its subparser and sets ``handler(args, argv) -> exit status`` on it.
_SUBCOMMANDS = (
    add_sweep_parser,
    add_paper_parser,
    add_compare_parser,
    add_bench_parser,
    add_check_parser,
    add_calibrate_parser,
    add_rate_parser,
    add_warmup_parser,
    add_cases_parser,
)


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="recipsim",
        description="Reciprocating refrigeration compressor simulator (CoolProp cylinder + crank).",
    )
    parser.add_argument("--version", action="version", version=f"recipsim {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="simulate cases and write a report per case")
    run.add_argument("cases", nargs="+", type=Path, help="case files (TOML)")
    add_common_options(
        run,
        Path("reports"),
        "parent directory of the reports: each case's goes to OUT/<case name>/, "
        "OUT/<case name>+<digest of the --set values>/ with --set (default: reports/)",
    )
    run.add_argument(
        "--plots",
        type=figure_list,
        default=None,
        metavar="NAMES",
        help=f"draw only these figures, comma-separated ({', '.join(FIGURE_NAMES)})",
    )
    run.add_argument("--quiet", action="store_true", help="print nothing but errors")
    run.set_defaults(handler=_run_command)
    for register in _SUBCOMMANDS:
        register(sub)
    return parser


def figure_list(text: str) -> tuple[str, ...]:
    """argparse type of ``--plots``: comma-separated figure names, checked."""
    names = tuple(name.strip() for name in text.split(",") if name.strip())
    try:
        return check_figure_names(names)
    except CaseError as exc:
        raise argparse.ArgumentTypeError(exc.message + f" (got {exc.key!r})") from None


def _run_command(args: argparse.Namespace, argv: list[str] | None) -> int:
    """``recipsim run``: every case is attempted; the status is the worst of them."""
    status = 0
    for path in args.cases:

        def one(path: Path = path) -> int:
            run, target = run_case(
                path,
                args.overrides,
                args.out,
                False if args.no_plots else (args.plots if args.plots is not None else True),
                argv if argv is not None else sys.argv,
                args.allow_external_paths,
            )
            row = run.row
            if not args.quiet:
                _print_summary(row, target)
            if not row["converged [-]"]:
                print(
                    f"recipsim: {path}: did not reach its periodic state in "
                    f"{row['revolutions [-]']} revolutions (cycle residual "
                    f"{row['cycle_residual [-]']:.1e}, tolerance in solver.cycle_tolerance); "
                    f"the report says so: {target}",
                    file=sys.stderr,
                )
                return 1
            return 0

        status = max(status, exit_status(one, str(path)))
    return status


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``recipsim`` command."""
    args = _parser().parse_args(argv)
    show_notes(not getattr(args, "quiet", False))  # recipsim: ... lines on standard error
    with warnings.catch_warnings():  # restores the caller's warning display afterwards
        warnings.showwarning = _one_line_warning
        try:
            status: int = args.handler(args, argv)
        except KeyboardInterrupt:  # reports are written atomically: nothing half-written
            print(
                "recipsim: interrupted (Ctrl-C); no report was left half-written", file=sys.stderr
            )
            return 130
    return status


def _one_line_warning(
    message: Warning | str,
    category: type[Warning],
    filename: str,
    lineno: int,
    file: Any = None,
    line: str | None = None,
) -> None:
    """Show a warning as one line on standard error, ``recipsim: warning: ...``."""
    print(f"recipsim: warning: {message}", file=sys.stderr)


def _print_summary(row: dict[str, Any], where: Path) -> None:
    """The key figures (:func:`recipsim.report.summary_text.summary_text`), the bearings'
    RMS loads and where the report went."""
    rms = ", ".join(
        f"{name} {row[f'bearing_rms_{name} [N]']:.0f}"
        for name in ("primary", "secondary", "eccentric", "pin", "piston_top", "piston_skirt")
    )
    print(f"{summary_text(row)}\nbearing RMS loads [N]: {rms}\nreport: {where}")


if __name__ == "__main__":
    raise SystemExit(main())
