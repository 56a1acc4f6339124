"""Per-revolution tables and summary metrics of a converged cycle.

Every column name carries its unit (``cylinder_pressure [Pa]``); the meaning of each
column is documented in ``reports/README.md``.

Definitions (per converged revolution, f = shaft speed in revolutions per second):

- mass flows: net mass through each path per revolution times f;
- ``cooling_capacity``: discharge mass flow times (h of the suction gas at the
  suction pressure and the suction temperature - h of the liquid at the discharge
  pressure and liquid temperature), with the temperatures of the case's rating
  standard where it names one (:mod:`recipsim.case.rating`);
- ``indicated_power``: (-integral of p dV) f; ``shaft_power``: (integral of the
  driving torque times omega dt) f (equal to the indicated power on the frictionless
  rigid crank), plus the mean friction with ``options.friction = "mean"``;
- ``COP``: cooling capacity / motor electrical power (:mod:`recipsim.results.electrical`);
  ``indicated_COP``: cooling capacity / indicated power;
- ``volumetric_efficiency``: discharge mass flow / (rho_suction V_swept f);
- ``isentropic_efficiency``: discharge mass flow (h_2s - h_1) / shaft power;
- ``discharge_temperature``: T at the discharge pressure and the mass-weighted
  enthalpy of the gas that left through the discharge valve.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pandas as pd

from recipsim.case.load import Case
from recipsim.model.build import case_mechanism_parameters, scenes
from recipsim.model.plenum import isentropic_state
from recipsim.physics.kinematics import piston_displacement
from recipsim.physics.mechanics import layout as mlay
from recipsim.physics.mechanics.tabulated import tabulated_pressure
from recipsim.physics.thermo import cylinder as cyl
from recipsim.results.bearings import (
    film_summary,
    flexible_columns,
    mechanism_summary,
    pinned_columns,
)
from recipsim.results.electrical import loss_columns, rating_enthalpies
from recipsim.results.loss_breakdown import loss_breakdown
from recipsim.results.outcome import (
    discharge_valve_never_opens,
    property_error,
    state_or_explain,
)
from recipsim.results.thermal import thermal_columns
from recipsim.results.valve_metrics import valve_summary
from recipsim.solve.periodic import PeriodicSolution, sample_outputs
from recipsim.solve.residual import closures

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
    data["time [s]"] = _time_from_tdc(grid, np.asarray(data["crank_speed [rad/s]"]))
    frame = pd.DataFrame(data)
    frame.insert(1, "time [s]", frame.pop("time [s]"))
    frame["crank_angle [deg]"] = np.round(frame["crank_angle [deg]"].to_numpy(), 9)
    return frame


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


def _open_interval(angles: np.ndarray, flowing: np.ndarray) -> tuple[float, float]:
    """Opening and closing crank angle [deg] of the longest circular run of ``flowing``."""
    n = flowing.shape[0]
    if not flowing.any():
        return math.nan, math.nan
    if flowing.all():
        return 0.0, 360.0
    start = int(np.argmin(flowing))  # a closed sample: unroll the circle from here
    rolled = np.roll(flowing, -start)
    best = (0, 0, 0)
    i = 0
    while i < n:
        if rolled[i]:
            j = i
            while j < n and rolled[j]:
                j += 1
            if j - i > best[0]:
                best = (j - i, i, j - 1)
            i = j
        else:
            i += 1
    first = angles[(best[1] + start) % n]
    last = angles[(best[2] + start) % n]
    return float(first), float(last)


def _operating_columns(case: Case) -> dict[str, Any]:
    op = case.operating_point
    geo = case.geometry
    opts = case.options
    return {
        "case": case.name,
        "refrigerant": case.refrigerant.name,
        "pressure": opts.pressure,
        "mechanics": opts.mechanics,
        "drive": opts.drive,
        "valves": opts.valves,
        "heat_transfer": opts.heat_transfer,
        "leakage": opts.leakage,
        "evaporating_temperature [K]": op.evaporating_temperature,
        "condensing_temperature [K]": op.condensing_temperature,
        "suction_pressure [Pa]": op.suction_pressure,
        "suction_temperature [K]": op.suction_temperature,
        "discharge_pressure [Pa]": op.discharge_pressure,
        "liquid_temperature [K]": op.liquid_temperature,
        "pressure_ratio [-]": op.pressure_ratio,
        "shaft_speed [rpm]": op.shaft_speed * 60.0 / (2.0 * math.pi),
        "swept_volume [m3]": geo.swept_volume,
        "clearance_volume [m3]": geo.clearance_volume,
    }


GAS_SUMMARY = (
    "suction_mass_flow [kg/s]",
    "discharge_mass_flow [kg/s]",
    "leakage_mass_flow [kg/s]",
    "suction_backflow_mass_flow [kg/s]",
    "discharge_backflow_mass_flow [kg/s]",
    "cooling_capacity [W]",
    "isentropic_power [W]",
    "heat_to_wall [W]",
    "COP [-]",
    "indicated_COP [-]",
    "volumetric_efficiency [-]",
    "isentropic_efficiency [-]",
    "indicated_isentropic_efficiency [-]",
    "discharge_temperature [K]",
    "mass_balance_residual [-]",
    "energy_balance_residual [-]",
)


def _ratio(a: float, b: float) -> float:
    return a / b if b > 0.0 else math.nan


def _gas_metrics(
    solution: PeriodicSolution, freq: float, p_shaft: float, p_electrical: float
) -> dict[str, Any]:
    """Mass flows, capacity, efficiencies and closures from the cylinder quadratures."""
    model = solution.model
    op = model.case.operating_point
    geo = model.case.geometry
    y = solution.final.y_end
    m_suc = y[cyl.Q_MSUC_IN] - y[cyl.Q_MSUC_OUT]
    m_dis = y[cyl.Q_MDIS_OUT] - y[cyl.Q_MDIS_IN]
    m_leak = y[cyl.Q_MLEAK_OUT] - y[cyl.Q_MLEAK_IN]
    work = y[cyl.Q_WORK]
    heat_in = y[cyl.Q_HEAT]
    fluid = model.fluid
    suction = model.compressor_inlet
    h_gas, h_liquid = rating_enthalpies(fluid, op)
    try:
        h_2s = isentropic_state(fluid, suction, op.discharge_pressure)["h"]
    except (ValueError, ArithmeticError, RuntimeError) as exc:
        what = "the isentropic discharge enthalpy"
        raise property_error(exc, "ps", op.discharge_pressure, suction.entropy, what) from None
    mdot_dis = m_dis * freq
    mass_closure, energy_closure = closures(model, y)
    capacity = mdot_dis * (h_gas - h_liquid)
    p_ind = work * freq
    p_isen = mdot_dis * (h_2s - suction.enthalpy)
    if not discharge_valve_never_opens(solution):  # else NaN by design (no_delivery)
        h_mix = y[cyl.Q_HDIS_OUT] / y[cyl.Q_MDIS_OUT]
        what = "the discharge temperature (mass-weighted discharge enthalpy)"
        t_dis = state_or_explain(fluid, "ph", op.discharge_pressure, h_mix, what)["T"]
    else:
        t_dis = math.nan
    return {
        "suction_mass_flow [kg/s]": m_suc * freq,
        "discharge_mass_flow [kg/s]": mdot_dis,
        "leakage_mass_flow [kg/s]": m_leak * freq,
        "suction_backflow_mass_flow [kg/s]": y[cyl.Q_MSUC_OUT] * freq,
        "discharge_backflow_mass_flow [kg/s]": y[cyl.Q_MDIS_IN] * freq,
        "cooling_capacity [W]": capacity,
        "indicated_power [W]": p_ind,
        "isentropic_power [W]": p_isen,
        "heat_to_wall [W]": -heat_in * freq,
        "COP [-]": _ratio(capacity, p_electrical),
        "indicated_COP [-]": _ratio(capacity, p_ind),
        "volumetric_efficiency [-]": _ratio(mdot_dis, suction.density * geo.swept_volume * freq),
        "isentropic_efficiency [-]": _ratio(p_isen, p_shaft),
        "indicated_isentropic_efficiency [-]": _ratio(p_isen, p_ind),
        "discharge_temperature [K]": t_dis,
        "mass_balance_residual [-]": mass_closure,
        "energy_balance_residual [-]": energy_closure,
    }


def _loop_work(cycle: pd.DataFrame) -> float:
    """-closed integral of p dV over the cycle table [J] (trapezoid, periodic)."""
    p = cycle["cylinder_pressure [Pa]"].to_numpy()
    v = cycle["cylinder_volume [m3]"].to_numpy()
    dv = np.roll(v, -1) - v
    return float(-np.sum(0.5 * (p + np.roll(p, -1)) * dv))


def summary(
    solution: PeriodicSolution | None, cycle: pd.DataFrame | None = None, case: Case | None = None
) -> dict[str, Any]:
    """Summary metrics of the converged revolution (units in the keys).

    ``solution`` is None for the pinned mechanism under a tabulated pressure (nothing
    integrated); ``cycle`` and ``case`` are then required.
    """
    if solution is not None:
        case = solution.model.case
        if cycle is None:
            cycle = cycle_table(solution)
    assert case is not None and cycle is not None
    op = case.operating_point
    row = _operating_columns(case)
    mech = mechanism_summary(cycle)
    # one revolution's frequency: the mean crank speed when the speed is free
    freq = mech["mean_crank_speed [rpm]"] / 60.0
    model = solution.model if solution is not None else None
    bearing_loss = drive_work = math.nan
    if model is not None and model.scene != scenes.SCENE_CYLINDER:
        q = model.mechanism_offset + mlay.N_STATE
        drive_work = solution.final.y_end[q + scenes.MQ_DRIVE]  # type: ignore[union-attr]
        bearing_loss = solution.final.y_end[q + scenes.MQ_BEARINGS]  # type: ignore[union-attr]
        freq = 1.0 / solution.final.duration if model.free_speed else freq  # type: ignore[union-attr]
    elif model is not None:
        drive_work = solution.final.y_end[cyl.Q_SHAFT]  # type: ignore[union-attr]
        bearing_loss = 0.0
    else:
        torque = cycle["shaft_torque [N m]"].to_numpy()
        drive_work = float(np.mean(torque)) * 2.0 * math.pi
        bearing_loss = 0.0
    p_drive = drive_work * freq
    losses = loss_columns(case, cycle, p_drive, freq)
    p_shaft = losses.pop("shaft_power [W]")
    if model is not None and model.has_gas:
        gas = _gas_metrics(
            solution,  # type: ignore[arg-type]
            freq,
            p_shaft,
            losses["motor_electrical_power [W]"],
        )
    else:
        gas = dict.fromkeys(GAS_SUMMARY, math.nan)
        if model is not None:  # work of the gas on the piston, integrated with the motion
            q = model.mechanism_offset + mlay.N_STATE + scenes.MQ_GAS
            gas["indicated_power [W]"] = -solution.final.y_end[q] * freq  # type: ignore[union-attr]
        else:
            gas["indicated_power [W]"] = _loop_work(cycle) * freq
    row.update(gas)
    row.update(valve_summary(case.name, solution))
    row["shaft_power [W]"] = p_shaft
    row["bearing_dissipation_power [W]"] = bearing_loss * freq
    row.update(_motor_metrics(case, cycle, freq, p_drive))
    row.update(losses)
    row.update(mech)
    row.update(film_summary(cycle))
    if model is not None and model.scene != scenes.SCENE_CYLINDER:
        row["mechanical_efficiency [-]"] = _ratio(row["indicated_power [W]"], p_shaft)
        # drive power = indicated power + friction and bearing losses, over the revolution
        row["mechanical_balance_residual [-]"] = _ratio(
            p_drive - row["indicated_power [W]"] - bearing_loss * freq, p_drive
        )
    row.update(_solver_metrics(solution))
    row.update(thermal_columns(solution, case))
    row.update(loss_breakdown(row, cycle, solution))

    angles = cycle["crank_angle [deg]"].to_numpy()
    p = cycle["cylinder_pressure [Pa]"].to_numpy()
    torque = cycle["shaft_torque [N m]"].to_numpy()
    for side in ("suction", "discharge"):
        if model is None or not model.has_gas:
            row[f"{side}_valve_opening_angle [deg]"] = math.nan
            row[f"{side}_valve_closing_angle [deg]"] = math.nan
            continue
        flow = cycle[f"{side}_mass_flow [kg/s]"].to_numpy()
        if case.options.valves == "reed":
            flowing = cycle[f"{side}_valve_lift [m]"].to_numpy() > 0.0
        else:
            flowing = np.abs(flow) > 1e-12 * max(np.abs(flow).max(), 1e-300)
        opening, closing = _open_interval(angles, flowing)
        row[f"{side}_valve_opening_angle [deg]"] = opening
        row[f"{side}_valve_closing_angle [deg]"] = closing
    row["peak_cylinder_pressure [Pa]"] = float(p.max())
    row["minimum_cylinder_pressure [Pa]"] = float(p.min())
    row["discharge_overpressure [-]"] = float(p.max() / op.discharge_pressure - 1.0)
    row["suction_underpressure [-]"] = float(1.0 - p.min() / op.suction_pressure)
    # plus the mean friction's torque (options.friction = "mean"; else exactly 0)
    row["mean_shaft_torque [N m]"] = float(
        drive_work / (2.0 * math.pi) + (p_shaft - p_drive) / (2.0 * math.pi * freq)
    )
    row["peak_shaft_torque [N m]"] = float(torque.max())
    row["minimum_shaft_torque [N m]"] = float(torque.min())
    return row


MOTOR_SUMMARY = ("motor_input_power [W]", "motor_rotor_loss_power [W]", "motor_slip [-]")


def _motor_metrics(case: Case, cycle: pd.DataFrame, freq: float, p_shaft: float) -> dict[str, Any]:
    """Air-gap power, rotor copper loss and slip of the induction motor drive (NaN for
    other drives). The air-gap power ``omega_s * mean(T)`` (time mean) is the motor's
    input less its stator losses, which are not modelled."""
    if case.options.drive != "induction_motor" or case.motor is None:
        return dict.fromkeys(MOTOR_SUMMARY, math.nan)
    sync = case.motor.synchronous_speed
    torque = cycle["shaft_torque [N m]"].to_numpy()
    speed = cycle["crank_speed [rad/s]"].to_numpy()
    # time mean of T over one revolution from uniform crank-angle samples: dt = dtheta/omega
    mean_torque = float(np.mean(torque / speed)) * 2.0 * math.pi * freq
    p_in = sync * mean_torque
    return {
        "motor_input_power [W]": p_in,
        "motor_rotor_loss_power [W]": p_in - p_shaft,
        "motor_slip [-]": 1.0 - 2.0 * math.pi * freq / sync,
    }


def _solver_metrics(solution: PeriodicSolution | None) -> dict[str, Any]:
    if solution is None:  # inverse dynamics only: nothing to converge
        return {
            "revolutions [-]": 0,
            "cycle_residual [-]": 0.0,
            "converged [-]": True,
            "rhs_evaluations [-]": 0,
            "steps [-]": 0,
            "rejected_steps [-]": 0,
            "events [-]": 0,
            "wall_time [s]": 0.0,
            "periodic_method": "none",
            "newton_iterations [-]": 0,
        }
    return {
        "revolutions [-]": solution.revolutions,
        "cycle_residual [-]": solution.residual,
        "converged [-]": solution.converged,
        "rhs_evaluations [-]": solution.nfev,
        "steps [-]": solution.steps,
        "rejected_steps [-]": solution.rejected,
        "events [-]": solution.events,
        "wall_time [s]": solution.wall_time,
        "periodic_method": solution.method,
        "newton_iterations [-]": solution.newton_iterations,
    }
