"""Bearing loads, orbits and crank speed for the report: cycle columns and summary metrics.

Forces are those on the journal-side body (rotor for primary, secondary and
eccentric; piston for pin, piston_top and piston_skirt), inertial X, Y, Z [N];
displacements are journal minus bushing marker normal to the bearing axis [m] (zero
for the pinned mechanism). Every column name carries its unit; the columns that are
mechanism outputs take name and unit from the layout's table
(:data:`recipsim.physics.mechanics.layout.OUTPUTS`), meaning included; the others are
declared in :mod:`.column_docs`. A bearing on an oil film adds the columns its law
declares (:attr:`~recipsim.slots.ModelChoice.outputs`, per bearing with ``<name>``; a
law's others, such as the piston film's friction, once): the mechanism's outputs of those
names, or the orbit's film thickness and eccentricity ratio, and their summaries.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from recipsim.physics.mechanics import layout as lay
from recipsim.physics.mechanics.bearing_laws.law import BearingLaw
from recipsim.physics.mechanics.bearing_laws.registry import BEARING_LAWS
from recipsim.physics.mechanics.pinned import N_PIN_OUT, pinned_reactions_array
from recipsim.physics.mechanics.pinned import OUTPUTS as PIN_OUTPUTS
from recipsim.results.sampled import CycleColumns, nan_max, nan_min
from recipsim.slots import PER_BEARING, Output

#: Displacement components reported for every bearing (normal to the Z journal axis;
#: the piston bearings, axis X, report X as 0).
_DISPLACEMENT_AXES = "xy"
#: Outputs of the flexible crank reported as they are (the pinned crank reports the speed
#: and zeros in their place).
_FLEXIBLE_OUTPUTS = (
    "crank_speed",
    "piston_lateral_displacement",
    "piston_tilt",
    "bearing_power_loss",
)
#: Film outputs computed from the orbit, ``f(radial clearance [m], displacement [m])``;
#: a film law's other cycle outputs are the mechanism's output slots of their names.
_FROM_ORBIT = {
    "film_thickness_<name>": lambda clearance, e: clearance - e,
    "eccentricity_ratio_<name>": lambda clearance, e: e / clearance,
}


def _column(name: str) -> str:
    """Report column of the mechanism output ``name``: its layout name and unit."""
    return lay.OUTPUTS.entry(name).column


def _series(layout: Any, quantity: str) -> slice:
    """The slots ``<quantity>_<bearing>_<axis>`` of ``layout`` (bearing after bearing,
    X, Y, Z): one series (:meth:`Layout.add_series`), so a slice."""
    names = [f"{quantity}_{b}_{ax}" for b in lay.BEARING_NAMES for ax in "xyz"]
    first = layout.entry(names[0]).index
    assert [layout.entry(n).index for n in names] == list(range(first, first + len(names)))
    return slice(first, first + len(names))


#: The bearing series of the pinned reactions and of the flexible mechanism's outputs.
_PIN_FORCES = _series(PIN_OUTPUTS, "bearing_force")
_FORCES = _series(lay.OUTPUTS, "bearing_force")
_DISPLACEMENTS = _series(lay.OUTPUTS, "bearing_displacement")
_PIN_DRIVE_TORQUE = PIN_OUTPUTS.entry("drive_torque").index

#: Report columns per bearing: force components X, Y, Z, force magnitude, displacement
#: components (:data:`_DISPLACEMENT_AXES`).
_FORCE_AXIS_COLUMNS = tuple(
    tuple(_column(f"bearing_force_{name}_{ax}") for ax in "xyz") for name in lay.BEARING_NAMES
)
FORCE_COLUMNS = tuple(f"bearing_force_{name} [N]" for name in lay.BEARING_NAMES)
_DISPLACEMENT_COLUMNS = tuple(
    tuple(_column(f"bearing_displacement_{name}_{ax}") for ax in _DISPLACEMENT_AXES)
    for name in lay.BEARING_NAMES
)


def _bearing_series(outputs: np.ndarray, series: slice) -> np.ndarray:
    """The X, Y, Z outputs of every bearing in the columns ``series`` of ``outputs``
    (samples, slots), shape (6, 3, n): each bearing's component contiguous, as the
    column it becomes (a view where ``outputs`` is laid out so, else a copy)."""
    rows = np.ascontiguousarray(outputs[:, series].T)
    return rows.reshape(len(lay.BEARING_NAMES), 3, outputs.shape[0])


def _zeros(n: int) -> np.ndarray:
    """``n`` zeros, read-only (columns that are 0 share one)."""
    zero = np.zeros(n)
    zero.flags.writeable = False
    return zero


def bearing_columns(
    forces: np.ndarray, displacements: np.ndarray | None, components: bool = True
) -> dict[str, np.ndarray]:
    """Report columns from force [N] and displacement [m] arrays of shape (6, 3, n)
    (bearing, X Y Z, sample; displacements None: all 0, one read-only array); without
    ``components``, the forces' magnitudes but not their X, Y, Z columns (what the
    summary reads)."""
    cols: dict[str, np.ndarray] = {}
    zero = _zeros(forces.shape[2])
    # all bearings at once, x^2 + y^2 + z^2 left to right (as a sum over the axis)
    squares = forces * forces
    magnitudes = np.sqrt(squares[:, 0] + squares[:, 1] + squares[:, 2])
    for i, (axes, magnitude, moved) in enumerate(
        zip(_FORCE_AXIS_COLUMNS, FORCE_COLUMNS, _DISPLACEMENT_COLUMNS, strict=True)
    ):
        if components:
            for k, column in enumerate(axes):
                cols[column] = forces[i, k]
        cols[magnitude] = magnitudes[i]
        for column, ax in zip(moved, _DISPLACEMENT_AXES, strict=True):
            cols[column] = zero if displacements is None else displacements[i, "xyz".index(ax)]
    return cols


def film_laws(mech_par: np.ndarray) -> dict[str, BearingLaw]:
    """The law of every bearing that runs on an oil film, by bearing name (in
    ``layout.BEARING_NAMES`` order), from the mechanism's parameters."""
    par = lay.PAR.bundle(mech_par)
    laws = {
        name: BEARING_LAWS.by_code(int(getattr(par, f"{name}_law"))) for name in lay.BEARING_NAMES
    }
    return {name: law for name, law in laws.items() if law.film}


