"""The paper study's runs on linear bearings: the pinned runs (inverse dynamics at
constant speed) and the three flexible runs (``inertia``, ``gas`` undamped and
``gas_damped``) of :func:`recipsim.studies.paper.run_paper_study`.

Every flexible run is the study's case under the load's pressure curve, solved like
any case (:func:`recipsim.studies.paper_load_run.solve_load`: the compiled scene and the
shared periodic solver): the damped run by revolutions until periodic; an undamped
periodic response by ``solver.periodic = "shooting"`` at constant speed and a tenth
of the study's ``rtol`` (the ``gas`` run starting from the ``inertia`` run's Jacobian:
at constant speed the pressure table only adds a forcing, the map's linear part is the
same); an undamped transient as a fixed number of revolutions
(``solver.min_revolutions = solver.max_revolutions``) from the quasi-static or the
unloaded pose at TDC (:func:`tdc_start`), as the paper's time-marching runs start.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import Any

import numpy as np
import pandas as pd

from recipsim.case.load import Case
from recipsim.model import scenes
from recipsim.model.build import Model, crank_geometry
from recipsim.model.pinned import pinned_loads
from recipsim.physics.mechanics import layout as mlay
from recipsim.physics.mechanics.crank_trains import FLEXIBLE, PINNED
from recipsim.physics.mechanics.drives import CONSTANT_SPEED
from recipsim.physics.mechanics.flexible_setup import initial_state
from recipsim.physics.mechanics.pinned import PinnedLoads
from recipsim.physics.mechanics.tabulated import PressureCurve, tabulated_pressure
from recipsim.studies.paper_load_run import LoadRun, solve_load, tabulated_case
from recipsim.studies.paper_runs import CONFIGURATIONS, DEFLECTED_START, RunRecord
from recipsim.studies.paper_tables import cylinder_pressures, pinned_table

#: The undamped shooting integrates at this times the study's ``rtol``: an undamped
#: revolution's end state jumps with the step sequence by ~1e-4 of the vibration
#: amplitude at rtol 1e-6 (the periodicity tolerance's size): see
#: :mod:`recipsim.solve.shooting`.
PERIODIC_RTOL_FACTOR = 0.1


def load_of(config: str) -> str:
    """The load (``inertia`` or ``gas``) of a configuration."""
    return "inertia" if config == "inertia" else "gas"


def pinned_runs(
    case: Case, loads: dict[str, PressureCurve], options: dict[str, Any]
) -> dict[str, tuple[pd.DataFrame, PinnedLoads, RunRecord]]:
    """The pinned runs at constant speed (inverse dynamics): table, loads, record."""
    n = options["samples_per_revolution"]
    theta = 2.0 * math.pi * np.arange(n) / n
    omega = case.operating_point.shaft_speed
    out = {}
    for load, curve in loads.items():
        name = f"{load}_pinned"
        t0 = time.perf_counter()
        result = pinned_loads(
            case.mechanism,
            crank_geometry(case),
            theta,
            omega,
            pressure_angles=curve.crank_angle,
            pressures=curve.pressure,
            shell_pressure=case.operating_point.shell_pressure,
        )
        pressure = cylinder_pressures(theta, curve.crank_angle, curve.pressure)
        table = pinned_table(result, omega, pressure)
        wall = time.perf_counter() - t0
        out[name] = (
            table,
            result,
            RunRecord(name, load, PINNED.name, "algebraic", 0, True, None, 0, wall),
        )
    return out


def flexible_case(
    case: Case, curve: PressureCurve, config: str, options: dict[str, Any]
) -> tuple[Case, str]:
    """The case of one flexible run and how it is made (the record's ``mode``)."""
    changes: dict[str, Any] = {
        "solver.rtol": options["rtol"],
        "solver.samples_per_revolution": options["samples_per_revolution"],
        "solver.cycle_tolerance": options["periodic_tolerance"],
        "solver.max_revolutions": options["max_revolutions"],
        "solver.min_revolutions": 2,
        "solver.periodic": "revolutions",
        "options.drive": options["drive"],
    }
    if config == "gas_damped":
        return tabulated_case(case, curve, changes, config), "until_periodic"
    changes.update({f"bearings.{name}.damping": 0.0 for name in mlay.BEARING_NAMES})
    if options["undamped_start"] == "periodic":
        changes["options.drive"] = CONSTANT_SPEED.name
        changes["solver.periodic"] = "shooting"
        changes["solver.rtol"] = PERIODIC_RTOL_FACTOR * options["rtol"]
        changes["solver.max_revolutions"] = 2 * options["max_revolutions"]
        return tabulated_case(case, curve, changes, config), "shooting"
    n = options["undamped_revolutions"]
    changes["solver.min_revolutions"] = changes["solver.max_revolutions"] = n
    return tabulated_case(case, curve, changes, config), "fixed_revolutions"


def tdc_start(curve: PressureCurve, deflected: bool) -> Callable[[Model], Model]:
    """A start at TDC, as a time-marching run of the paper makes it: the pinned pose with
    the bearings deflected by the pinned loads under ``curve`` (``deflected``) or
    undeflected; the model's revolutions then run from TDC to TDC."""
    p_tdc = tabulated_pressure(0.0, curve.crank_angle, curve.pressure)

    def start(model: Model) -> Model:
        y0 = model.y0.copy()  # the built model's is read-only
        omega = scenes.named_state(model.scene, y0).mechanism_crank_speed
        model.mechanism_state(y0)[:] = initial_state(
            model.mechanism_par.copy(), 0.0, omega, p_tdc, static_deflection=deflected
        )
        return model.with_start(y0, 0.0)  # the samples' crank angles at constant speed

    return start


def flexible_runs(
    case: Case, loads: dict[str, PressureCurve], options: dict[str, Any]
) -> dict[str, tuple[LoadRun, RunRecord]]:
    """The three flexible runs on linear bearings, in order (see the module docstring)."""
    out: dict[str, tuple[LoadRun, RunRecord]] = {}
    jacobian = None  # at constant speed the loads share the map's linear part
    for config in CONFIGURATIONS:
        name = f"{config}_flexible"
        run_case, mode = flexible_case(case, loads[load_of(config)], config, options)
        start = None
        if mode == "fixed_revolutions":
            start = tdc_start(loads[load_of(config)], options["undamped_start"] == DEFLECTED_START)
        t0 = time.perf_counter()
        result = solve_load(config, run_case, start, jacobian if mode == "shooting" else None)
        if mode == "shooting":
            jacobian = result.jacobian
        wall = time.perf_counter() - t0
        converged = None if mode == "fixed_revolutions" else result.converged
        record = RunRecord(
            name, config, FLEXIBLE.name, mode, result.revolutions, converged,
            result.residual, result.nfev, wall,
        )  # fmt: skip
        out[name] = (result, record)
    return out
