"""Bearing loads, orbits and crank speed for the report: cycle columns and summary metrics.

Forces are those on the journal-side body (rotor for primary, secondary and
eccentric; piston for pin, piston_top and piston_skirt), inertial X, Y, Z [N];
displacements are journal minus bushing marker normal to the bearing axis [m] (zero
for the pinned mechanism). Every column name carries its unit; the columns that are
mechanism outputs take name and unit from the layout's table
(:data:`recipsim.physics.mechanics.layout.OUTPUTS`), meaning included; the others are
declared in :mod:`.column_docs`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from recipsim.physics.mechanics import layout as lay
from recipsim.physics.mechanics.pinned import N_PIN_OUT, PIN_DRIVE_TORQUE, pinned_reactions_array
from recipsim.results.columns import CycleLike

#: Displacement components reported for every bearing (normal to the Z journal axis;
#: the piston bearings, axis X, report X as 0).
_DISPLACEMENT_AXES = "xy"


def _column(index: int) -> str:
    """Report column of mechanism output ``index``: its layout name and unit."""
    return lay.OUTPUTS.column(index)


def bearing_columns(forces: np.ndarray, displacements: np.ndarray) -> dict[str, np.ndarray]:
    """Report columns from (n, 6, 3) force [N] and displacement [m] arrays."""
    cols: dict[str, np.ndarray] = {}
    magnitudes = np.sqrt((forces * forces).sum(axis=2))  # all bearings at once
    for i, name in enumerate(lay.BEARING_NAMES):
        for k in range(3):
            cols[_column(lay.A_BEARING_FORCE + 3 * i + k)] = forces[:, i, k]
        cols[f"bearing_force_{name} [N]"] = magnitudes[:, i]
        for ax in _DISPLACEMENT_AXES:
            k = "xyz".index(ax)
            cols[_column(lay.A_BEARING_DISPLACEMENT + 3 * i + k)] = displacements[:, i, k]
    return cols


def film_clearances(mech_par: np.ndarray) -> dict[str, float]:
    """Radial clearance [m] of every bearing that runs on an oil film, by name."""
    out = {}
    for i, name in enumerate(lay.BEARING_NAMES):
        row = lay.P_BEARINGS + i * lay.N_BEARING_PAR
        if int(mech_par[row + lay.BP_LAW]) != lay.LAW_LINEAR:
            out[name] = float(mech_par[row + lay.BP_CLEARANCE])
    return out


def flexible_columns(mech_aux: np.ndarray, mech_par: np.ndarray) -> dict[str, np.ndarray]:
    """Columns of the flexible mechanism from its outputs, shape (n, ``layout.N_AUX``),
    and its parameters (film bearings add film thickness, friction torque, absorbed
    power, contact force and peak film pressure)."""
    nb = lay.N_BEARINGS
    f = mech_aux[:, lay.A_BEARING_FORCE : lay.A_BEARING_FORCE + 3 * nb].reshape(-1, nb, 3)
    d = mech_aux[:, lay.A_BEARING_DISPLACEMENT : lay.A_BEARING_DISPLACEMENT + 3 * nb]
    cols = bearing_columns(f, d.reshape(-1, nb, 3))
    for index in (lay.A_CRANK_SPEED, lay.A_PISTON_LATERAL, lay.A_PISTON_TILT, lay.A_BEARING_POWER):
        cols[_column(index)] = mech_aux[:, index]
    films = film_clearances(mech_par)
    for name, clearance in films.items():
        i = lay.BEARING_NAMES.index(name)
        e = np.hypot(d[:, 3 * i], d[:, 3 * i + 1])
        cols[f"film_thickness_{name} [m]"] = clearance - e
        cols[f"eccentricity_ratio_{name} [-]"] = e / clearance
        for index in (
            lay.A_BEARING_TORQUE + 2 * i,  # on the journal-side body
            lay.A_BEARING_DISSIPATION + i,
            lay.A_BEARING_CONTACT + i,
            lay.A_BEARING_PEAK_PRESSURE + i,
        ):
            cols[_column(index)] = mech_aux[:, index]
    if "piston_skirt" in films:
        for index in (lay.A_PISTON_FRICTION, lay.A_PISTON_FRICTION_POWER):
            cols[_column(index)] = mech_aux[:, index]
    return cols


def _time_mean(values: np.ndarray, speed: np.ndarray) -> float:
    """Time mean over one revolution from uniform crank-angle samples (dt = dtheta/omega)."""
    return float(np.sum(values / speed) / np.sum(1.0 / speed))


def film_summary(cycle: CycleLike) -> dict[str, Any]:
    """Per film bearing: smallest film, largest eccentricity ratio, film pressure and
    contact force, friction power; the piston film's friction power."""
    row: dict[str, Any] = {}
    speed = cycle["crank_speed [rad/s]"].to_numpy()
    for name in lay.BEARING_NAMES:
        if f"film_thickness_{name} [m]" not in cycle:
            continue
        row[f"min_film_thickness_{name} [m]"] = float(cycle[f"film_thickness_{name} [m]"].min())
        row[f"max_eccentricity_ratio_{name} [-]"] = float(
            cycle[f"eccentricity_ratio_{name} [-]"].max()
        )
        row[f"max_film_pressure_{name} [Pa]"] = float(
            cycle[f"film_peak_pressure_{name} [Pa]"].max()
        )
        row[f"max_contact_force_{name} [N]"] = float(cycle[f"contact_force_{name} [N]"].max())
        loss = cycle[f"bearing_power_loss_{name} [W]"].to_numpy()
        row[f"friction_power_{name} [W]"] = _time_mean(loss, speed)
    if "piston_friction_power [W]" in cycle:
        row["piston_friction_power [W]"] = _time_mean(
            cycle["piston_friction_power [W]"].to_numpy(), speed
        )
    return row