def _outputs(laws: dict[str, BearingLaw], table: str) -> list[tuple[str | None, Output]]:
    """The outputs the film bearings ``laws`` add to ``table``, as (bearing, output): each
    bearing's per-bearing ones in bearing order, then each law's others once (bearing
    None)."""
    found: list[tuple[str | None, Output]] = [
        (name, output)
        for name, law in laws.items()
        for output in law.outputs
        if output.table == table and output.per_bearing
    ]
    for law in {law.name: law for law in laws.values()}.values():  # once each, in bearing order
        found += [(None, o) for o in law.outputs if o.table == table and not o.per_bearing]
    return found


def _film_columns(out: Any, mech_par: np.ndarray) -> dict[str, np.ndarray]:
    """The cycle columns the film bearings' laws declare, from the mechanism's outputs by
    name ``out`` and its parameters."""
    cols: dict[str, np.ndarray] = {}
    par = lay.PAR.bundle(mech_par)
    for bearing, output in _outputs(film_laws(mech_par), "cycle"):
        if bearing is None:
            cols[output.column] = getattr(out, output.name)
        elif output.name in _FROM_ORBIT:
            e = np.hypot(
                getattr(out, f"bearing_displacement_{bearing}_x"),
                getattr(out, f"bearing_displacement_{bearing}_y"),
            )
            clearance = float(getattr(par, f"{bearing}_clearance"))
            cols[output.column_of(bearing)] = _FROM_ORBIT[output.name](clearance, e)
        else:
            slot = output.name.replace(PER_BEARING, bearing)
            cols[output.column_of(bearing)] = getattr(out, slot)
    return cols


def flexible_columns(
    mech_aux: np.ndarray, mech_par: np.ndarray, components: bool = True
) -> dict[str, np.ndarray]:
    """Columns of the flexible mechanism from its outputs, shape (n, ``layout.N_AUX``)
    (fastest as the transpose of a C-contiguous array: the columns are then its rows),
    and its parameters (a bearing on an oil film adds its law's columns: film thickness,
    friction torque, absorbed power, contact force, peak film pressure, ...);
    ``components`` as in :func:`bearing_columns`."""
    out = lay.OUTPUTS.bundle(mech_aux)
    cols = bearing_columns(
        _bearing_series(mech_aux, _FORCES),
        _bearing_series(mech_aux, _DISPLACEMENTS),
        components,
    )
    for field in _FLEXIBLE_OUTPUTS:
        cols[_column(field)] = getattr(out, field)
    cols.update(_film_columns(out, mech_par))
    return cols


def _time_mean(values: np.ndarray, speed: np.ndarray) -> float:
    """Time mean over one revolution from uniform crank-angle samples (dt = dtheta/omega)."""
    return float(np.sum(values / speed) / np.sum(1.0 / speed))


#: How a film law's summary output reduces its cycle output: the cycle output's name and
#: the reduction (the cycle's columns, the crank speed [rad/s]) -> value.
_SUMMARY_OF: dict[str, tuple[str, Any]] = {
    "min_film_thickness_<name>": ("film_thickness_<name>", lambda x, _: float(nan_min(x))),
    "max_eccentricity_ratio_<name>": ("eccentricity_ratio_<name>", lambda x, _: float(nan_max(x))),
    "max_film_pressure_<name>": ("film_peak_pressure_<name>", lambda x, _: float(nan_max(x))),
    "max_contact_force_<name>": ("contact_force_<name>", lambda x, _: float(nan_max(x))),
    "friction_power_<name>": ("bearing_power_loss_<name>", _time_mean),
    "piston_friction_power": ("piston_friction_power", _time_mean),
}


