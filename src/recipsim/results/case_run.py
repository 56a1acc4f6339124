"""A simulated case as the report and the API see it: the summary row, the cycle table and
the provenance, post-processed from the solver's periodic solution."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import pandas as pd

from recipsim.case.case import Case
from recipsim.results.outcome import classify, explained
from recipsim.results.provenance import case_provenance, provenance
from recipsim.results.sampled import CycleColumns
from recipsim.results.startup import startup_summary
from recipsim.results.tables import cycle_columns, pinned_tabulated_columns, summary
from recipsim.solve.periodic import PeriodicSolution
from recipsim.solve.startup import StartupRun


@dataclass
class CaseRun:
    """A simulated case.

    Attributes
    ----------
    case : Case
        The case as solved (at the motor's slip speed, the case at that speed).
    solution : PeriodicSolution or None
        None for the pinned mechanism under a tabulated pressure (inverse dynamics only).
    cycle : pandas.DataFrame
        The converged revolution, one row per crank-angle sample (``cycle.csv``).
    row : dict
        The summary row (:func:`recipsim.results.tables.summary`), units in the keys,
        ending with ``status`` and ``status_message`` (:mod:`recipsim.results.outcome`).
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


def case_run(
    case: Case,
    solution: PeriodicSolution | None,
    startup: StartupRun | None = None,
    argv: list[str] | None = None,
) -> CaseRun:
    """Post-process a solved case: its cycle table, summary row and provenance.

    Parameters
    ----------
    case : Case
        The case as solved.
    solution : PeriodicSolution or None
        Its periodic solution; None for the pinned mechanism under a tabulated pressure
        (the table is then computed by inverse dynamics).
    startup : StartupRun, optional
        The start-up from rest that preceded the periodic solve.
    argv : list of str, optional
        The command line, for the provenance.
    """
    if solution is None:
        columns = pinned_tabulated_columns(case)
        meta = case_provenance(case, argv)
    else:
        columns = cycle_columns(solution)
        meta = provenance(solution, argv)
    row = _status_row(case, solution, columns, startup)
    return CaseRun(case, solution, pd.DataFrame(columns), row, meta, startup)


def summary_only(solution: PeriodicSolution, startup: StartupRun | None = None) -> dict[str, Any]:
    """The summary row of :func:`case_run` (the same values) from only the columns the
    summary reads, without the cycle table or the provenance: what a sweep point keeps."""
    columns = cycle_columns(solution, full=False)
    return _status_row(solution.model.case, solution, columns, startup)


def _status_row(
    case: Case,
    solution: PeriodicSolution | None,
    columns: CycleColumns,
    startup: StartupRun | None,
) -> dict[str, Any]:
    """The summary row (with the start-up's columns), then its status and message."""
    with explained("post-processing the converged revolution"):
        row = summary(solution, columns, case)
        if startup is not None:
            row |= startup_summary(startup)
    row["status"], row["status_message"] = classify(solution, columns, row)
    return row
