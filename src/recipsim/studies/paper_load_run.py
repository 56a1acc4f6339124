"""One flexible run of the paper study, made like any case: a :class:`~recipsim.case.load.Case`
under a given pressure curve (:func:`tabulated_case`) solved by
:func:`recipsim.solve.drive.build_model_for` -> :func:`recipsim.solve.periodic.solve_periodic`
(:func:`solve_load`), and its result (:class:`LoadRun`): the case's cycle table and
summary row. The linear-bearing runs (:mod:`.paper_linear_runs`) and the hydrodynamic
column (:mod:`.paper_hydrodynamic`) are both made of these.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
import pandas as pd

from recipsim.case.load import Case
from recipsim.model.build import Model
from recipsim.physics.mechanics.crank_trains import FLEXIBLE
from recipsim.physics.mechanics.layout import BEARING_NAMES
from recipsim.physics.mechanics.tabulated import PressureCurve
from recipsim.physics.thermo.pressure_sources import TABULATED
from recipsim.results.tables import cycle_table, summary
from recipsim.solve.drive import build_model_for
from recipsim.solve.periodic import solve_periodic
from recipsim.solve.shooting import solve_shooting


@dataclass(frozen=True)
class LoadRun:
    """One load of the study on flexible (linear or film) bearings, solved like a case.

    Attributes
    ----------
    configuration : str
        The study's configuration (``inertia``, ``gas``, ``gas_damped``).
    case : Case
        The case that was run (tabulated pressure, the study's drive and bearings).
    cycle : pandas.DataFrame
        Its cycle table (``recipsim run``'s, from TDC at equal crank-angle steps), plus
        ``drive_torque [N m]`` (the shaft torque, the study's torque column).
    summary : dict
        Its summary row (``bearing_rms_<name> [N]``, ``orbit_radius_max_<name> [m]``,
        ``min_film_thickness_<name> [m]``, ...).
    revolutions, nfev : int
        Revolutions integrated (shooting Jacobians included), right-hand-side evaluations.
    converged : bool
        The case's periodicity test passed.
    residual : float
        Cycle residual of the reported revolution [-].
    wall_time : float
        [s].
    start : numpy.ndarray or None
        State at the start of the reported revolution (the model's state vector), to
        run on from it.
    jacobian : (numpy.ndarray, numpy.ndarray) or None
        Shooting's last Jacobian and its scales
        (:attr:`recipsim.solve.revolution.PeriodicSolution.jacobian`), to seed another
        load of the same crank train.
    """

    configuration: str
    case: Case
    cycle: pd.DataFrame
    summary: dict[str, Any]
    revolutions: int
    converged: bool
    residual: float
    nfev: int
    wall_time: float
    start: np.ndarray | None = None
    jacobian: tuple[np.ndarray, np.ndarray] | None = field(default=None, repr=False)

    @property
    def force_rms(self) -> np.ndarray:
        """(6,) RMS force magnitude per bearing, ``BEARING_NAMES`` order [N]."""
        return np.array([self.summary[f"bearing_rms_{b} [N]"] for b in BEARING_NAMES])

    @property
    def force_peak(self) -> np.ndarray:
        """(6,) peak force magnitude per bearing [N]."""
        return np.array([self.summary[f"bearing_max_{b} [N]"] for b in BEARING_NAMES])

    @property
    def orbit_radius_max(self) -> np.ndarray:
        """(6,) largest journal displacement per bearing [m]."""
        return np.array([self.summary[f"orbit_radius_max_{b} [m]"] for b in BEARING_NAMES])

    @property
    def min_film_thickness(self) -> np.ndarray:
        """(6,) smallest film per bearing [m]; nan for the bearings without a film."""
        key = "min_film_thickness_{} [m]"
        return np.array([self.summary.get(key.format(b), np.nan) for b in BEARING_NAMES])


def tabulated_case(
    case: Case, curve: PressureCurve, changes: dict[str, Any], label: str = ""
) -> Case:
    """``case`` with ``changes`` (dotted keys, validated like the file) on its flexible
    crank train under the pressure ``curve`` (crank angle from TDC [rad], [Pa]).

    The pressure source is set to the curve directly (a curve is data, not a case key);
    ``label`` is appended to the case name.
    """
    changed = case.with_({"options.mechanics": FLEXIBLE.name, **changes})
    return replace(
        changed,
        name=case.name + (f"_{label}" if label else ""),
        options=replace(changed.options, pressure=TABULATED.name),
        pressure_curve=curve,
    )


def solve_load(
    configuration: str,
    case: Case,
    start: Callable[[Model], Model] | None = None,
    jacobian: tuple[np.ndarray, np.ndarray] | None = None,
) -> LoadRun:
    """Solve ``case`` to its periodic state (``solver.periodic``) and tabulate it.

    Parameters
    ----------
    configuration : str
        Recorded in the result.
    case : Case
    start : callable, optional
        Called with the built model before the solve; the model it returns is solved
        (another initial state ``y0``, say).
    jacobian : (numpy.ndarray, numpy.ndarray), optional
        Seed of a shooting solve (:func:`recipsim.solve.shooting.solve_shooting`; the
        case's ``solver.periodic`` must be ``"shooting"``).

    Raises
    ------
    SolverError
        If an integration fails.
    """
    t0 = time.perf_counter()
    model = build_model_for(case)
    if start is not None:
        model = start(model)
    if jacobian is not None and case.solver.periodic == "shooting":
        sol = solve_shooting(model, jacobian=jacobian)
    else:
        sol = solve_periodic(model)
    cycle = cycle_table(sol)
    cycle["drive_torque [N m]"] = cycle["shaft_torque [N m]"]
    return LoadRun(
        configuration=configuration,
        case=case,
        cycle=cycle,
        summary=summary(sol, cycle, case),
        revolutions=sol.revolutions,
        converged=sol.converged,
        residual=sol.residual,
        nfev=sol.nfev,
        wall_time=time.perf_counter() - t0,
        start=sol.final.y_start.copy(),
        jacobian=sol.jacobian,
    )
