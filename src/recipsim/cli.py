"""Command line: ``recipsim run CASE... [--out DIR] [--set KEY=VALUE ...]``,
``recipsim paper CASE [--out DIR]`` (see :mod:`recipsim.paper_command`).

Exit status: 0 success; 1 a simulation failed (message names crank angle and state);
2 invalid input (message names file, key and what is allowed), no traceback.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from .errors import CaseError, RecipsimError, SolverError
from .paper_command import add_paper_parser, run_paper_command


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="recipsim",
        description="Reciprocating refrigeration compressor simulator (CoolProp cylinder + crank).",
    )
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="simulate cases and write a report per case")
    run.add_argument("cases", nargs="+", type=Path, help="case files (TOML)")
    run.add_argument(
        "--out",
        type=Path,
        default=Path("reports"),
        help="parent directory of the reports (default: reports/)",
    )
    run.add_argument(
        "--set",
        dest="overrides",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="override a case value, KEY a dotted path (e.g. solver.rtol=1e-9)",
    )
    run.add_argument("--no-plots", action="store_true", help="write the CSV files only")
    run.add_argument("--quiet", action="store_true", help="print nothing but errors")
    add_paper_parser(sub)
    return parser


def run_case(
    path: Path, overrides: list[str], out: Path, plots: bool = True, argv: list[str] | None = None
) -> dict[str, Any]:
    """Load, simulate and report one case; returns its summary row."""
    from .case import load_case
    from .model import build_model
    from .report import case_provenance, provenance, write_report
    from .results import cycle_table, pinned_tabulated_cycle, summary
    from .solve.periodic import solve_periodic

    case = load_case(path, overrides)
    solution = None
    if case.options.pressure == "tabulated" and case.options.mechanics == "pinned":
        cycle = pinned_tabulated_cycle(case)  # inverse dynamics only, nothing to integrate
        meta = case_provenance(case, argv)
    else:
        solution = solve_periodic(build_model(case))
        cycle = cycle_table(solution)
        meta = provenance(solution, argv)
    row = summary(solution, cycle, case)
    op = case.operating_point
    write_report(
        out / case.name,
        row,
        cycle,
        case.source_text,
        overrides,
        meta,
        plenum=(op.suction_pressure, op.discharge_pressure),
        plots=plots,
    )
    return row


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``recipsim`` command."""
    args = _parser().parse_args(argv)
    if args.command == "run":
        status = 0
        for path in args.cases:
            try:
                row = run_case(
                    path,
                    args.overrides,
                    args.out,
                    not args.no_plots,
                    argv if argv is not None else sys.argv,
                )
            except CaseError as exc:
                print(f"recipsim: invalid input: {exc}", file=sys.stderr)
                status = max(status, 2)
                continue
            except SolverError as exc:
                print(f"recipsim: {path}: {exc}", file=sys.stderr)
                status = max(status, 1)
                continue
            except RecipsimError as exc:
                print(f"recipsim: {path}: {exc}", file=sys.stderr)
                status = max(status, 1)
                continue
            if not args.quiet:
                _print_summary(row, args.out / row["case"])
        return status
    if args.command == "paper":
        try:
            return run_paper_command(args)
        except CaseError as exc:
            print(f"recipsim: invalid input: {exc}", file=sys.stderr)
            return 2
        except RecipsimError as exc:
            print(f"recipsim: {args.case}: {exc}", file=sys.stderr)
            return 1
    return 2


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
