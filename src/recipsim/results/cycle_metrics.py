"""Crank-angle metrics of a cycle table for the summary: when each valve opens and
closes, the extremes of the cylinder pressure and of the shaft torque
(:func:`recipsim.results.tables.summary` writes them).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from recipsim.case.load import Case
from recipsim.physics.thermo.valve_models import VALVE_MODELS
from recipsim.results.sampled import CycleColumns

if TYPE_CHECKING:
    from recipsim.solve.periodic import PeriodicSolution


def _open_interval(angles: np.ndarray, flowing: np.ndarray) -> tuple[float, float]:
    """Opening and closing crank angle [deg] of the longest circular run of ``flowing``."""
    n = flowing.shape[0]
    closed = np.flatnonzero(~flowing)
    if closed.size == n:
        return math.nan, math.nan
    if closed.size == 0:
        return 0.0, 360.0
    start = int(closed[0])  # a closed sample: unroll the circle from here
    rolled = np.concatenate((flowing[start:], flowing[:start], [False]))
    # closed at both ends: the changes alternate, the sample before a run and its last
    change = np.flatnonzero(rolled[1:] != rolled[:-1])
    before, last = change[0::2], change[1::2]
    best = int(np.argmax(last - before))  # the first of the longest
    return float(angles[(before[best] + 1 + start) % n]), float(angles[(last[best] + start) % n])


def valve_timing(
    solution: PeriodicSolution | None, case: Case, cycle: CycleColumns
) -> dict[str, float]:
    """Opening and closing crank angle of each valve (NaN without a gas state).

    Parameters
    ----------
    solution : PeriodicSolution or None
        As in :func:`recipsim.results.tables.summary`.
    case : Case
        Its ``options.valves`` picks the test: reed lift above 0, else a mass flow.
    cycle : CycleColumns
        The cycle table.

    Returns
    -------
    dict
        ``<side>_valve_opening_angle [deg]`` and ``..._closing_angle [deg]``, suction
        then discharge.
    """
    model = solution.model if solution is not None else None
    angles = cycle["crank_angle [deg]"]
    row: dict[str, float] = {}
    for side in ("suction", "discharge"):
        if model is None or not model.has_gas:
            row[f"{side}_valve_opening_angle [deg]"] = math.nan
            row[f"{side}_valve_closing_angle [deg]"] = math.nan
            continue
        if VALVE_MODELS[case.options.valves].moves_reeds:
            flowing = cycle[f"{side}_valve_lift [m]"] > 0.0
        else:
            flow = np.abs(cycle[f"{side}_mass_flow [kg/s]"])
            flowing = flow > 1e-12 * max(flow.max(), 1e-300)
        opening, closing = _open_interval(angles, flowing)
        row[f"{side}_valve_opening_angle [deg]"] = opening
        row[f"{side}_valve_closing_angle [deg]"] = closing
    return row


def pressure_and_torque(
    case: Case,
    cycle: CycleColumns,
    drive_work: float,
    p_shaft: float,
    p_drive: float,
    freq: float,
) -> dict[str, float]:
    """Extremes of the cylinder pressure and of the shaft torque, and the mean torque.

    Parameters
    ----------
    case : Case
        Its plenum pressures are the references of the over- and underpressure.
    cycle : CycleColumns
        The cycle table.
    drive_work : float
        Work of the drive per revolution [J].
    p_shaft, p_drive : float
        Shaft power and drive power [W] (they differ by the mean friction).
    freq : float
        Revolutions per second [1/s].

    Returns
    -------
    dict
        Column name to value.
    """
    op = case.operating_point
    p = cycle["cylinder_pressure [Pa]"]
    torque = cycle["shaft_torque [N m]"]
    p_max, p_min = float(p.max()), float(p.min())
    return {
        "peak_cylinder_pressure [Pa]": p_max,
        "minimum_cylinder_pressure [Pa]": p_min,
        "discharge_overpressure [-]": p_max / op.discharge_pressure - 1.0,
        "suction_underpressure [-]": 1.0 - p_min / op.suction_pressure,
        # plus the mean friction's torque (options.friction = "mean"; else exactly 0)
        "mean_shaft_torque [N m]": float(
            drive_work / (2.0 * math.pi) + (p_shaft - p_drive) / (2.0 * math.pi * freq)
        ),
        "peak_shaft_torque [N m]": float(torque.max()),
        "minimum_shaft_torque [N m]": float(torque.min()),
    }
