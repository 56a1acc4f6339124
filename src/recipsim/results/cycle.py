"""The cycle table: one row per uniform crank-angle sample of the converged revolution.

Every column name carries its unit (``cylinder_pressure [Pa]``); the meaning of each
column is documented in ``reports/README.md``. :func:`cycle_columns` gives the columns as
numpy arrays, :func:`cycle_table` the DataFrame of them (the same values);
:func:`pinned_tabulated_cycle` is the table of the pinned mechanism under a tabulated
pressure, where nothing is integrated.
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
from recipsim.results.bearings import flexible_columns, pinned_columns
from recipsim.solve.periodic import PeriodicSolution, sample_outputs

CYCLE_COLUMNS: list[tuple[str, int]] = [
    ("cylinder_volume [m3]", cyl.A_VOLUME),
    ("cylinder_pressure [Pa]", cyl.A_PRESSURE),
    ("gas_temperature [K]", cyl.A_TEMPERATURE),
    ("gas_density [kg/m3]", cyl.A_DENSITY),
    ("gas_mass [kg]", cyl.A_MASS),
    ("gas_specific_enthalpy [J/kg]", cyl.A_ENTHALPY),
    ("vapour_quality [-]", cyl.A_QUALITY),
    ("suction_valve_lift [m]", cyl.A_LIFT_S),
    ("discharge_valve_lift [m]", cyl.A_LIFT_D),
    ("suction_valve_velocity [m/s]", cyl.A_VEL_S),
    ("discharge_valve_velocity [m/s]", cyl.A_VEL_D),
    ("suction_mass_flow [kg/s]", cyl.A_MDOT_SUC),
    ("discharge_mass_flow [kg/s]", cyl.A_MDOT_DIS),
    ("leakage_mass_flow [kg/s]", cyl.A_MDOT_LEAK),
    ("leakage_eccentricity [-]", cyl.A_LEAK_ECC),
    ("heat_flow_to_gas [W]", cyl.A_QDOT),
    ("heat_transfer_coefficient [W/(m2 K)]", cyl.A_HTC),
    ("piston_displacement [m]", cyl.A_DISPLACEMENT),
    ("piston_velocity [m/s]", cyl.A_PISTON_VELOCITY),
    ("gas_force [N]", cyl.A_FORCE_GAS),
    ("gas_torque [N m]", cyl.A_TORQUE_GAS),
    ("inertia_torque [N m]", cyl.A_TORQUE_INERTIA),
    ("shaft_torque [N m]", cyl.A_TORQUE_SHAFT),
]


#: Cycle columns that need the gas state (absent when the pressure is tabulated).
GAS_COLUMNS = {
    "gas_temperature [K]",
    "gas_density [kg/m3]",
    "gas_mass [kg]",
    "gas_specific_enthalpy [J/kg]",
    "vapour_quality [-]",
    "suction_valve_lift [m]",
    "discharge_valve_lift [m]",
    "suction_valve_velocity [m/s]",
    "discharge_valve_velocity [m/s]",
    "suction_mass_flow [kg/s]",
    "discharge_mass_flow [kg/s]",
    "leakage_mass_flow [kg/s]",
    "leakage_eccentricity [-]",
    "heat_flow_to_gas [W]",
    "heat_transfer_coefficient [W/(m2 K)]",
}


def _uniform_angles(n: int) -> np.ndarray:
    return 2.0 * math.pi * np.arange(n) / n


def _periodic_resample(theta: np.ndarray, values: np.ndarray, grid: np.ndarray) -> np.ndarray:
    """Columns of ``values`` (samples at crank angles ``theta``) at the angles ``grid``."""
    order = np.argsort(theta, kind="stable")
    th = theta[order]
    out = np.empty((grid.shape[0], values.shape[1]))
    for j in range(values.shape[1]):
        out[:, j] = np.interp(grid, th, values[order, j], period=2.0 * math.pi)
    return out


def _time_from_tdc(grid: np.ndarray, speed: np.ndarray) -> np.ndarray:
    """Time since top dead centre at each crank angle of ``grid`` [s] (trapezoid on 1/omega)."""
    inv = 1.0 / speed
    steps = 0.5 * (inv[1:] + inv[:-1]) * np.diff(grid)
    return np.concatenate([[0.0], np.cumsum(steps)])


def cycle_table(solution: PeriodicSolution) -> pd.DataFrame:
    """One row per uniform crank-angle sample of the converged revolution, from TDC."""
    return pd.DataFrame(cycle_columns(solution))


def cycle_columns(solution: PeriodicSolution) -> dict[str, np.ndarray]:
    """The columns of :func:`cycle_table`, in its order, as numpy arrays (what the
    summary of a point whose table is not kept reads, see :mod:`.columns`)."""
    model = solution.model
    rev = solution.final
    out = sample_outputs(model, rev)
    theta = np.mod(out[:, cyl.A_THETA], 2.0 * math.pi)
    # the TDC sample can land a round-off below 2 pi (then it would sort last as 360 deg)
    theta = np.where(theta > 2.0 * math.pi - 1e-9, 0.0, theta)
    if model.free_speed:
        grid = _uniform_angles(model.case.solver.samples_per_revolution)
        values = _periodic_resample(theta, out, grid)
        modes = np.rint(_periodic_resample(theta, rev.sample_modes.astype(float), grid))
    else:
        order = np.argsort(theta, kind="stable")
        grid = theta[order]
        values = out[order]
        modes = rev.sample_modes[order]
    data: dict[str, Any] = {"crank_angle [deg]": np.degrees(grid)}
    for name, idx in CYCLE_COLUMNS:
        if model.has_gas or name not in GAS_COLUMNS:
            data[name] = values[:, idx]
    if model.has_gas:
        data["suction_valve_state [-]"] = modes[:, 0].astype(np.int64)
        data["discharge_valve_state [-]"] = modes[:, 1].astype(np.int64)
    omega = model.case.operating_point.shaft_speed
    if model.scene == scenes.SCENE_CYLINDER:
        par = case_mechanism_parameters(model.case)
        mech, _ = pinned_columns(grid, data["cylinder_pressure [Pa]"], omega, par)
    else:
        mech = flexible_columns(values[:, scenes.A_MECH :], model.mechanism_par)
    data.update(mech)
    time = _time_from_tdc(grid, np.asarray(data["crank_speed [rad/s]"]))
    columns = {"crank_angle [deg]": np.round(data.pop("crank_angle [deg]"), 9), "time [s]": time}
    columns.update(data)
    return columns


def pinned_tabulated_cycle(case: Case) -> pd.DataFrame:
    """Cycle table of the pinned mechanism under the case's tabulated pressure.

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
        "cylinder_volume [m3]": geo.clearance_volume + geo.piston_area * x,
        "cylinder_pressure [Pa]": p,
        "piston_displacement [m]": x,
        "piston_velocity [m/s]": dxdth * omega,
        "gas_force [N]": force,
        "gas_torque [N m]": force * dxdth,
        "inertia_torque [N m]": torque + force * dxdth,
        "shaft_torque [N m]": torque,
    }
    data.update(mech)
    return pd.DataFrame(data)
