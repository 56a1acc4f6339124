"""One case from file to report: the path shared by ``recipsim run``, sweeps and comparisons."""

from __future__ import annotations

import logging
from typing import TYPE_CHECKING, Any

from recipsim.cache_dirs import numba_cache_lacks

if TYPE_CHECKING:
    import numpy as np
    import pandas as pd

    from recipsim.case.case import Case
    from recipsim.solve.periodic import PeriodicSolution
    from recipsim.solve.startup import StartupRun


logger = logging.getLogger(__name__)

#: The integrators (:func:`solver_entry`) this process has run: compiled or loaded from
#: numba's cache, so their first-run note is not looked for again (a sweep point would
#: otherwise search the cache directory, about 1 ms).
_COMPILED: set[str] = set()


class CaseRun:
    """A simulated case.

    Parameters
    ----------
    case : Case
    solution : PeriodicSolution or None
        None for the pinned mechanism under a tabulated pressure (inverse dynamics only).
    cycle : pandas.DataFrame or dict of str to numpy.ndarray
        The converged revolution: the table, or its columns
        (:func:`recipsim.results.cycle.cycle_columns`), from which :attr:`cycle` builds
        the table when first asked (importing pandas then, 0.2-0.3 s: ``recipsim run``
        hands the columns to a report process, which writes and draws them without
        pandas).
    row : dict
        The summary row (:func:`recipsim.results.tables.summary`), units in the keys.
    meta : dict
        Provenance (versions, options, solver statistics).
    startup : StartupRun or None
        The start-up transient before the periodic solve (``solver.start = "rest"``).
    """

    def __init__(
        self,
        case: Case,
        solution: PeriodicSolution | None,
        cycle: pd.DataFrame | dict[str, np.ndarray],
        row: dict[str, Any],
        meta: dict[str, Any],
        startup: StartupRun | None = None,
    ) -> None:
        self.case = case
        self.solution = solution
        self._cycle = cycle
        self.row = row
        self.meta = meta
        self.startup = startup

    @property
    def cycle(self) -> pd.DataFrame:
        """The cycle table (:func:`recipsim.results.tables.cycle_table`)."""
        from recipsim.results.columns import as_table

        self._cycle = as_table(self._cycle)
        return self._cycle

    @property
    def table(self) -> pd.DataFrame | dict[str, np.ndarray]:
        """The cycle table as it is held: the DataFrame, or its columns while no one has
        asked for :attr:`cycle` (what a report process is sent)."""
        return self._cycle


def solver_entry(case: Case) -> str | None:
    """The compiled integrator (:mod:`recipsim.solve.scene_entries`) that ``case`` starts
    with, by name; None when nothing is integrated (pinned mechanism, tabulated pressure)."""
    from recipsim.solve.scene_entries import entry_name

    return entry_name(case.options, case.solver)


def simulate_case(case: Case, argv: list[str] | None = None) -> CaseRun:
    """Solve ``case`` to its periodic steady state and tabulate the converged revolution
    (from rest first, through the start-up transient, with ``solver.start = "rest"``).

    The summary row ends with ``status`` and ``status_message``
    (:mod:`recipsim.results.outcome`).

    Raises
    ------
    OutsideEnvelopeError
        Before integrating, for a point outside the refrigerant's envelope.
    SolverError
        Naming the crank angle and the state where the integration failed, or the
        quantity and state of a failed property evaluation (never a raw library error).
    """
    from recipsim.results.columns import Columns, CycleLike
    from recipsim.results.outcome import classify, explained
    from recipsim.results.provenance import case_provenance, provenance
    from recipsim.results.tables import cycle_columns, pinned_tabulated_columns, summary

    case, solution, startup = _solve(case)
    # the columns: the summary reads them as it reads the DataFrame (.columns)
    if solution is None:  # pinned mechanism, tabulated pressure: inverse dynamics only
        table = pinned_tabulated_columns(case)
        meta = case_provenance(case, argv)
    else:
        table = cycle_columns(solution)
        meta = provenance(solution, argv)
    cycle: CycleLike = Columns(table)
    with explained("post-processing the converged revolution"):
        row = summary(solution, cycle, case)
        _add_startup(row, startup)
    row["status"], row["status_message"] = classify(solution, cycle, row)
    return CaseRun(case, solution, table, row, meta, startup)


def simulate_row(case: Case) -> dict[str, Any]:
    """The summary row of :func:`simulate_case` (the same values), without building the
    cycle table's DataFrame or the provenance: what a sweep point keeps.

    Raises
    ------
    OutsideEnvelopeError, SolverError
        As :func:`simulate_case`.
    """
    from recipsim.results.outcome import classify, explained
    from recipsim.results.tables import summary_row

    _, solution, startup = _solve(case)
    if solution is None:  # nothing integrated: the table is the summary's input
        return simulate_case(case).row
    with explained("post-processing the converged revolution"):
        row, cycle = summary_row(solution)
        _add_startup(row, startup)
    row["status"], row["status_message"] = classify(solution, cycle, row)
    return row


def _add_startup(row: dict[str, Any], startup: StartupRun | None) -> None:
    if startup is not None:
        from recipsim.results.startup import startup_summary

        row |= startup_summary(startup)


def _solve(case: Case) -> tuple[Case, PeriodicSolution | None, StartupRun | None]:
    """The case as solved (at the motor's slip speed it is the case at that speed), its
    periodic solution (None for the pinned mechanism under a tabulated pressure: nothing
    to integrate) and the start-up run before it, if any."""
    from recipsim.case.envelope import check_envelope
    from recipsim.results.compile_ahead import (
        compile_outputs_while_waiting,
        wait_for_compile_ahead,
    )
    from recipsim.results.outcome import explained
    from recipsim.solve.drive import build_model_for
    from recipsim.solve.motor_speed import solve_at_motor_speed
    from recipsim.solve.periodic import solve_periodic

    entry = solver_entry(case)
    if entry is not None and entry not in _COMPILED and numba_cache_lacks("integrator", entry):
        logger.info("compiling the solver for this scene (once per installation: about 10-20 s)")
    check_envelope(case)  # refuse a point outside the refrigerant's envelope up front
    if case.options.pressure == "tabulated" and case.options.mechanics == "pinned":
        wait_for_compile_ahead()
        return case, None, None
    if case.solver.start == "rest":  # the start-up transient, then the periodic solve
        from recipsim.solve.startup import solve_from_rest

        with explained("building the model"):
            model = build_model_for(case)
        compile_outputs_while_waiting(model)
        wait_for_compile_ahead()
        with explained("integrating the start-up from rest"):
            startup = solve_from_rest(model)
        return case, startup.solution, startup
    if case.options.speed == "motor_slip":
        wait_for_compile_ahead()
        with explained("integrating the periodic state at the motor's slip speed"):
            at_speed = solve_at_motor_speed(case)
        return at_speed.case, at_speed.solution, None
    with explained("building the model"):
        model = build_model_for(case)
    # a child compiling the solver on a fresh machine (compile_ahead): the model build
    # above (the property table's compiled functions) ran beside it, and so do the
    # sample outputs' compiled code
    compile_outputs_while_waiting(model)
    wait_for_compile_ahead()
    with explained("integrating the periodic state"):
        solution = solve_periodic(model)
    if entry is not None:
        _COMPILED.add(entry)
    return case, solution, None
