"""``recipsim warmup [CASE ...] [--refrigerants NAMES]``: prepare the caches ahead of a job.

A first run compiles the solver (numba's cache) and builds the property table of its
refrigerant; both are kept in recipsim's cache directory (``$RECIPSIM_CACHE``, see
``docs/caches.md``). ``warmup`` does that work now, with a line per step, so that a
long sweep, a cluster's workers sharing the cache or a timed run do not pay for it:
each CASE is solved for one revolution, which compiles the code of its scene
(cylinder on the rigid crank, cylinder on the flexible crank, flexible crank under a
tabulated pressure: each scene compiles on its own) and only that, with the
Rosenbrock-W step for a case whose ``solver.method`` is ``"dopri5_stiff"`` (which a run
compiles only once a stretch turns stiff); by default one case of each scene. Each
refrigerant of ``--refrigerants`` gets its property table.
"""

from __future__ import annotations

import argparse
import sys
import time
from typing import Any

from recipsim.case.load import load_case
from recipsim.case.refrigerant import case_fluid, load_refrigerant
from recipsim.cli.options import exit_status
from recipsim.physics.thermo.property_backends import TABLE
from recipsim.pipeline import simulate_case
from recipsim.solve.scene_entries import compile_entry, entry_name

#: One revolution is enough to call, and so compile, every kernel of a scene.
_ONE_REVOLUTION = {"solver.min_revolutions": 1, "solver.max_revolutions": 1}
#: One shipped case of each scene (rigid crank, coupled, tabulated pressure on the
#: flexible crank): the default of ``warmup``, which then compiles every scene.
EVERY_SCENE = ["reference_r134a_lbp", "reference_r134a_lbp_coupled", "paper_tabulated"]


def add_warmup_parser(sub: Any) -> argparse.ArgumentParser:
    """Add the ``warmup`` subcommand to the subparsers ``sub``."""
    parser: argparse.ArgumentParser = sub.add_parser(
        "warmup",
        help="compile the solver and build property tables now (once per installation)",
        description=__doc__.split("\n\n")[1] if __doc__ else None,
    )
    parser.add_argument(
        "cases",
        nargs="*",
        default=EVERY_SCENE,
        help=f"cases whose scenes to compile (default: {', '.join(EVERY_SCENE)})",
    )
    parser.add_argument(
        "--refrigerants",
        type=lambda text: [n.strip() for n in text.split(",") if n.strip()],
        default=[],
        metavar="NAMES",
        help="comma-separated refrigerants whose property tables to build (e.g. R134a,R290)",
    )
    parser.add_argument("--quiet", action="store_true", help="print nothing but errors")
    parser.set_defaults(handler=run_warmup_command)
    return parser


def run_warmup_command(args: argparse.Namespace, argv: list[str] | None) -> int:
    """Handler of ``recipsim warmup``."""
    return exit_status(lambda: warmup(args.cases, args.refrigerants, not args.quiet))


def warmup(cases: list[str], refrigerants: list[str], verbose: bool = True) -> int:
    """Compile the scenes of ``cases`` and build the property tables of ``refrigerants``.

    Parameters
    ----------
    cases : list of str
        Case files or shipped case names; each is solved for one revolution.
    refrigerants : list of str
        Refrigerant names (files of ``refrigerants/`` or beside the cases).
    verbose : bool
        Print a line per step with its wall time [s].

    Returns
    -------
    int
        0 (a failure raises).

    Raises
    ------
    CaseError
        An unknown case or refrigerant.
    """

    def say(text: str) -> None:
        if verbose:
            print(f"recipsim: {text}", file=sys.stderr, flush=True)

    for name in refrigerants:
        start = time.perf_counter()
        case_fluid(load_refrigerant(name, "--refrigerants", name), TABLE.name)
        say(f"property table of {name} ready ({time.perf_counter() - start:.1f} s)")
    for case in cases:
        start = time.perf_counter()
        loaded = load_case(case).with_(_ONE_REVOLUTION)
        simulate_case(loaded, ["recipsim", "warmup"])
        entry = entry_name(loaded.options, loaded.solver)
        w_step = ""
        if entry is not None and loaded.solver.method == "dopri5_stiff":
            compile_entry(entry + "_w")  # taken over to where a stretch turns stiff
            w_step = ", with the Rosenbrock-W step"
        say(
            f"{loaded.name}: solver compiled for its scene ({loaded.options.mechanics} "
            f"crank, {loaded.options.pressure} pressure{w_step}) "
            f"({time.perf_counter() - start:.1f} s)"
        )
    return 0
