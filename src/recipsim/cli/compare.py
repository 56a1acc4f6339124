"""``recipsim compare CASE_A CASE_B [--out DIR] [--set KEY=VALUE] [--no-plots]``.

Runs two cases (e.g. the coupled cylinder + flexible mechanism run against the flexible
mechanism under a tabulated pressure curve; two refrigerants; pinned against flexible)
and writes one output directory ``<out>/<A>_vs_<B>/`` (``<A>_vs_<B>+<digest>`` when
``--set``, ``--set-a`` or ``--set-b`` is given), built beside its destination and
swapped in whole; ``<dir>`` below::

    <dir>/comparison.csv     quantity, group, <A>, <B>, difference, relative_difference [-]
    <dir>/cases.csv          per case: file, overrides, refrigerant, options, converged
    <dir>/overlay_*.png      pressure, p-V, torque, bearing loads, orbits (one curve per case)
    <dir>/provenance.json    versions, command, the two case files and overrides
    <dir>/<A>/, <dir>/<B>/   each case's full report (as ``recipsim run``)

``--set`` applies to both cases, ``--set-a`` / ``--set-b`` to one (after ``--set``), so
one file can be compared with itself at another setting. Labels are the case names,
suffixed ``_a``/``_b`` when equal. Default ``--out``: ``reports/compare``.

Exit status: 0 success; 1 a simulation failed (the message names the case file, crank
angle and state); 2 invalid input (missing file, bad ``--set``, an ``--out`` that exists and was not
written by recipsim). Nothing is written unless both cases ran.
"""

from __future__ import annotations

import argparse
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pandas as pd

from recipsim.atomic import atomic_directory, check_replaceable
from recipsim.case.case import Case
from recipsim.case.load import load_case
from recipsim.cli.compare_console import console_summary
from recipsim.cli.options import add_common_options, exit_status
from recipsim.errors import SolverError
from recipsim.pipeline import simulate_case
from recipsim.report.case_report import json_text, report_dir, write_case_report
from recipsim.report.compare_plots import save_overlay_figures
from recipsim.report.figure_names import OVERLAY_NAMES
from recipsim.results.case_run import CaseRun
from recipsim.studies.compare import case_labels, case_records, comparison_table


@dataclass
class Comparison:
    """The result of :func:`run_comparison`.

    Attributes
    ----------
    runs : tuple of CaseRun
        Case A and case B as simulated.
    labels : tuple of str
        Their column labels in ``comparison.csv``.
    table : pandas.DataFrame
        The comparison table (``comparison.csv``,
        :func:`recipsim.studies.compare.comparison_table`).
    cases : pandas.DataFrame
        The text columns per case (``cases.csv``, :func:`recipsim.studies.compare.case_records`).
    out : Path
        The output directory.
    wall_time : float
        Wall time of the comparison (loading, both runs, writing) [s].
    """

    runs: tuple[CaseRun, CaseRun]
    labels: tuple[str, str]
    table: pd.DataFrame
    cases: pd.DataFrame
    out: Path
    wall_time: float


def add_compare_parser(sub: Any) -> argparse.ArgumentParser:
    """Register the ``compare`` subcommand on the subparsers ``sub``."""
    parser: argparse.ArgumentParser = sub.add_parser(
        "compare",
        help="run two cases and compare them (comparison.csv, overlay plots)",
        description=(
            "Run two cases and write comparison.csv (one row per summary quantity: both "
            "values, B - A and (B - A)/|A|), cases.csv, overlay plots and each case's "
            "report. See reports/README.md."
        ),
    )
    parser.add_argument("case_a", type=Path, help="case A (TOML), the base of the differences")
    parser.add_argument("case_b", type=Path, help="case B (TOML)")
    add_common_options(
        parser,
        Path("reports/compare"),
        "parent directory of the comparison: it goes to OUT/<A>_vs_<B>/ "
        "(OUT/<A>_vs_<B>+<digest of the --set values>/ with --set), replaced whole "
        "(default: reports/compare/)",
    )
    for side in ("a", "b"):
        parser.add_argument(
            f"--set-{side}",
            dest=f"overrides_{side}",
            action="append",
            default=[],
            metavar="KEY=VALUE",
            help=f"override a value of case {side.upper()} only (after --set); repeatable",
        )
    parser.add_argument("--quiet", action="store_true", help="print nothing but errors")
    parser.set_defaults(handler=run_compare_command)
    return parser


def run_compare_command(args: argparse.Namespace, argv: list[str] | None) -> int:
    """``recipsim compare``: returns the exit status (0, 1 or 2)."""

    def action() -> int:
        comparison = run_comparison(
            args.case_a,
            args.case_b,
            overrides=args.overrides,
            overrides_a=args.overrides_a,
            overrides_b=args.overrides_b,
            parent=args.out,
            plots=not args.no_plots,
            argv=argv if argv is not None else sys.argv,
            allow_external_paths=args.allow_external_paths,
        )
        if not args.quiet:
            rows = [run.row for run in comparison.runs]
            out, wall = comparison.out, comparison.wall_time
            print(console_summary(comparison.labels, comparison.table, rows, out, wall))
        return 0

    return exit_status(action)


def _simulate(path: Path, case: Case, argv: list[str] | None) -> CaseRun:
    """Run one case; a solver failure names the case file."""
    try:
        return simulate_case(case, argv)
    except SolverError as exc:
        raise SolverError(f"{path}: {exc}") from exc


