"""``recipsim paper CASE [--out DIR]``: the paper's pinned-against-flexible study.

Writes ``<out>/<case name>/`` (``+<digest>`` with ``--set``; default ``--out``:
``reports/paper``).

Runs, for the mechanism, geometry, operating point and pressure curve of a case,
the pinned and the flexible crank train (each flexible run the case itself, solved by
its periodic solver) under (a) inertia only, (b) the gas load,
(c) the gas load with the case's bearing damping, and writes ``table1.csv`` (the
layout of the paper's Table 1) with the figures (:mod:`recipsim.studies.paper`).
The undamped flexible runs (a), (b) are their periodic response at constant speed,
found by shooting (``--undamped-start periodic``, the default), or a transient of
``--undamped-revolutions`` from the unloaded (or quasi-static) pose.

The hydrodynamic column (default; ``--no-hydrodynamic`` leaves it out) runs loads (a)
and (b) with the primary, secondary and eccentric journals on oil films
(``--bearing-law``, default ``finite_journal``; the case's journal geometry, clearance and
``[oil]``) at constant speed, through the ordinary case solve
(:mod:`recipsim.studies.paper_hydrodynamic`), and prints whether the paper's conclusion 3
(hydrodynamic loads close to the pinned ones) holds.

The pressure curve is the case's table (``options.pressure = "tabulated"``) or, for a
cylinder case, the cylinder pressure of its rigid-crank run.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import Any

import numpy as np

from recipsim.case.load import load_case
from recipsim.cli.options import add_common_options, exit_status, positive_int
from recipsim.model.build import build_model
from recipsim.physics.mechanics.crank_trains import CRANK_TRAINS, PINNED
from recipsim.physics.mechanics.drives import CONSTANT_SPEED, TORQUE_PROFILE
from recipsim.physics.mechanics.tabulated import PressureCurve
from recipsim.report.case_report import report_dir
from recipsim.results.tables import cycle_table
from recipsim.solve.periodic import solve_periodic
from recipsim.studies.paper import run_paper_study
from recipsim.studies.paper_hydrodynamic import DEFAULT_LAW, FILM_LAWS
from recipsim.studies.paper_report import conclusion_three
from recipsim.studies.paper_runs import UNDAMPED_STARTS


def add_paper_parser(sub: Any) -> None:
    """Register the ``paper`` subcommand."""
    p = sub.add_parser(
        "paper",
        help="the paper's study: pinned vs flexible bearing loads (table1.csv, figures)",
    )
    p.add_argument(
        "case", type=Path, help="case file (TOML) or a shipped case name, e.g. paper_tabulated"
    )
    add_common_options(
        p,
        Path("reports/paper"),
        "parent directory of the study: it goes to OUT/<case name>/ "
        "(OUT/<case name>+<digest of the --set values>/ with --set) (default: reports/paper/)",
    )
    p.set_defaults(
        handler=lambda args, argv: exit_status(lambda: run_paper_command(args), str(args.case))
    )
    p.add_argument(
        "--undamped-start",
        choices=UNDAMPED_STARTS,
        default=None,
        help=(
            "undamped runs: their periodic response at constant speed, by shooting "
            "(default), or a transient from the unloaded or quasi-static pose (default "
            "unloaded when --undamped-revolutions is given)"
        ),
    )
    p.add_argument(
        "--no-hydrodynamic",
        action="store_true",
        help="leave out the hydrodynamic column (journals on oil films)",
    )
    p.add_argument(
        "--bearing-law",
        choices=FILM_LAWS,
        default=DEFAULT_LAW,
        help=f"film law of the hydrodynamic column's journals (default {DEFAULT_LAW})",
    )
    p.add_argument(
        "--undamped-revolutions",
        type=positive_int,
        default=None,
        help="revolutions of an undamped transient, the last one reported (default 8)",
    )


def run_paper_command(args: argparse.Namespace) -> int:
    """Run the study for ``args.case``; returns the exit status."""
    external = args.allow_external_paths
    case = load_case(args.case, args.overrides, allow_external_paths=external)
    op = case.operating_point
    if case.pressure_curve is not None:
        curve = case.pressure_curve
        source = "the case's tabulated curve"
    else:
        rigid = load_case(
            args.case,
            [
                *args.overrides,
                f'options.mechanics="{PINNED.name}"',
                f'options.drive="{CONSTANT_SPEED.name}"',
            ],
            allow_external_paths=external,
        )
        cycle = cycle_table(solve_periodic(build_model(rigid)))
        curve = PressureCurve(
            np.radians(cycle["crank_angle [deg]"].to_numpy()),
            cycle["cylinder_pressure [Pa]"].to_numpy(),
        )
        source = "the cylinder pressure of the case on the rigid crank"

    out = report_dir(args.out, case.name, args.overrides)  # checked before the study runs
    flexible = CRANK_TRAINS[case.options.mechanics].flexible
    drive = case.options.drive if flexible else TORQUE_PROFILE.name
    start = args.undamped_start or ("periodic" if args.undamped_revolutions is None else "unloaded")
    study = run_paper_study(
        case,
        curve,
        out,
        drive=drive,
        undamped_revolutions=8 if args.undamped_revolutions is None else args.undamped_revolutions,
        undamped_start=start,
        plots=not args.no_plots,
        hydrodynamic=not args.no_hydrodynamic,
        bearing_law=args.bearing_law,
    )
    rpm = op.shaft_speed * 60.0 / (2.0 * math.pi)
    print(f"{case.name}: paper study at {rpm:.0f} rpm, drive {drive}, pressure from {source}")
    print(f"undamped runs: {study.settings['undamped_runs']}")
    rms = [c for c in study.table1.columns if c == "bearing" or c.endswith("_rms [N]")]
    print("RMS bearing loads [N] (the layout of the paper's Table 1):")
    print(study.table1[rms].round(1).to_string(index=False))
    if study.hydrodynamic:
        print(conclusion_three(study.table1))
    print(f"-> {out}")
    return 0
