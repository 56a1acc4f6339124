"""The cycle table: one row per uniform crank-angle sample of the converged revolution.

Every column name carries its unit (``cylinder_pressure [Pa]``); the meaning of each
column is its layout entry's or declared in :mod:`.column_docs` (``reports/README.md``'s
tables are generated from them). :func:`cycle_columns` gives the columns as
numpy arrays, :func:`cycle_table` the DataFrame of them (the same values);
:func:`pinned_tabulated_cycle` is the table of the pinned mechanism under a tabulated
pressure, where nothing is integrated (:func:`pinned_tabulated_columns` its columns).
The gas's columns are those the case's pressure source declares
(:attr:`~recipsim.slots.ModelChoice.outputs`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pandas as pd

from recipsim.case.load import Case
from recipsim.model.build import case_mechanism_parameters, scenes
from recipsim.physics.kinematics import piston_displacement
from recipsim.physics.mechanics.tabulated import tabulated_pressure
from recipsim.physics.thermo import cylinder as cyl
from recipsim.physics.thermo.pressure_sources import (
    GAS_OUTPUTS,
    PRESSURE_SOURCES,
    VALVE_STATE_OUTPUTS,
)
from recipsim.results.bearings import flexible_columns, pinned_columns
from recipsim.solve.periodic import PeriodicSolution, sample_outputs


def _column(index: int) -> str:
    """Report column of cylinder output ``index``: ``"<name> [<unit>]"``."""
    return cyl.OUTPUTS.column(index)


#: Output slots that need the gas state: those the cylinder pressure source declares
#: (:data:`~recipsim.physics.thermo.pressure_sources.GAS_OUTPUTS`, in its order).
_GAS_OUTPUTS = tuple(cyl.OUTPUTS.entry(output.name).index for output in GAS_OUTPUTS)
#: The cycle columns a pressure source adds (its declared outputs): a case's table has
#: those of its own source only.
_SOURCE_COLUMNS = frozenset(
    output.column
    for source in PRESSURE_SOURCES
    for output in source.outputs
    if output.table == "cycle"
)

#: Output slots the cycle table writes, in column order; each column's name and unit are
#: its :data:`~recipsim.physics.thermo.cylinder.OUTPUTS` entry's (``"name [unit]"``).
_CYCLE_OUTPUTS = (
    cyl.A_VOLUME,
    cyl.A_PRESSURE,
    *_GAS_OUTPUTS,
    cyl.A_DISPLACEMENT,
    cyl.A_PISTON_VELOCITY,
    cyl.A_FORCE_GAS,
    cyl.A_TORQUE_GAS,
    cyl.A_TORQUE_INERTIA,
    cyl.A_TORQUE_SHAFT,
)

#: The cycle table's output columns: (``"name [unit]"`` from the layout, output index).
CYCLE_COLUMNS: list[tuple[str, int]] = [(_column(i), i) for i in _CYCLE_OUTPUTS]

#: Cycle columns of the cylinder's outputs that need the gas state (absent when the
#: pressure is tabulated).
GAS_COLUMNS = {_column(i) for i in _GAS_OUTPUTS}

#: The scene outputs the cycle table reads on the rigid crank: the first this many (the
#: cylinder's; the mechanism's block is the pinned mechanism's inverse dynamics there).
_CYLINDER_WIDTH = 1 + max(i for i in _CYCLE_OUTPUTS)
#: The scene output holding the crank angle (by name: a bundle of all 111 costs more).
_CRANK_ANGLE = scenes.OUTPUTS.entry("crank_angle").index


def _uniform_angles(n: int) -> np.ndarray:
    return 2.0 * math.pi * np.arange(n) / n


def _periodic_resample(theta: np.ndarray, values: np.ndarray, grid: np.ndarray) -> np.ndarray:
    """Columns of ``values`` (samples at crank angles ``theta``) at the angles ``grid``,
    as rows (slots, samples)."""
    order = np.argsort(theta, kind="stable")
    th = theta[order]
    out = np.empty((values.shape[1], grid.shape[0]))
    for j in range(values.shape[1]):
        out[j] = np.interp(grid, th, values[order, j], period=2.0 * math.pi)
    return out


def _time_from_tdc(grid: np.ndarray, speed: np.ndarray) -> np.ndarray:
    """Time since top dead centre at each crank angle of ``grid`` [s] (trapezoid on 1/omega)."""
    inv = 1.0 / speed
    steps = 0.5 * (inv[1:] + inv[:-1]) * np.diff(grid)
    return np.concatenate([[0.0], np.cumsum(steps)])


def cycle_table(solution: PeriodicSolution) -> pd.DataFrame:
    """One row per uniform crank-angle sample of the converged revolution, from TDC."""
    return pd.DataFrame(cycle_columns(solution))


def cycle_columns(solution: PeriodicSolution, full: bool = True) -> dict[str, np.ndarray]:
    """The columns of :func:`cycle_table`, in its order, as numpy arrays (what the
    summary reads).

    Parameters
    ----------
    solution : PeriodicSolution
        The converged run.
    full : bool
        Every column of the table; False: only those the summary and
        :func:`recipsim.results.outcome.classify` read (no ``time [s]``, no X, Y, Z
        bearing force components), the same values (a sweep point, which keeps only
        its summary row).
    """
    model = solution.model
    rev = solution.final
    rigid = model.scene == scenes.SCENE_CYLINDER
    out = sample_outputs(model, rev, cylinder_only=rigid)
    theta = np.mod(out[:, _CRANK_ANGLE], 2.0 * math.pi)
    # the TDC sample can land a round-off below 2 pi (then it would sort last as 360 deg)
    theta = np.where(theta > 2.0 * math.pi - 1e-9, 0.0, theta)
    if rigid:  # copy (sort) only the columns read
        out = out[:, :_CYLINDER_WIDTH]
    # the outputs as rows (slot, sample), sorted by crank angle: each column contiguous
    if model.free_speed:
        grid = _uniform_angles(model.case.solver.samples_per_revolution)
        rows = _periodic_resample(theta, out, grid)
        modes = np.rint(_periodic_resample(theta, rev.sample_modes.astype(float), grid))
    else:
        order = np.argsort(theta, kind="stable")
        grid = theta[order]
        rows = np.ascontiguousarray(out[order].T)
        modes = rev.sample_modes[order].T
    data: dict[str, Any] = {"crank_angle [deg]": np.degrees(grid)}
    source = PRESSURE_SOURCES[model.case.options.pressure]
    added = {output.column for output in source.outputs}
    for name, idx in CYCLE_COLUMNS:
        if name in added or name not in _SOURCE_COLUMNS:
            data[name] = rows[idx]
    for side, state in enumerate(VALVE_STATE_OUTPUTS):  # suction, discharge
        if state.column in added:
            data[state.column] = modes[side].astype(np.int64)
    omega = model.case.operating_point.shaft_speed
    if model.scene == scenes.SCENE_CYLINDER:
        par = case_mechanism_parameters(model.case)
        mech, _ = pinned_columns(grid, data[_column(cyl.A_PRESSURE)], omega, par, full)
    else:
        mech = flexible_columns(model.mechanism_outputs(rows.T), model.mechanism_par, full)
    data.update(mech)
    columns = {"crank_angle [deg]": np.round(data.pop("crank_angle [deg]"), 9)}
    if full:
        columns["time [s]"] = _time_from_tdc(grid, np.asarray(data["crank_speed [rad/s]"]))
    columns.update(data)
    return columns


def pinned_tabulated_cycle(case: Case) -> pd.DataFrame:
    """Cycle table of the pinned mechanism under the case's tabulated pressure (the
    DataFrame of :func:`pinned_tabulated_columns`)."""
    return pd.DataFrame(pinned_tabulated_columns(case))


def pinned_tabulated_columns(case: Case) -> dict[str, np.ndarray]:
    """The columns of :func:`pinned_tabulated_cycle`, in its order, as numpy arrays (what
    the summary reads).

    Nothing is integrated: inverse dynamics at every uniform crank angle.
    """
    assert case.pressure_curve is not None
    op = case.operating_point
    geo = case.geometry
    omega = op.shaft_speed
    grid = _uniform_angles(case.solver.samples_per_revolution)
    curve = case.pressure_curve
    p = np.array([tabulated_pressure(t, curve.crank_angle, curve.pressure) for t in grid])
    mech, torque = pinned_columns(grid, p, omega, case_mechanism_parameters(case))
    kin = np.array(
        [piston_displacement(t, geo.crank_radius, geo.connecting_rod_length)[:2] for t in grid]
    )
    x, dxdth = kin[:, 0], kin[:, 1]
    force = (p - op.shell_pressure) * geo.piston_area
    data: dict[str, Any] = {
        "crank_angle [deg]": np.round(np.degrees(grid), 9),
        "time [s]": grid / omega,
        _column(cyl.A_VOLUME): geo.clearance_volume + geo.piston_area * x,
        _column(cyl.A_PRESSURE): p,
        _column(cyl.A_DISPLACEMENT): x,
        _column(cyl.A_PISTON_VELOCITY): dxdth * omega,
        _column(cyl.A_FORCE_GAS): force,
        _column(cyl.A_TORQUE_GAS): force * dxdth,
        _column(cyl.A_TORQUE_INERTIA): torque + force * dxdth,
        _column(cyl.A_TORQUE_SHAFT): torque,
    }
    data.update(mech)
    return data