def film_summary(cycle: CycleColumns, laws: dict[str, BearingLaw]) -> dict[str, Any]:
    """The summary columns the film bearings' laws declare (per film bearing: smallest
    film, largest eccentricity ratio, film pressure and contact force, friction power;
    the piston film's friction power), from their cycle columns.

    Parameters
    ----------
    cycle : CycleColumns
        The cycle table, with the film bearings' columns.
    laws : dict
        The law of each bearing on an oil film (:func:`film_laws`; empty for the pinned
        crank, whose cycle has no film columns).
    """
    row: dict[str, Any] = {}
    speed = cycle["crank_speed [rad/s]"]
    by_name = {o.name: o for _, o in _outputs(laws, "cycle")}
    for bearing, output in _outputs(laws, "summary"):
        source, reduce = _SUMMARY_OF[output.name]
        if bearing is None:
            row[output.column] = reduce(cycle[by_name[source].column], speed)
        else:
            row[output.column_of(bearing)] = reduce(
                cycle[by_name[source].column_of(bearing)], speed
            )
    return row


def pinned_columns(
    theta: np.ndarray,
    pressure: np.ndarray,
    omega: float,
    mech_par: np.ndarray,
    components: bool = True,
) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """Columns of the pinned mechanism by inverse dynamics at constant speed
    (``components`` as in :func:`bearing_columns`).

    Returns the columns and the driving torque [N m] (which includes the inertia of
    every body, as the flexible model's does).
    """
    out = np.zeros((theta.shape[0], N_PIN_OUT))
    pinned_reactions_array(
        np.ascontiguousarray(theta), omega, np.ascontiguousarray(pressure), mech_par, out
    )
    forces = _bearing_series(out, _PIN_FORCES)
    cols = bearing_columns(forces, None, components)
    cols[_column("crank_speed")] = np.full(theta.shape, omega)
    zero = _zeros(theta.shape[0])
    for field in _FLEXIBLE_OUTPUTS[1:]:
        cols[_column(field)] = zero  # the same columns as the flexible crank's
    return cols, out[:, _PIN_DRIVE_TORQUE].copy()


#: Summary columns per bearing: RMS load, peak load, largest orbit radius.
_RMS_COLUMNS = tuple(f"bearing_rms_{name} [N]" for name in lay.BEARING_NAMES)
_MAX_COLUMNS = tuple(f"bearing_max_{name} [N]" for name in lay.BEARING_NAMES)
_ORBIT_COLUMNS = tuple(f"orbit_radius_max_{name} [m]" for name in lay.BEARING_NAMES)


def mechanism_summary(cycle: CycleColumns, pinned: bool = False) -> dict[str, Any]:
    """Per-bearing RMS and peak load, largest orbit radius; crank speed and its ripple.

    Statistics over the uniform crank-angle samples of the cycle table (an RMS over
    crank angle; at constant speed the same as over time). ``pinned``: the table is the
    pinned mechanism's, whose journals do not move in their bushings (its displacement
    columns are 0): the orbit radii are 0 without reading them.
    """
    # one row per bearing: each row's reduction is the column's own (same summation)
    f = np.stack([cycle[c] for c in FORCE_COLUMNS])
    rms = np.sqrt(np.mean(f * f, axis=1)).tolist()
    peak = f.max(axis=1).tolist()
    if pinned:
        orbit = [0.0] * len(lay.BEARING_NAMES)
    else:
        x = np.stack([cycle[moved[0]] for moved in _DISPLACEMENT_COLUMNS])
        y = np.stack([cycle[moved[1]] for moved in _DISPLACEMENT_COLUMNS])
        r2 = x * x + y * y  # the X and Y displacements (_DISPLACEMENT_AXES)
        orbit = np.sqrt(np.max(r2, axis=1)).tolist()
    row: dict[str, Any] = {}
    for rms_column, max_column, rms_value, peak_value in zip(
        _RMS_COLUMNS, _MAX_COLUMNS, rms, peak, strict=True
    ):
        row[rms_column] = rms_value
        row[max_column] = peak_value
    row.update(zip(_ORBIT_COLUMNS, orbit, strict=True))
    speed = cycle["crank_speed [rad/s]"]
    # time mean (revolutions per second): the harmonic mean over uniform crank angles
    mean = float(1.0 / np.mean(1.0 / speed))
    row["mean_crank_speed [rpm]"] = mean * 60.0 / (2.0 * math.pi)
    row["crank_speed_ripple [-]"] = float((speed.max() - speed.min()) / mean)
    return row
