"""One case from file to report, in one process: case -> model -> solve -> results -> report.

The Python API (:func:`recipsim.simulate`), every command of the command line and the
studies (sweeps, comparisons, the paper's study, calibration, the hard-case check) take a
case through these functions:

- :func:`solve_case`: the periodic steady state of a case (from rest first with
  ``solver.start = "rest"``, at the motor's slip speed with ``options.speed =
  "motor_slip"``);
- :func:`simulate_case`: that, post-processed into a :class:`~recipsim.results.case_run.CaseRun`
  (summary row, cycle table, provenance);
- :func:`simulate_row`: only the summary row (a sweep point without a report);
- :func:`run_case`: a case file, loaded, simulated and reported.
"""

from __future__ import annotations

from collections.abc import Collection, Sequence
from pathlib import Path
from typing import Any

from recipsim.case.case import Case
from recipsim.case.envelope import check_envelope
from recipsim.case.load import load_case
from recipsim.physics.mechanics.crank_trains import CRANK_TRAINS
from recipsim.physics.speed_models import SPEED_MODELS
from recipsim.physics.thermo.pressure_sources import PRESSURE_SOURCES
from recipsim.progress import logger
from recipsim.report.case_report import report_dir, write_case_report
from recipsim.results.case_run import CaseRun, case_run, summary_only
from recipsim.results.outcome import explained
from recipsim.solve.drive import build_model_for
from recipsim.solve.motor_speed import solve_at_motor_speed
from recipsim.solve.periodic import PeriodicSolution, check_step_budget, solve_periodic
from recipsim.solve.scene_entries import entry_name
from recipsim.solve.startup import StartupRun, solve_from_rest


def solve_case(case: Case) -> tuple[Case, PeriodicSolution | None, StartupRun | None]:
    """The periodic steady state of ``case``.

    Returns
    -------
    case : Case
        The case as solved (at the motor's slip speed it is the case at that speed).
    solution : PeriodicSolution or None
        The periodic solution; None for the pinned mechanism under a tabulated pressure
        (nothing to integrate: the table comes from inverse dynamics).
    startup : StartupRun or None
        The start-up transient from rest before the periodic solve
        (``solver.start = "rest"``).

    Raises
    ------
    OutsideEnvelopeError
        Before integrating, for a point outside the refrigerant's envelope.
    SolverError
        Naming the crank angle and the state where the integration failed, or the
        quantity and state of a failed property evaluation.
    """
    entry = entry_name(case.options, case.solver)
    if entry is not None:
        check_step_budget(case.solver)  # before anything is compiled or integrated
    check_envelope(case)
    if (
        not PRESSURE_SOURCES[case.options.pressure].solves_gas
        and not CRANK_TRAINS[case.options.mechanics].flexible
    ):
        return case, None, None
    if case.solver.start == "rest":
        with explained("building the model"):
            model = build_model_for(case)
        with explained("integrating the start-up from rest"):
            startup = solve_from_rest(model)
        return case, startup.solution, startup
    if SPEED_MODELS[case.options.speed].at_motor_load:
        with explained("integrating the periodic state at the motor's slip speed"):
            at_speed = solve_at_motor_speed(case)
        return at_speed.case, at_speed.solution, None
    with explained("building the model"):
        model = build_model_for(case)
    with explained("integrating the periodic state"):
        solution = solve_periodic(model)
    return case, solution, None


def simulate_case(case: Case, argv: list[str] | None = None) -> CaseRun:
    """Solve ``case`` (:func:`solve_case`) and post-process the converged revolution.

    Parameters
    ----------
    case : Case
        A validated case.
    argv : list of str, optional
        The command line, for the provenance.

    Raises
    ------
    OutsideEnvelopeError, SolverError
        As :func:`solve_case`.
    """
    solved, solution, startup = solve_case(case)
    return case_run(solved, solution, startup, argv)


def simulate_row(case: Case) -> dict[str, Any]:
    """The summary row of :func:`simulate_case` (the same values), without the cycle
    table or the provenance: what a sweep point keeps.

    Raises
    ------
    OutsideEnvelopeError, SolverError
        As :func:`solve_case`.
    """
    solved, solution, startup = solve_case(case)
    if solution is None:  # nothing integrated: the table is the summary's input
        return case_run(solved, None).row
    return summary_only(solution, startup)


def run_case(
    path: str | Path,
    overrides: Sequence[str],
    out: Path,
    plots: bool | Collection[str] = True,
    argv: list[str] | None = None,
    allow_external_paths: bool = False,
) -> tuple[CaseRun, Path]:
    """Load, simulate and report one case file; ``recipsim run``.

    The report goes to ``out/<case name>`` (``out/<case name>+<digest>`` with overrides,
    :func:`recipsim.report.case_report.report_name`). The target is checked before the
    simulation (it must be new, empty or a recipsim report), so a refused ``--out``
    costs nothing.

    Parameters
    ----------
    path : str or Path
        A case file, or a shipped case's name.
    overrides : sequence of str
        ``KEY=VALUE`` overrides (``--set``).
    out : Path
        Parent directory of the report.
    plots : bool or collection of str
        Every figure, none, or those named.
    argv : list of str, optional
        The command line, for the provenance.
    allow_external_paths : bool
        Let the case name files outside its directory.

    Returns
    -------
    run : CaseRun
        The simulated case.
    directory : Path
        Its report.
    """
    case = load_case(path, list(overrides), allow_external_paths=allow_external_paths)
    target = report_dir(out, case.name, case.overrides)
    run = simulate_case(case, argv)
    if plots:  # drawing the figures is the largest part of a warm run (seconds)
        logger.info("drawing the report's figures into %s", target)
    write_case_report(run, target, list(overrides), plots)
    return run, target
