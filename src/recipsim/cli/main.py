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
import atexit
import contextlib
import gc
import sys
from collections.abc import Collection
from pathlib import Path
from typing import Any

from recipsim import __version__, start_up_collector, timeline
from recipsim.cli.bench import add_bench_parser
from recipsim.cli.bench_system import add_bench_system_parser
from recipsim.cli.calibrate import add_calibrate_parser
from recipsim.cli.cases import add_cases_parser
from recipsim.cli.check import add_check_parser
from recipsim.cli.compare import add_compare_parser
from recipsim.cli.options import add_common_options, exit_status
from recipsim.cli.paper import add_paper_parser
from recipsim.cli.sweep import add_sweep_parser
from recipsim.cli.warmup import add_warmup_parser
from recipsim.physics import compiled_runtime
from recipsim.report.figure_names import FIGURE_NAMES, check_figure_names

# Each registers its subparser and sets ``handler(args, argv) -> exit status`` on it.
_SUBCOMMANDS = (
    add_sweep_parser,
    add_paper_parser,
    add_compare_parser,
    add_bench_parser,
    add_bench_system_parser,
    add_check_parser,
    add_calibrate_parser,
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
    from recipsim.errors import CaseError

    names = tuple(name.strip() for name in text.split(",") if name.strip())
    try:
        return check_figure_names(names)
    except CaseError as exc:
        raise argparse.ArgumentTypeError(exc.message + f" (got {exc.key!r})") from None


def run_case(
    path: Path,
    overrides: list[str],
    out: Path,
    plots: bool | Collection[str] = True,
    argv: list[str] | None = None,
    allow_external_paths: bool = False,
    fork_figures: bool = False,
) -> tuple[dict[str, Any], Path]:
    """Load, simulate and report one case; returns its summary row and report directory.

    The report goes to ``out/<case name>`` (``out/<case name>+<digest>`` with overrides,
    :func:`recipsim.report.case_report.report_name`). It is checked before the
    simulation (it must be new, empty or a recipsim report), so a refused ``--out``
    costs nothing. ``plots``: every figure, none, or those named. ``fork_figures``:
    write the tables and draw the figures in forked processes that import pandas and
    matplotlib while this one solves (:mod:`recipsim.report.figure_process`; the
    command line's choice, never a library's).
    """
    figures = None
    if fork_figures:  # the command line: on a fresh machine, compile while the table builds
        from recipsim.report.figure_process import (
            REPORT_PRELOAD,
            TABLES_PRELOAD,
            start_figure_processes,
        )
        from recipsim.results.compile_ahead import start_compile_ahead

        start_compile_ahead(path, overrides, allow_external_paths)
        # the report processes import pandas (and matplotlib) while this one solves
        preload = REPORT_PRELOAD if plots else TABLES_PRELOAD
        figures = start_figure_processes(
            None if plots else 1, preload, at_least=1, busy_parent=True
        )
    try:
        with compiled_runtime.importing_numba():  # the case's modules import numba
            from recipsim.case.load import load_case
            from recipsim.report.case_report import report_dir, write_case_report
            from recipsim.results.run import simulate_case

        timeline.mark("report processes started")
        case = load_case(path, overrides, allow_external_paths=allow_external_paths)
        timeline.mark("case loaded")
        target = report_dir(out, case.name, case.overrides)
        run = simulate_case(case, argv)
        timeline.mark("solved")
        write_case_report(run, target, overrides, plots, figures)
        timeline.mark("report renamed into place")
    except BaseException:
        if figures is not None:  # the children exit without drawing; the first error wins
            with contextlib.suppress(BaseException):
                figures.wait()
        raise
    return run.row, target


def _run_command(args: argparse.Namespace, argv: list[str] | None) -> int:
    """``recipsim run``: every case is attempted; the status is the worst of them."""
    status = 0
    for path in args.cases:

        def one(path: Path = path) -> int:
            row, target = run_case(
                path,
                args.overrides,
                args.out,
                False if args.no_plots else (args.plots if args.plots is not None else True),
                argv if argv is not None else sys.argv,
                args.allow_external_paths,
                fork_figures=True,
            )
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
    timeline.mark("imports")
    atexit.unregister(_quick_exit)  # once per process, however often main() runs
    atexit.register(_quick_exit)
    compiled_runtime.allow_stand_in()  # numba starts without scipy.linalg (0.1-0.2 s)
    args = _parser().parse_args(argv)
    _show_progress_notes(not getattr(args, "quiet", False))
    start_up_collector.pause()  # until numba has started (:mod:`recipsim.start_up_collector`)
    try:
        status: int = args.handler(args, argv)
    finally:
        start_up_collector.resume()
        timeline.flush("parent")
    return status


def _quick_exit() -> None:
    """At the interpreter's exit, before its last garbage collection, move every object
    to the collector's permanent generation: that collection walked all the objects
    numba and the solve made (0.3-0.4 s after a warm run, 0.04-0.06 s frozen), to free
    memory the process's end frees anyway. Registered once by :func:`main`; in a process
    that calls :func:`main` and goes on (tests, a notebook) it runs only at its end."""
    gc.freeze()


def _show_progress_notes(show: bool) -> None:
    """Print recipsim's one-line notes (compiling the solver, building a property table)
    on standard error, ``recipsim: ...``; ``--quiet`` keeps them off."""
    import logging

    logger = logging.getLogger("recipsim")
    if not any(getattr(h, "_recipsim_cli", False) for h in logger.handlers):
        handler = logging.StreamHandler()
        handler.setFormatter(logging.Formatter("recipsim: %(message)s"))
        handler._recipsim_cli = True  # type: ignore[attr-defined]
        logger.addHandler(handler)
    logger.setLevel(logging.INFO if show else logging.WARNING)


def _print_summary(row: dict[str, Any], where: Path) -> None:
    conv = "converged" if row["converged [-]"] else "NOT converged"
    lines = [
        f"{row['case']}: {row['refrigerant']}, {row['shaft_speed [rpm]']:.0f} rpm, "
        f"PR {row['pressure_ratio [-]']:.2f}, pressure {row['pressure']}, "
        f"mechanics {row['mechanics']}, drive {row['drive']}"
    ]
    if row["pressure"] == "cylinder":
        lines += [
            f"  mass flow {row['discharge_mass_flow [kg/s]'] * 3600:.3f} kg/h, "
            f"capacity {row['cooling_capacity [W]']:.1f} W, "
            f"shaft power {row['shaft_power [W]']:.1f} W, COP {row['COP [-]']:.3f}",
            f"  volumetric eff. {row['volumetric_efficiency [-]']:.3f}, "
            f"isentropic eff. {row['isentropic_efficiency [-]']:.3f}, "
            f"discharge {row['discharge_temperature [K]'] - 273.15:.1f} C",
        ]
    else:
        lines.append(
            f"  indicated power {row['indicated_power [W]']:.1f} W, "
            f"shaft power {row['shaft_power [W]']:.1f} W"
        )
    rms = ", ".join(
        f"{name} {row[f'bearing_rms_{name} [N]']:.0f}"
        for name in ("primary", "secondary", "eccentric", "pin", "piston_top", "piston_skirt")
    )
    lines.append(f"  bearing RMS [N]: {rms}")
    lines.append(
        f"  {conv} in {row['revolutions [-]']} revolutions "
        f"(residual {row['cycle_residual [-]']:.1e}), {row['wall_time [s]']:.3f} s -> {where}"
    )
    print("\n".join(lines))


if __name__ == "__main__":
    raise SystemExit(main())
