"""``recipsim check DIR_OR_FILES [--fast] [--jobs N] [--set KEY=VALUE] [--out DIR]``.

Runs every case (see :mod:`recipsim.studies.check`), prints a table (case, expected and actual
outcome, revolutions, wall time, mass / energy / drive closures, message) and writes
``<out>/<name>/check.csv`` atomically, ``<name>`` the checked folder's or file's (``hard``;
several joined by ``_``), ``+<digest>`` with ``--set``. Exit status: 0 every outcome
matches its expectation, 1 some do not, 2 invalid input to the check itself (a missing
path, a bad expectations file). This module imports nothing heavy at module level.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from recipsim.atomic import MAX_NAME_LENGTH, atomic_directory, name_from_stem
from recipsim.case.files import shipped_path
from recipsim.cli.options import add_common_options, exit_status, positive_int
from recipsim.report.case_report import report_dir
from recipsim.studies.check.run import run_check
from recipsim.studies.check.table import format_table, write_check_csv


def add_check_parser(sub: Any) -> argparse.ArgumentParser:
    """Add the ``check`` subcommand to the subparsers ``sub`` of the ``recipsim`` parser."""
    parser: argparse.ArgumentParser = sub.add_parser(
        "check",
        help="run a set of (hard) cases and compare each outcome with its expectation",
        description=(
            "Run every case of the given directories or files (e.g. 'hard', the shipped "
            "hard cases), compare each outcome (converged, not converged, refused, "
            "failed) and its mass, energy and drive closures with the expectations.toml "
            "beside the cases, print a table and write <out>/<name>/check.csv. A failing case is a "
            "row; the check goes on."
        ),
    )
    parser.add_argument(
        "paths",
        nargs="+",
        type=shipped_path,
        help="case directories or files, or a shipped folder or case by name (e.g. hard)",
    )
    parser.add_argument(
        "--fast",
        action="store_true",
        help="fast settings for CI (rtol 1e-5 and the expectations' per-case 'fast' overrides)",
    )
    parser.add_argument(
        "-j",
        "--jobs",
        type=positive_int,
        default=1,
        metavar="N",
        help="worker processes (default 1: one case after the other in this process)",
    )
    parser.add_argument(
        "--expectations",
        type=Path,
        default=None,
        metavar="FILE",
        help="expectations file (default: expectations.toml beside the cases)",
    )
    parser.add_argument("--quiet", action="store_true", help="print the table only")
    add_common_options(
        parser,
        Path("reports/check"),
        "parent directory of the check: it goes to OUT/<name>/ (the checked folder's or "
        "file's name; +<digest of the --set values> with --set) (default: reports/check/)",
        False,
    )
    parser.set_defaults(handler=run_check_command)
    return parser


def run_check_command(args: argparse.Namespace, argv: list[str] | None = None) -> int:
    """Run the ``check`` subcommand; returns the exit status."""
    label = " ".join(map(str, args.paths))
    return exit_status(lambda: _check(args), label)


def check_name(paths: list[Path]) -> str:
    """Name of a check's output directory: the checked folders' or files' names."""
    return name_from_stem("_".join(Path(p).stem for p in paths))[:MAX_NAME_LENGTH]


def _check(args: argparse.Namespace) -> int:

    target = report_dir(args.out, check_name(args.paths), args.overrides)  # before running

    def progress(row: Any) -> None:
        if not args.quiet:
            status = "ok" if row.matches else "UNEXPECTED"
            outcome = row.outcome.replace("_", " ")
            print(f"  {row.case}: {outcome} ({row.wall_time:.1f} s) {status}", file=sys.stderr)

    rows = run_check(
        args.paths,
        overrides=args.overrides,
        fast=args.fast,
        jobs=args.jobs,
        expectations_file=args.expectations,
        progress=progress,
    )
    print(format_table(rows))
    with atomic_directory(target) as tmp:
        write_check_csv(rows, tmp)
    path = target / "check.csv"
    if not args.quiet:
        print(f"-> {path}")
    return 0 if all(r.matches for r in rows) else 1
