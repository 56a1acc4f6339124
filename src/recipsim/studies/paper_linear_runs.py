"""The paper study's runs on linear bearings: the pinned runs (inverse dynamics at
constant speed) and the three flexible runs (``inertia``, ``gas`` undamped and
``gas_damped``) of :func:`recipsim.studies.paper.run_paper_study`."""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np
import pandas as pd

from recipsim.case.mechanism_spec import CrankGeometry, MechanismSpec, with_damping
from recipsim.model.mechanism_parameters import mechanism_parameters
from recipsim.model.pinned import pinned_loads
from recipsim.physics.mechanics.flexible_setup import initial_state
from recipsim.physics.mechanics.pinned import PinnedLoads
from recipsim.solve.mechanism_ivp import MechanismResult, simulate_mechanism
from recipsim.studies.paper_runs import CONFIGURATIONS, RunRecord
from recipsim.studies.paper_tables import cylinder_pressures, pinned_table
from recipsim.studies.paper_undamped import undamped_periodic

#: The undamped shooting integrates at this times the study's ``rtol``: an undamped
#: revolution's end state jumps with the step sequence by ~1e-3 of the vibration
#: amplitude at rtol 1e-6 under LSODA (the periodicity tolerance), ~1e-4 at 1e-7.
PERIODIC_RTOL_FACTOR = 0.1


def load_of(config: str) -> str:
    """The load (``inertia`` or ``gas``) of a configuration."""
    return "inertia" if config == "inertia" else "gas"


def pinned_runs(
    spec: MechanismSpec,
    geometry: CrankGeometry,
    angles: np.ndarray,
    loads: dict[str, np.ndarray],
    shell_pressure: float,
    omega: float,
    options: dict[str, Any],
) -> dict[str, tuple[pd.DataFrame, PinnedLoads, RunRecord]]:
    """The pinned runs at constant speed (inverse dynamics): table, loads, record."""
    n = options["samples_per_revolution"]
    theta = 2.0 * math.pi * np.arange(n) / n
    out = {}
    for load, pressures in loads.items():
        name = f"{load}_pinned"
        t0 = time.perf_counter()
        result = pinned_loads(
            spec,
            geometry,
            theta,
            omega,
            pressure_angles=angles,
            pressures=pressures,
            shell_pressure=shell_pressure,
        )
        table = pinned_table(result, omega, cylinder_pressures(theta, angles, pressures))
        wall = time.perf_counter() - t0
        out[name] = (
            table,
            result,
            RunRecord(name, load, "pinned", "algebraic", 0, True, None, 0, wall),
        )
    return out


def flexible_runs(
    spec: MechanismSpec,
    geometry: CrankGeometry,
    angles: np.ndarray,
    loads: dict[str, np.ndarray],
    shell_pressure: float,
    omega: float,
    options: dict[str, Any],
) -> dict[str, tuple[MechanismResult, RunRecord]]:
    """The three flexible runs on linear bearings (``solve_ivp`` driver), in order."""
    undamped = with_damping(spec, 0.0)
    out: dict[str, tuple[MechanismResult, RunRecord]] = {}
    jacobian: tuple[np.ndarray, np.ndarray] | None = None
    for config in CONFIGURATIONS:
        name = f"{config}_flexible"
        pressures = loads[load_of(config)]
        damped = config == "gas_damped"
        t0 = time.perf_counter()
        converged: bool | None
        if not damped and options["undamped_start"] == "periodic":
            result, jacobian = undamped_periodic(
                undamped,
                geometry,
                angles,
                pressures,
                shell_pressure,
                omega,
                rtol=PERIODIC_RTOL_FACTOR * options["rtol"],
                method=options["method"],
                samples_per_revolution=options["samples_per_revolution"],
                periodic_tolerance=options["periodic_tolerance"],
                max_revolutions=2 * options["max_revolutions"],
                jacobian=jacobian,
            )
            mode, converged = "shooting", result.converged
        else:
            extra: dict[str, Any] = {}
            if not damped and options["undamped_start"] == "unloaded":
                par = mechanism_parameters(undamped, geometry, shell_pressure=shell_pressure)
                extra["y0"] = initial_state(par, 0.0, omega, static_deflection=False)
            result = simulate_mechanism(
                spec if damped else undamped,
                geometry,
                angles,
                pressures,
                shell_pressure,
                omega,
                drive=options["drive"],
                revolutions=None if damped else options["undamped_revolutions"],
                rtol=options["rtol"],
                method=options["method"],
                samples_per_revolution=options["samples_per_revolution"],
                periodic_tolerance=options["periodic_tolerance"],
                max_revolutions=options["max_revolutions"],
                **extra,
            )
            mode = "until_periodic" if damped else "fixed_revolutions"
            converged = result.converged if damped else None
        wall = time.perf_counter() - t0
        record = RunRecord(
            name, config, "flexible", mode, result.revolutions, converged,
            result.cycle_change, result.nfev, wall,
        )  # fmt: skip
        out[name] = (result, record)
    return out
