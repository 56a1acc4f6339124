"""One case from file to report: the path shared by ``recipsim run``, sweeps and comparisons."""

from __future__ import annotations

import logging
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from recipsim.cache_dirs import numba_cache_lacks

if TYPE_CHECKING:
    import pandas as pd

    from recipsim.case.load import Case
    from recipsim.solve.periodic import PeriodicSolution
    from recipsim.solve.startup import StartupRun


logger = logging.getLogger(__name__)


@dataclass
class CaseRun:
    """A simulated case.

    Attributes
    ----------
    case : Case
    solution : PeriodicSolution or None
        None for the pinned mechanism under a tabulated pressure (inverse dynamics only).
    cycle : pandas.DataFrame
        The converged revolution (:func:`recipsim.results.tables.cycle_table`).
    row : dict
        The summary row (:func:`recipsim.results.tables.summary`), units in the keys.
    meta : dict
        Provenance (versions, options, solver statistics).
    startup : StartupRun or None
        The start-up transient before the periodic solve (``solver.start = "rest"``).
    """

    case: Case
    solution: PeriodicSolution | None
    cycle: pd.DataFrame
    row: dict[str, Any]
    meta: dict[str, Any]
    startup: StartupRun | None = None


def simulate_case(case: Case, argv: list[str] | None = None) -> CaseRun:
    """Solve ``case`` to its periodic steady state and tabulate the converged revolution
    (from rest first, through the start-up transient, with ``solver.start = "rest"``).

    Raises
    ------
    SolverError
        Naming the crank angle and the state where the integration failed.
    """
    from recipsim.results.provenance import case_provenance, provenance
    from recipsim.results.tables import cycle_table, pinned_tabulated_cycle, summary
    from recipsim.solve.drive import build_model_for
    from recipsim.solve.motor_speed import solve_at_motor_speed
    from recipsim.solve.periodic import solve_periodic

    if numba_cache_lacks("integrator"):
        logger.info("compiling the solver (once per installation: about 30-45 s)")
    solution = startup = None
    if case.solver.start == "rest":  # the start-up transient, then the periodic solve
        from recipsim.results.startup import startup_summary
        from recipsim.solve.startup import solve_from_rest

        startup = solve_from_rest(build_model_for(case))
        solution = startup.solution
        cycle = cycle_table(solution)
        meta = provenance(solution, argv)
        row = summary(solution, cycle, case) | startup_summary(startup)
        return CaseRun(case, solution, cycle, row, meta, startup)
    if case.options.pressure == "tabulated" and case.options.mechanics == "pinned":
        cycle = pinned_tabulated_cycle(case)  # inverse dynamics only, nothing to integrate
        meta = case_provenance(case, argv)
    else:
        if case.options.speed == "motor_slip":
            at_speed = solve_at_motor_speed(case)
            case, solution = at_speed.case, at_speed.solution
        else:
            solution = solve_periodic(build_model_for(case))
        cycle = cycle_table(solution)
        meta = provenance(solution, argv)
    return CaseRun(case, solution, cycle, summary(solution, cycle, case), meta)
