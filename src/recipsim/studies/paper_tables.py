"""The paper study's tables: the report table of a pinned run (the bearing, torque and
speed columns of a flexible run's, the case's cycle table) and ``table1.csv`` (the layout
of the paper's Table 1)."""

from __future__ import annotations

from typing import Any

import numpy as np
import pandas as pd

from recipsim.physics.mechanics.layout import BEARING_NAMES
from recipsim.physics.mechanics.pinned import PinnedLoads
from recipsim.physics.mechanics.tabulated import tabulated_pressure
from recipsim.studies.paper_load_run import LoadRun
from recipsim.studies.paper_runs import (
    CONFIGURATIONS,
    HYDRODYNAMIC_RUNS,
    PINNED_OF,
    PRESSURE_COLUMN,
    RUNS,
)


def cylinder_pressures(theta: np.ndarray, angles: np.ndarray, pressures: np.ndarray) -> np.ndarray:
    """Cylinder pressure [Pa] of the table (``angles`` [rad], ``pressures`` [Pa]) at the
    crank angles ``theta`` [rad]."""
    return np.array([tabulated_pressure(float(t), angles, pressures) for t in theta])


def pinned_table(
    loads: PinnedLoads, omega: float, cylinder_pressure: np.ndarray | None = None
) -> pd.DataFrame:
    """Report table of a pinned run, with the bearing, torque and speed columns of a
    flexible one.

    Parameters
    ----------
    loads : PinnedLoads
        Pinned results at crank angles from TDC over one revolution [rad].
    omega : float
        Crank speed [rad/s] (constant).
    cylinder_pressure : numpy.ndarray, optional
        Cylinder pressure at the samples [Pa], added as ``cylinder_pressure [Pa]``.

    Returns
    -------
    pandas.DataFrame
        ``crank_angle [deg]``, ``time [s]``, ``bearing_force_<name>_x|_y|_z [N]``,
        ``bearing_force_<name> [N]``, ``bearing_displacement_<name>_x|_y|_z [m]``
        (zero: rigid bearings), ``drive_torque [N m]``, ``crank_speed [rad/s]``,
        ``piston_displacement [m]``, ``piston_lateral [m]``, ``piston_tilt [rad]``.
    """
    theta = loads.crank_angle
    n = theta.size
    cols: dict[str, np.ndarray] = {
        "crank_angle [deg]": np.degrees(theta),
        "time [s]": (theta - theta[0]) / omega,
    }
    for i, name in enumerate(BEARING_NAMES):
        for k, ax in enumerate("xyz"):
            cols[f"bearing_force_{name}_{ax} [N]"] = loads.bearing_force[:, i, k]
        cols[f"bearing_force_{name} [N]"] = np.linalg.norm(loads.bearing_force[:, i], axis=1)
        for ax in "xyz":
            cols[f"bearing_displacement_{name}_{ax} [m]"] = np.zeros(n)
    cols["drive_torque [N m]"] = loads.drive_torque
    cols["crank_speed [rad/s]"] = np.full(n, omega)
    cols["piston_displacement [m]"] = loads.piston_displacement
    cols["piston_lateral [m]"] = np.zeros(n)
    cols["piston_tilt [rad]"] = np.zeros(n)
    if cylinder_pressure is not None:
        cols[PRESSURE_COLUMN] = np.asarray(cylinder_pressure, dtype=float)
    return pd.DataFrame(cols)


def flexible_table(run: LoadRun) -> pd.DataFrame:
    """Report table of a flexible run: the case's cycle table (``drive_torque [N m]``
    included) with the axial displacements ``bearing_displacement_<name>_z [m]`` (zero:
    the displacements are normal to the bearing axes), as in the pinned tables."""
    table = run.cycle.copy()
    for name in BEARING_NAMES:
        table[f"bearing_displacement_{name}_z [m]"] = 0.0
    return table


def table1_columns(hydrodynamic: bool = False) -> list[str]:
    """Column names of ``table1.csv``, in order (``bearing`` first).

    Parameters
    ----------
    hydrodynamic : bool
        With the hydrodynamic column's entries (after the flexible ones of each kind).
    """
    runs = [*RUNS, *(HYDRODYNAMIC_RUNS if hydrodynamic else ())]
    compared = [f"{c}_flexible" for c in CONFIGURATIONS]
    if hydrodynamic:
        compared += list(HYDRODYNAMIC_RUNS)
    rms = [f"{run}_rms [N]" for run in runs]
    rel = [f"{run}_vs_pinned [-]" for run in compared]
    peak = [f"{run}_peak [N]" for run in runs]
    orbit = [f"{run}_orbit_max [m]" for run in compared]
    film = [f"{run}_min_film [m]" for run in HYDRODYNAMIC_RUNS] if hydrodynamic else []
    return ["bearing", *rms, *rel, *peak, *orbit, *film]


def build_table1(
    pinned: dict[str, PinnedLoads],
    flexible: dict[str, LoadRun],
    hydrodynamic: dict[str, LoadRun],
) -> pd.DataFrame:
    """``table1.csv``: per bearing the RMS and peak loads of every run, the flexible and
    hydrodynamic runs against pinned, orbits and films (:func:`table1_columns`)."""
    rms: dict[str, np.ndarray] = {k: v.force_rms() for k, v in pinned.items()}
    peak: dict[str, np.ndarray] = {k: v.force_peak() for k, v in pinned.items()}
    orbit: dict[str, np.ndarray] = {}
    for k, v in flexible.items():
        rms[k], peak[k], orbit[k] = v.force_rms, v.force_peak, v.orbit_radius_max
    cols: dict[str, Any] = {"bearing": list(BEARING_NAMES)}
    for config, h in hydrodynamic.items():
        run = f"{config}_hydrodynamic"
        rms[run], peak[run], orbit[run] = h.force_rms, h.force_peak, h.orbit_radius_max
        cols[f"{run}_min_film [m]"] = h.min_film_thickness
    for run in [*RUNS, *(f"{c}_hydrodynamic" for c in hydrodynamic)]:
        config, model = run.rsplit("_", 1)
        cols[f"{run}_rms [N]"] = rms[run]
        cols[f"{run}_peak [N]"] = peak[run]
        if model != "pinned":
            cols[f"{run}_vs_pinned [-]"] = rms[run] / rms[PINNED_OF[config]] - 1.0
            cols[f"{run}_orbit_max [m]"] = orbit[run]
    table = pd.DataFrame(cols)
    return table[table1_columns(bool(hydrodynamic))]
