"""``recipsim calibrate CASE DATA.csv --parameters KEY[=LOWER:UPPER] ... [--points ROWS]
[--member DATA:bore=BORE ...]``.

Fits a few uncertain case parameters to measured or catalogue points with bounded least
squares (:mod:`recipsim.studies.calibrate`), of one compressor or of several of a family
at once (``--member``: shared parameters, each member its data and case or bore), prints
the fitted values with their 95 % intervals and their verdict against the plausible
ranges the case keys declare, and every point's error (the points not fitted are
predictions), and writes ``<out>/<case name>/`` (default ``--out``:
``reports/calibrate``): ``parameters.csv``, ``points.csv``, ``calibration.json`` and the
calibrated ``case.toml``. Exit status 2 for an invalid input or an ill-posed fit (the
message says why), 1 for a failed run.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import Any

from recipsim.case.load import load_case
from recipsim.cli.options import add_common_options, exit_status
from recipsim.errors import CaseError
from recipsim.report.case_report import report_dir
from recipsim.studies.calibrate.parameters import CalibrationError
from recipsim.studies.calibrate.priors import judged
from recipsim.studies.calibrate.report import write_calibration
from recipsim.studies.calibrate.run import calibrate_case


def _rows(text: str) -> list[int]:
    try:
        rows = [int(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected row numbers like 3,7; got {text!r}") from None
    if not rows or min(rows) < 1:
        raise argparse.ArgumentTypeError(f"expected row numbers >= 1 like 3,7; got {text!r}")
    return rows


def add_calibrate_parser(sub: Any) -> None:
    """Register the ``calibrate`` subcommand."""
    p = sub.add_parser(
        "calibrate",
        help="fit uncertain case parameters to measured or catalogue points",
        description=(
            "Fit case parameters (dotted keys, with bounds) to the measured targets of a "
            "CSV of operating points by bounded least squares; report the fitted values with "
            "95 %% intervals and every point's error; write the calibrated case."
        ),
    )
    p.add_argument("case", type=Path, help="case file (TOML) or a shipped case name")
    p.add_argument(
        "data",
        type=Path,
        help="CSV of measured points, or a shipped catalogue's file name (docs/calibration.md)",
    )
    p.add_argument(
        "--parameters",
        nargs="+",
        required=True,
        metavar="KEY[=LOWER:UPPER]",
        help="case keys to fit, with bounds (bare SI numbers or quantities with units)",
    )
    p.add_argument(
        "--points",
        type=_rows,
        default=None,
        metavar="ROWS",
        help="data rows (1-based, comma separated) to fit on; the others are predicted",
    )
    p.add_argument(
        "--targets",
        nargs="+",
        default=None,
        metavar="COLUMN",
        help="target columns (default: 'cooling_capacity [W]' and 'COP [-]' where present)",
    )
    p.add_argument(
        "--ignore", nargs="+", default=[], metavar="COLUMN", help="data columns to leave out"
    )
    p.add_argument(
        "--member",
        action="append",
        default=[],
        metavar="DATA[:bore=BORE|:displacement=VOLUME|:case=CASE][:points=ROWS]",
        help="another compressor of the family, fitted together with CASE (the parameters "
        "shared): its data file, and its bore or displacement on CASE's geometry or its own "
        "case; repeatable",
    )
    add_common_options(
        p,
        Path("reports/calibrate"),
        "parent directory of the result: it goes to OUT/<case name>/ (default: reports/calibrate/)",
    )
    p.set_defaults(handler=lambda args, argv: exit_status(lambda: _calibrate(args), str(args.case)))


def _calibrate(args: argparse.Namespace) -> int:

    case = load_case(args.case, args.overrides, allow_external_paths=args.allow_external_paths)
    try:
        result = calibrate_case(
            case,
            args.data,
            args.parameters,
            args.points,
            args.targets,
            args.ignore,
            members=args.member,
        )
    except CalibrationError as exc:
        raise CaseError(str(args.data), "--parameters", str(exc)) from None
    where = write_calibration(result, report_dir(args.out, case.name, args.overrides))
    table = result.parameters.drop(columns=["plausible_source", "verdict"])
    print(table.to_string(index=False, float_format=lambda v: f"{v:.4g}"))
    print()
    judged_columns = ["parameter", "fitted", "verdict", "plausible_source"]
    for key, value, verdict, source in result.parameters[judged_columns].values:
        print(f"{'WARNING ' if judged(verdict) else ''}{key} = {value:.4g}: {verdict}")
        if source and judged(verdict):
            print(f"    plausible range from: {source}")
    print()
    errors = [c for c in result.points.columns if c.startswith("error ")]
    columns = ["member", "row", "point", "used_in_fit", *errors]
    if not args.member:
        columns.remove("member")
    print(result.points[columns].to_string(index=False, float_format=lambda v: f"{v:+.3f}"))
    _print_volumetric(result.volumetric)
    worst = max((abs(v) for c in errors for v in result.points[c] if math.isfinite(v)), default=0.0)
    print(f"\nlargest error {worst:.1%}; {result.fit.evaluations} parameter sets run -> {where}")
    return 0


def _print_volumetric(table: Any) -> None:
    """The volumetric decomposition, catalogue against model (none without capacities)."""
    if table.empty:
        return
    print("\nvolumetric decomposition (eta_v = 1 - x - V_d/V R; docs/calibration.md):")
    for row in table.to_dict("records"):
        dead = row["effective_dead_volume [m3]"] * 1e6
        low = row["effective_dead_volume_ci95_low [m3]"] * 1e6
        high = row["effective_dead_volume_ci95_high [m3]"] * 1e6
        print(
            f"  {row['member']} {row['source']:>9}: effective dead volume {dead:.4f} cm3 "
            f"({low:.4f}..{high:.4f}), other losses {row['other_losses [-]']:.3f} "
            f"({row['other_losses_ci95_low [-]']:.3f}..{row['other_losses_ci95_high [-]']:.3f}), "
            f"rms {row['rms [-]']:.4f}"
        )