def pinned_columns(
    theta: np.ndarray, pressure: np.ndarray, omega: float, mech_par: np.ndarray
) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """Columns of the pinned mechanism by inverse dynamics at constant speed.

    Returns the columns and the driving torque [N m] (which includes the inertia of
    every body, as the flexible model's does).
    """
    out = np.zeros((theta.shape[0], N_PIN_OUT))
    pinned_reactions_array(
        np.ascontiguousarray(theta), omega, np.ascontiguousarray(pressure), mech_par, out
    )
    nb = lay.N_BEARINGS
    forces = out[:, : 3 * nb].reshape(-1, nb, 3)
    cols = bearing_columns(forces, np.zeros_like(forces))
    cols[_column(lay.A_CRANK_SPEED)] = np.full(theta.shape, omega)
    for index in (lay.A_PISTON_LATERAL, lay.A_PISTON_TILT, lay.A_BEARING_POWER):
        cols[_column(index)] = np.zeros(theta.shape)  # the same columns as the flexible crank's
    return cols, out[:, PIN_DRIVE_TORQUE].copy()


def mechanism_summary(cycle: CycleLike) -> dict[str, Any]:
    """Per-bearing RMS and peak load, largest orbit radius; crank speed and its ripple.

    Statistics over the uniform crank-angle samples of the cycle table (an RMS over
    crank angle; at constant speed the same as over time).
    """
    row: dict[str, Any] = {}
    for name in lay.BEARING_NAMES:
        f = cycle[f"bearing_force_{name} [N]"].to_numpy()
        row[f"bearing_rms_{name} [N]"] = float(np.sqrt(np.mean(f * f)))
        row[f"bearing_max_{name} [N]"] = float(f.max())
    for name in lay.BEARING_NAMES:
        r2 = sum(
            cycle[f"bearing_displacement_{name}_{ax} [m]"].to_numpy() ** 2
            for ax in _DISPLACEMENT_AXES
        )
        row[f"orbit_radius_max_{name} [m]"] = float(np.sqrt(np.max(r2)))
    speed = cycle["crank_speed [rad/s]"].to_numpy()
    # time mean (revolutions per second): the harmonic mean over uniform crank angles
    mean = float(1.0 / np.mean(1.0 / speed))
    row["mean_crank_speed [rpm]"] = mean * 60.0 / (2.0 * math.pi)
    row["crank_speed_ripple [-]"] = float((speed.max() - speed.min()) / mean)
    return row
