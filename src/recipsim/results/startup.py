"""Tables of the start-up from rest (:mod:`recipsim.solve.startup`): ``startup.csv``
against time and the start-up columns of the summary (reports/README.md)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pandas as pd

from recipsim.solve import startup as su
from recipsim.solve.startup import StartupRun


def startup_table(run: StartupRun) -> pd.DataFrame:
    """The transient at equal time steps (:data:`recipsim.solve.startup.SAMPLES_PER_PERIOD`
    per nominal period), units in the column names.

    Returns
    -------
    pandas.DataFrame
        ``time [s]``, ``crank_angle [deg]`` (from top dead centre, in [0, 360)),
        ``crank_speed [rad/s]``, ``crank_speed [rpm]``, ``motor_torque [N m]`` (positive
        along the rotation), ``cylinder_pressure [Pa]``, ``suction_pressure [Pa]`` and
        ``discharge_pressure [Pa]`` (the plenums along the pull-down ramp) and
        ``bearing_load_<name> [N]`` (force magnitude of each bearing).
    """
    tr = run.transient.trace
    speed = tr[:, su.TR_SPEED]
    col = su.TRACE.column  # "name [unit]" of a trace slot
    columns: dict[str, np.ndarray] = {
        col(su.TR_TIME): tr[:, su.TR_TIME],
        "crank_angle [deg]": np.degrees(np.mod(tr[:, su.TR_ANGLE], 2.0 * math.pi)),
        col(su.TR_SPEED): speed,
        "crank_speed [rpm]": speed * 30.0 / math.pi,
    }
    for slot in range(su.TR_MOTOR_TORQUE, su.N_TRACE):  # torque, pressures, bearing loads
        columns[col(slot)] = tr[:, slot]
    return pd.DataFrame(columns)


def startup_summary(run: StartupRun) -> dict[str, Any]:
    """Start-up columns of ``summary.csv`` (reports/README.md, "Start-up")."""
    t = run.transient
    e = t.energy
    return {
        "standstill_pressure [Pa]": t.standstill_pressure,
        "startup_time [s]": t.duration,
        "startup_revolutions [-]": t.windows,
        "startup_settled [-]": t.settled,
        "startup_wall_time [s]": t.wall_time,
        "startup_motor_work [J]": e.motor_work,
        "startup_kinetic_energy_gained [J]": e.kinetic_energy_gained,
        "startup_gas_work [J]": e.gas_work,
        "startup_dissipation [J]": e.dissipation,
        "startup_energy_closure [-]": e.closure,
        "startup_flow_difference [-]": run.flow_difference,
        "startup_power_difference [-]": run.power_difference,
    }
