"""The public API: load a case, change it, simulate it, look at and write the result.

>>> import recipsim
>>> case = recipsim.load_case("reference_r134a_lbp", {"operating_point.shaft_speed": "3000 rpm"})
>>> result = recipsim.simulate(case.with_(solver__rtol=1e-7))
>>> result.summary["COP [-]"]                                   # doctest: +SKIP
>>> ax = result.plot_pv()                                       # doctest: +SKIP
>>> result.write("reports/my_run")                              # doctest: +SKIP

Everything the ``recipsim run`` command does goes through these functions. Plot methods
draw into the Axes they are given (or a new figure's) and return the Axes; no backend
is ever chosen.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pandas as pd

from recipsim.case.load import Case, load_case
from recipsim.results.run import CaseRun, simulate_case

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from recipsim.solve.periodic import PeriodicSolution

__all__ = ["Case", "Result", "load_case", "simulate"]


@dataclass(frozen=True)
class Result:
    """A simulated case.

    Attributes
    ----------
    case : Case
        The case as simulated.
    summary : pandas.Series
        One value per quantity, the unit in the name (``"COP [-]"``,
        ``"cooling_capacity [W]"``); the row of the report's ``summary.csv``.
    cycle : pandas.DataFrame
        The converged revolution, one row per crank-angle sample (``cycle.csv``).
    provenance : dict
        Versions, options, solver settings and statistics.
    converged : bool
        Whether the periodic steady state was reached within the case's tolerance.
    solution : PeriodicSolution or None
        The solver's result (None for the pinned crank under a tabulated pressure,
        which is inverse dynamics only).
    """

    case: Case
    summary: pd.Series
    cycle: pd.DataFrame
    provenance: dict[str, Any]
    converged: bool
    solution: PeriodicSolution | None
    _run: CaseRun

    # ---- plots: each draws into ``ax`` (or a new figure) and returns the Axes --------
    def plot_pv(self, ax: Axes | None = None, log: bool = False) -> Axes:
        """Indicator diagram, cylinder pressure against volume (log-log with ``log``)."""
        from recipsim.report.plotting import plot_pv

        return _first_axes(plot_pv(self.cycle, ax=ax, log=log, label=self.case.name), ax)

    def plot_pressure(self, ax: Axes | None = None) -> Axes:
        """Cylinder pressure against crank angle, with the suction and discharge lines."""
        from recipsim.report.plotting import plot_pressure

        op = self.case.operating_point
        plenum = (op.suction_pressure, op.discharge_pressure)
        return _first_axes(plot_pressure(self.cycle, ax=ax, plenum=plenum), ax)

    def plot_torque(self, ax: Axes | None = None) -> Axes:
        """Driving torque with its gas and inertia parts against crank angle."""
        from recipsim.report.plotting import plot_torque

        return _first_axes(plot_torque(self.cycle, ax=ax), ax)

    def plot_valves(self, ax: Axes | None = None) -> Axes:
        """Reed lifts and valve mass flows against crank angle (cylinder scenes)."""
        from recipsim.report.plotting import plot_valves

        return _first_axes(plot_valves(self.cycle, ax=ax), ax)

    def plot_bearing_loads(self) -> Any:
        """Force magnitude of every bearing against crank angle; returns the figure's
        array of Axes (one per bearing)."""
        from recipsim.report.mechanics_plots import plot_bearing_loads

        return plot_bearing_loads({self.case.name: self.cycle}).axes

    def plot_orbits(self) -> Any:
        """Journal orbits of the primary and secondary bearings (flexible mechanics);
        returns the figure's Axes."""
        from recipsim.report.mechanics_plots import plot_orbits

        return plot_orbits({self.case.name: self.cycle}).axes

    # ---- report -------------------------------------------------------------------------
    def write(self, directory: str | Path, plots: bool = True) -> Path:
        """Write the report (``summary.csv``, ``cycle.csv``, figures, ``case.toml``,
        ``provenance.json``) into ``directory``, atomically; a directory that recipsim
        did not write is refused (:class:`~recipsim.errors.CaseError`)."""
        from recipsim.report.case_report import write_case_report

        return write_case_report(self._run, Path(directory), list(self.case.overrides), plots)


def _first_axes(fig: Any, ax: Axes | None) -> Axes:
    return ax if ax is not None else fig.axes[0]


def simulate(case: Case) -> Result:
    """Solve ``case`` to its periodic steady state.

    Parameters
    ----------
    case : Case
        From :func:`load_case` (and :meth:`Case.with_`).

    Returns
    -------
    Result

    Raises
    ------
    SolverError
        Naming the crank angle and the state where the integration failed.
    """
    run = simulate_case(case)
    return Result(
        case=case,
        summary=pd.Series(run.row, name=case.name),
        cycle=run.cycle,
        provenance=run.meta,
        converged=bool(run.row.get("converged [-]", True)),
        solution=run.solution,
        _run=run,
    )
