"""Run one rung in this process: load, build, solve ``repeats`` times, keep the medians.

What is timed: the periodic solve only (:func:`recipsim.solve.periodic.solve_periodic`,
or :func:`.ivp.solve_periodic_ivp`), from the model's initial state to the converged
revolution, after start-up: imports, case loading and model building (plenum states,
property tables) are outside, and the first run of each kind of rung in the process
(integrator, property backend, scene) is an untimed warm-up that loads or compiles the
numba code. Each repeat builds a fresh model (the solve moves the model's discharge
plenum). Repeats stop early once their total wall time exceeds the budget; fast rungs
repeat beyond the requested count until their solves add up to a minimum time.
"""

from __future__ import annotations

import dataclasses
import gc
import math
import statistics
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from recipsim.case.case import Case
from recipsim.case.load import load_case
from recipsim.errors import CaseError, RecipsimError
from recipsim.physics.speed_models import SPEED_MODELS
from recipsim.results.tables import cycle_table, summary
from recipsim.solve.drive import build_model_for
from recipsim.solve.motor_speed import solve_at_motor_speed
from recipsim.solve.periodic import solve_periodic
from recipsim.studies.bench.errors import compared_quantities
from recipsim.studies.bench.ivp import solve_periodic_ivp
from recipsim.studies.bench.ladder import (
    COMPILED,
    Rung,
    case_settings,
    fidelity,
    requested_settings,
)

OK = "ok"
UNCONVERGED = "unconverged"
UNAVAILABLE = "unavailable"
FAILED = "failed"
#: Most timed solves of one rung.
MAX_REPEATS = 50


@dataclass
class Outcome:
    """What one rung produced.

    Attributes
    ----------
    settings : dict
        The settings columns (integrator, tolerances, options).
    status : str
        ``ok``, ``unconverged`` (max_revolutions reached), ``unavailable`` (the case
        loader rejected an override) or ``failed`` (the solve raised).
    wall_times, cpu_times, build_times : list of float
        Per timed repeat: wall and CPU time of the solve, wall time of building the
        model [s].
    quantities : dict
        Compared summary quantities (:func:`.errors.compared_quantities`).
    trace : tuple of ndarray or None
        Crank angle [deg] and cylinder pressure [Pa] of the converged revolution.
    """

    rung: Rung
    settings: dict[str, Any]
    fidelity: str
    status: str
    message: str = ""
    wall_times: list[float] = field(default_factory=list)
    cpu_times: list[float] = field(default_factory=list)
    build_times: list[float] = field(default_factory=list)
    rhs_evaluations: int = 0
    steps: int = -1
    revolutions: int = 0
    residual: float = math.nan
    periodic_used: str = ""
    quantities: dict[str, float] = field(default_factory=dict)
    trace: tuple[np.ndarray, np.ndarray] | None = None

    @property
    def wall_time(self) -> float:
        """Median wall time of the solve [s] (NaN if it did not run)."""
        return statistics.median(self.wall_times) if self.wall_times else math.nan

    @property
    def cpu_time(self) -> float:
        """Median CPU time of the solve [s]."""
        return statistics.median(self.cpu_times) if self.cpu_times else math.nan

    @property
    def build_time(self) -> float:
        """Median wall time of building the model [s]."""
        return statistics.median(self.build_times) if self.build_times else math.nan

    @property
    def usable(self) -> bool:
        """Whether the rung produced a result to compare."""
        return self.status in (OK, UNCONVERGED)


def pressure_trace(cycle: Any) -> tuple[np.ndarray, np.ndarray]:
    """``(crank angle [deg], cylinder pressure [Pa])`` of a cycle table."""
    return (
        cycle["crank_angle [deg]"].to_numpy(dtype=float),
        cycle["cylinder_pressure [Pa]"].to_numpy(dtype=float),
    )


def solve(model: Any, integrator: str) -> Any:
    """Solve ``model`` to its periodic state with ``integrator`` (a PeriodicSolution);
    at the motor's slip speed (``options.speed = "motor_slip"``) the speed's fixed point,
    every revolution of its solves counted."""
    if integrator in COMPILED:
        # the rung names the compiled integrator, whatever the case file's solver.method
        solver = dataclasses.replace(model.case.solver, method=integrator)
        model = dataclasses.replace(model, case=dataclasses.replace(model.case, solver=solver))
        if SPEED_MODELS[model.case.options.speed].at_motor_load:  # as `recipsim run` solves it
            at_speed = solve_at_motor_speed(model.case)  # builds a model per speed
            return dataclasses.replace(at_speed.solution, revolutions=at_speed.revolutions)
        return solve_periodic(model)
    if SPEED_MODELS[model.case.options.speed].at_motor_load:
        raise CaseError(
            model.case.path, "options.speed", "the solve_ivp driver solves at the case's speed"
        )

    if getattr(model.case.solver, "periodic", "revolutions") == "shooting":
        raise CaseError(
            model.case.path, "solver.periodic", "the solve_ivp driver iterates revolutions only"
        )
    return solve_periodic_ivp(model, integrator)


