"""Crank-angle metrics of a cycle for the summary: when each valve opens and closes,
the extremes of the cylinder pressure and of the shaft torque
(:func:`recipsim.results.tables.summary` writes them), from the cycle's statistics
(:mod:`recipsim.results.cycle_statistics`).
"""

from __future__ import annotations

import math

import numpy as np

from recipsim.case.load import Case
from recipsim.results.cycle_statistics import (
    ALWAYS_OPEN,
    NEVER_OPEN,
    S_CLOSE_SAMPLE,
    S_OPEN_SAMPLE,
    S_PRESSURE_MAX,
    S_PRESSURE_MIN,
    S_TORQUE_MAX,
    S_TORQUE_MIN,
)


def interval_angles(angles: np.ndarray, first: float, last: float) -> tuple[float, float]:
    """Opening and closing crank angle [deg] of an open run from its first and last
    sample (:func:`recipsim.results.cycle_statistics._longest_open_run`): NaN if the
    valve never opens, (0, 360) if it never closes."""
    if first == NEVER_OPEN:
        return math.nan, math.nan
    if first == ALWAYS_OPEN:
        return 0.0, 360.0
    return float(angles[int(first)]), float(angles[int(last)])


def valve_timing(stats: list[float], angles: np.ndarray) -> dict[str, float]:
    """Opening and closing crank angle of each valve: the ends of its longest circular
    run of open samples (a reed that lifts, or a mass flow above 1e-12 of its largest;
    NaN without a gas state).

    Parameters
    ----------
    stats : list of float
        The cycle's statistics (:func:`recipsim.results.cycle_statistics.cycle_statistics`).
    angles : ndarray
        The cycle table's crank angles [deg].

    Returns
    -------
    dict
        ``<side>_valve_opening_angle [deg]`` and ``..._closing_angle [deg]``, suction
        then discharge.
    """
    row: dict[str, float] = {}
    for k, side in enumerate(("suction", "discharge")):
        opening, closing = interval_angles(
            angles, stats[S_OPEN_SAMPLE + k], stats[S_CLOSE_SAMPLE + k]
        )
        row[f"{side}_valve_opening_angle [deg]"] = opening
        row[f"{side}_valve_closing_angle [deg]"] = closing
    return row


def pressure_and_torque(
    case: Case,
    stats: list[float],
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
    stats : list of float
        The cycle's statistics (:func:`recipsim.results.cycle_statistics.cycle_statistics`).
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
    p_max, p_min = stats[S_PRESSURE_MAX], stats[S_PRESSURE_MIN]
    return {
        "peak_cylinder_pressure [Pa]": p_max,
        "minimum_cylinder_pressure [Pa]": p_min,
        "discharge_overpressure [-]": p_max / op.discharge_pressure - 1.0,
        "suction_underpressure [-]": 1.0 - p_min / op.suction_pressure,
        # plus the mean friction's torque (options.friction = "mean"; else exactly 0)
        "mean_shaft_torque [N m]": float(
            drive_work / (2.0 * math.pi) + (p_shaft - p_drive) / (2.0 * math.pi * freq)
        ),
        "peak_shaft_torque [N m]": stats[S_TORQUE_MAX],
        "minimum_shaft_torque [N m]": stats[S_TORQUE_MIN],
    }
