"""Run one case and judge its outcome against its expectation (one row of the check)."""

from __future__ import annotations

import re
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from recipsim.case.load import load_case
from recipsim.errors import CaseError, RecipsimError
from recipsim.pipeline import simulate_case
from recipsim.studies.check.expectations import Expectation
from recipsim.studies.check.metrics import (
    ORBIT_METRIC,
    closures,
    cycle_metrics,
    non_finite_results,
)

if TYPE_CHECKING:
    from recipsim.results.case_run import CaseRun


@dataclass
class CheckRow:
    """One case's outcome under ``recipsim check`` (a row of ``check.csv``).

    Numbers are None where they do not apply (a refused case has no revolutions; a
    tabulated pressure has no mass closure).
    """

    case: str
    file: str
    expected: str
    outcome: str
    message: str = ""
    revolutions: int | None = None
    cycle_residual: float | None = None
    wall_time: float = 0.0  # load + simulate + tables [s]
    solve_time: float | None = None  # the periodic solution alone [s]
    steps: int | None = None
    mass_closure: float | None = None
    energy_closure: float | None = None
    drive_closure: float | None = None
    mass_balance_residual: float | None = None
    energy_balance_residual: float | None = None
    volumetric_efficiency: float | None = None
    non_finite: tuple[str, ...] = ()
    metrics: dict[str, float] = field(default_factory=dict)
    matches: bool = False
    note: str = ""
    reason: str = ""

    @property
    def finite(self) -> bool | None:
        """True when every checked result is finite (None: nothing ran)."""
        if self.outcome not in ("converged", "not_converged"):
            return None
        return not self.non_finite


def judge(row: CheckRow, expectation: Expectation) -> tuple[bool, str]:
    """Whether ``row``'s outcome meets ``expectation``, and why not.

    A converged or not-converged run must have finite results; a converged run
    expected to converge must also have its closures within tolerance (a closure that
    is NaN fails, None means not applicable) and its metrics at or above the minima;
    a refused or failed case must have a message matching the expected pattern.
    """
    notes = []
    if row.outcome != expectation.expected:
        notes.append(f"expected {expectation.expected.replace('_', ' ')}")
    elif row.outcome in ("refused", "failed") and expectation.message:
        if not re.search(expectation.message, row.message, re.IGNORECASE):
            notes.append(f"message does not match /{expectation.message}/")
    if row.non_finite:
        notes.append("non-finite results: " + ", ".join(row.non_finite[:4]))
    if row.outcome == "converged" and expectation.expected == "converged":
        for name, value, tol in (
            ("mass", row.mass_closure, expectation.mass_tolerance),
            ("energy", row.energy_closure, expectation.energy_tolerance),
            ("drive", row.drive_closure, expectation.drive_tolerance),
        ):
            if value is not None and not value <= tol:
                notes.append(f"{name} closure {value:.2g} > {tol:.2g}")
        for metric, minimum in expectation.minimum.items():
            value = row.metrics.get(metric)
            if value is None or not value >= minimum:
                notes.append(f"{metric} {value} < {minimum:g}")
    if row.outcome in ("converged", "not_converged"):
        ratio = row.metrics.get(ORBIT_METRIC)
        if ratio is not None and not ratio < 1.0:
            notes.append(f"a journal left its clearance (eccentricity ratio {ratio:.3g})")
    return not notes, "; ".join(notes)


def check_case(
    file: Path, expectation: Expectation, overrides: Sequence[str] = (), fast: bool = False
) -> CheckRow:
    """Run one case and judge it; never raises for a failing case (a failure is a row).

    Overrides are applied in this order: the case file, then (with ``fast``) the
    expectation's fast overrides, then ``overrides`` (``--set``).
    """
    file = Path(file)
    row = CheckRow(case=file.stem, file=str(file), expected=expectation.expected, outcome="failed")
    row.reason = expectation.reason
    applied = [*(expectation.fast if fast else ()), *overrides]
    start = time.perf_counter()
    try:
        case = load_case(file, applied)
        row.case = case.name
        _fill_run(row, simulate_case(case))
    except CaseError as exc:
        row.outcome, row.message = "refused", str(exc)
    except RecipsimError as exc:
        row.outcome, row.message = "failed", str(exc)
    except Exception as exc:  # a bug: reported as a row, the check goes on
        row.outcome, row.message = "failed", f"internal error {type(exc).__name__}: {exc}"
    row.wall_time = time.perf_counter() - start
    row.matches, row.note = judge(row, expectation)
    return row


def _fill_run(row: CheckRow, run: CaseRun) -> None:
    r = run.row
    row.outcome = "converged" if r["converged [-]"] else "not_converged"
    if r.get("status_message"):  # the diagnosis, or what no_delivery / subharmonic mean
        row.message = f"{r['status']}: {r['status_message']}"
    row.revolutions = int(r["revolutions [-]"])
    row.cycle_residual = float(r["cycle_residual [-]"])
    row.solve_time = float(r["wall_time [s]"])
    row.steps = int(r["steps [-]"])
    c = closures(run)
    row.mass_closure, row.energy_closure, row.drive_closure = c["mass"], c["energy"], c["drive"]
    for name in ("mass_balance_residual", "energy_balance_residual", "volumetric_efficiency"):
        value = r.get(f"{name} [-]")
        setattr(row, name, None if value is None else float(value))
    row.non_finite = non_finite_results(run)
    row.metrics = cycle_metrics(run)