def load_rung(path: Path, base_overrides: list[str], rung: Rung, base: Case) -> Case | Outcome:
    """The rung's case, or an ``unavailable`` outcome naming what the loader rejected."""
    try:
        return load_case(path, list(base_overrides) + list(rung.overrides))
    except CaseError as exc:
        settings = requested_settings(base, rung)
        return Outcome(rung, settings, fidelity(base, settings), UNAVAILABLE, str(exc))


def warm_up_key(case: Case, rung: Rung) -> tuple[str, ...]:
    """Rungs with the same key share compiled code: only the first needs a warm-up."""
    o = case.options
    return (rung.integrator, o.properties, o.mechanics, o.pressure, o.drive)


def run_rung(
    path: Path,
    base_overrides: list[str],
    rung: Rung,
    base: Case,
    repeats: int,
    budget: float = 60.0,
    warmed: set[tuple[str, ...]] | None = None,
    min_time: float = 0.0,
) -> Outcome:
    """Run ``rung`` in this process (``repeats`` timed solves within ``budget`` seconds).

    Parameters
    ----------
    path, base_overrides : Path, list of str
        The case file and the command's own overrides (applied before the rung's).
    base : Case
        The case as the command loaded it (for the fidelity and unavailable rows).
    warmed : set, optional
        Warm-up keys already run in this process; updated.
    min_time : float
        A fast rung repeats beyond ``repeats`` until its solves add up to ``min_time``
        seconds (at most :data:`MAX_REPEATS`), for a steadier median.
    """
    loaded = load_rung(path, base_overrides, rung, base)
    if isinstance(loaded, Outcome):
        return loaded
    case = loaded
    settings = case_settings(case, rung.integrator)
    out = Outcome(rung, settings, fidelity(base, settings), OK)
    warmed = set() if warmed is None else warmed
    try:
        key = warm_up_key(case, rung)
        if key not in warmed:
            solve(build_model_for(case), rung.integrator)
            warmed.add(key)
        solution = None
        while True:
            t0 = time.perf_counter()
            model = build_model_for(case)
            out.build_times.append(time.perf_counter() - t0)
            gc.collect()
            t0, c0 = time.perf_counter(), time.process_time()
            solution = solve(model, rung.integrator)
            out.wall_times.append(time.perf_counter() - t0)
            out.cpu_times.append(time.process_time() - c0)
            count, total = len(out.wall_times), sum(out.wall_times)
            if total > budget or count >= MAX_REPEATS:
                break
            if count >= repeats and total >= min_time:
                break
        assert solution is not None
        cycle = cycle_table(solution)
        row = summary(solution, cycle)
    except CaseError as exc:  # an option the loader accepts but the model cannot build yet
        out.status, out.message = UNAVAILABLE, str(exc)
        return out
    except RecipsimError as exc:
        out.status, out.message = FAILED, str(exc)
        return out
    except Exception as exc:  # noqa: BLE001 - a rung's failure is a row, not the end of the bench
        frame = traceback.extract_tb(exc.__traceback__)[-1]
        where = f"{Path(frame.filename).name}:{frame.lineno}"
        out.status, out.message = FAILED, f"{type(exc).__name__} at {where}: {exc}"
        return out
    fill_from_solution(out, solution, row, cycle)
    return out


def fill_from_solution(out: Outcome, solution: Any, row: dict[str, Any], cycle: Any) -> None:
    """Counters, status, compared quantities and the pressure trace of a solved rung."""
    out.rhs_evaluations = int(solution.nfev)
    out.steps = int(solution.steps)
    out.revolutions = int(solution.revolutions)
    out.residual = float(solution.residual)
    out.periodic_used = str(getattr(solution, "method", "revolutions"))
    if not solution.converged:
        out.status = UNCONVERGED
        out.message = (
            f"cycle residual {solution.residual:.2e} after {solution.revolutions} revolutions"
        )
    out.quantities = compared_quantities(row)
    out.trace = pressure_trace(cycle)