def run_comparison(
    path_a: Path,
    path_b: Path,
    overrides: list[str] | None = None,
    overrides_a: list[str] | None = None,
    overrides_b: list[str] | None = None,
    out: Path | None = None,
    plots: bool = True,
    argv: list[str] | None = None,
    allow_external_paths: bool = False,
    parent: Path | None = None,
) -> Comparison:
    """Run two cases and write their comparison directory atomically.

    Parameters
    ----------
    path_a, path_b : Path
        Case files; A is the base of the differences.
    overrides : list of str, optional
        ``KEY=VALUE`` applied to both cases.
    overrides_a, overrides_b : list of str, optional
        ``KEY=VALUE`` applied to one case, after ``overrides``.
    out : Path, optional
        Output directory itself (replaced whole); by default ``<parent>/<A>_vs_<B>``
        (``+<digest>`` with overrides, :func:`recipsim.report.case_report.report_name`).
    plots : bool
        Write the overlay figures and each report's figures.
    argv : list of str, optional
        Command line recorded in the provenance.
    allow_external_paths : bool
        See :func:`recipsim.case.load.load_case`.
    parent : Path, optional
        Parent of the default output directory (``--out``); default ``reports/compare``.

    Returns
    -------
    Comparison

    Raises
    ------
    CaseError
        A case file is missing or invalid, or ``out`` exists and is not a comparison
        directory; raised before anything is simulated or written.
    SolverError
        A case failed (the message names its file); nothing is written.
    """
    start = time.perf_counter()
    paths = (Path(path_a), Path(path_b))
    sets = [
        [*(overrides or []), *(overrides_a or [])],
        [*(overrides or []), *(overrides_b or [])],
    ]
    cases = [
        load_case(p, s, allow_external_paths=allow_external_paths)
        for p, s in zip(paths, sets, strict=True)
    ]  # both before running
    labels = case_labels(cases[0].name, cases[1].name)
    target = _output_directory(out, parent, [c.name for c in cases], sets)
    runs = (_simulate(paths[0], cases[0], argv), _simulate(paths[1], cases[1], argv))
    table = comparison_table(runs[0].row, runs[1].row, *labels)
    extra = [
        {"file": str(p), "overrides": "; ".join(s), "report": f"{label}/"}
        for p, s, label in zip(paths, sets, labels, strict=True)
    ]
    records = case_records([r.row for r in runs], labels, extra)
    cases = pd.DataFrame.from_records(records)
    _write(target, runs, labels, sets, (table, cases), plots, argv, start)
    return Comparison(runs, labels, table, cases, target, time.perf_counter() - start)


#: Default ``--out`` of ``recipsim compare`` (the parent of ``<A>_vs_<B>``).
DEFAULT_PARENT = Path("reports/compare")


def _output_directory(
    out: Path | None, parent: Path | None, names: list[str], sets: list[list[str]]
) -> Path:
    """The comparison's directory, checked before anything runs: ``out``, or
    ``<parent>/<A>_vs_<B>`` (``+<digest>`` of the overrides)."""
    if out is not None:
        check_replaceable(Path(out))
        return Path(out)
    sides = [f"{side}.{text}" for side, s in zip("ab", sets, strict=True) for text in s]
    return report_dir(parent or DEFAULT_PARENT, f"{names[0]}_vs_{names[1]}", sides)


def _write(
    target: Path,
    runs: tuple[CaseRun, CaseRun],
    labels: tuple[str, str],
    sets: list[list[str]],
    tables: tuple[pd.DataFrame, pd.DataFrame],
    plots: bool,
    argv: list[str] | None,
    start: float,
) -> None:
    """Build the output directory beside ``target`` and swap it in (``tables``: the
    comparison table and the cases' table)."""
    table, cases = tables
    with atomic_directory(target) as tmp:
        for run, label, s in zip(runs, labels, sets, strict=True):
            write_case_report(run, tmp / label, s, plots)
        if plots:
            plenum = {
                label: (
                    run.case.operating_point.suction_pressure,
                    run.case.operating_point.discharge_pressure,
                )
                for run, label in zip(runs, labels, strict=True)
            }
            cycles = {label: run.cycle for run, label in zip(runs, labels, strict=True)}
            save_overlay_figures(cycles, tmp, plenum, OVERLAY_NAMES)
        table.to_csv(tmp / "comparison.csv", index=False)
        cases.to_csv(tmp / "cases.csv", index=False)
        meta = _provenance(runs, labels, cases.to_dict("records"), argv)
        meta["wall_time_s"] = time.perf_counter() - start
        (tmp / "provenance.json").write_text(json_text(meta))


def _provenance(
    runs: tuple[CaseRun, CaseRun],
    labels: tuple[str, str],
    records: list[dict[str, Any]],
    argv: list[str] | None,
) -> dict[str, Any]:
    """Versions and command (from case A's provenance) and, per case, file, overrides,
    options and solver statistics."""
    per_case = ("property_backend", "fluid", "options", "solver")
    shared = {k: v for k, v in runs[0].meta.items() if k in _SHARED_KEYS}
    shared["command"] = argv or sys.argv
    shared["cases"] = {
        label: {
            "file": record["file"],
            "overrides": record["overrides"],
            "name": run.case.name,
            "report": record["report"],
            **{k: run.meta[k] for k in per_case if k in run.meta},
            **{k: run.meta[k] for k in _SOLVER_KEYS if k in run.meta},
        }
        for run, label, record in zip(runs, labels, records, strict=True)
    }
    return shared


_SHARED_KEYS = (
    "recipsim",
    "git_commit",
    "python",
    "platform",
    "CoolProp",
    "numpy",
    "scipy",
    "numba",
    "pandas",
    "created",
)
_SOLVER_KEYS = ("revolutions", "cycle_residual", "rhs_evaluations", "steps", "wall_time_s")
