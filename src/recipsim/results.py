"""Per-revolution tables and summary metrics of a converged cycle.

Every column name carries its unit (``cylinder_pressure [Pa]``); the meaning of each
column is documented in ``reports/README.md``.

Definitions (per converged revolution, f = shaft speed in revolutions per second):

- mass flows: net mass through each path per revolution times f;
- ``cooling_capacity``: discharge mass flow times (h of the suction gas at the
  compressor inlet - h of the liquid at the discharge pressure and liquid
  temperature), the ASHRAE 23 convention;
- ``indicated_power``: (-integral of p dV) f; ``shaft_power``: (integral of the
  driving torque times omega dt) f (equal to the indicated power on the frictionless
  rigid crank);
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

from .solve.periodic import PeriodicSolution, sample_outputs
from .thermo import cylinder as cyl

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
    ("heat_flow_to_gas [W]", cyl.A_QDOT),
    ("heat_transfer_coefficient [W/(m2 K)]", cyl.A_HTC),
    ("piston_displacement [m]", cyl.A_DISPLACEMENT),
    ("piston_velocity [m/s]", cyl.A_PISTON_VELOCITY),
    ("gas_force [N]", cyl.A_FORCE_GAS),
    ("gas_torque [N m]", cyl.A_TORQUE_GAS),
    ("inertia_torque [N m]", cyl.A_TORQUE_INERTIA),
    ("shaft_torque [N m]", cyl.A_TORQUE_SHAFT),
]


def cycle_table(solution: PeriodicSolution) -> pd.DataFrame:
    """One row per uniform crank-angle sample of the converged revolution, from TDC."""
    model = solution.model
    rev = solution.final
    out = sample_outputs(model, rev)
    theta = np.mod(out[:, cyl.A_THETA], 2.0 * math.pi)
    order = np.argsort(theta, kind="stable")
    omega = model.par[cyl.C_OMEGA]
    data: dict[str, Any] = {
        "crank_angle [deg]": np.degrees(theta[order]),
        "time [s]": theta[order] / omega,
    }
    for name, idx in CYCLE_COLUMNS:
        data[name] = out[order, idx]
    data["suction_valve_state [-]"] = rev.sample_modes[order, 0]
    data["discharge_valve_state [-]"] = rev.sample_modes[order, 1]
    frame = pd.DataFrame(data)
    frame["crank_angle [deg]"] = np.round(frame["crank_angle [deg]"].to_numpy(), 9)
    return frame


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


def summary(solution: PeriodicSolution, cycle: pd.DataFrame | None = None) -> dict[str, Any]:
    """Summary metrics of the converged revolution (units in the keys)."""
    model = solution.model
    case = model.case
    op = case.operating_point
    geo = case.geometry
    y = solution.final.y_end
    freq = op.shaft_speed / (2.0 * math.pi)
    m_suc = y[cyl.Q_MSUC_IN] - y[cyl.Q_MSUC_OUT]
    m_dis = y[cyl.Q_MDIS_OUT] - y[cyl.Q_MDIS_IN]
    m_leak = y[cyl.Q_MLEAK_OUT] - y[cyl.Q_MLEAK_IN]
    work = y[cyl.Q_WORK]
    shaft = y[cyl.Q_SHAFT]
    heat_in = y[cyl.Q_HEAT]
    h_out = (y[cyl.Q_HDIS_OUT] - y[cyl.Q_HDIS_IN]) + (y[cyl.Q_HLEAK_OUT] - y[cyl.Q_HLEAK_IN])
    h_in = y[cyl.Q_HSUC_IN] - y[cyl.Q_HSUC_OUT]
    fluid = model.fluid
    suction = model.suction
    h_liquid = fluid.state_pt(op.discharge_pressure, op.liquid_temperature)["h"]
    h_2s = fluid.state_ps(op.discharge_pressure, suction.entropy)["h"]
    mdot_dis = m_dis * freq
    capacity = mdot_dis * (suction.enthalpy - h_liquid)
    p_ind = work * freq
    p_shaft = shaft * freq
    p_isen = mdot_dis * (h_2s - suction.enthalpy)
    if y[cyl.Q_MDIS_OUT] > 0.0:
        h_mix = y[cyl.Q_HDIS_OUT] / y[cyl.Q_MDIS_OUT]
        t_dis = fluid.state_ph(op.discharge_pressure, h_mix)["T"]
    else:
        t_dis = math.nan

    def ratio(a: float, b: float) -> float:
        return a / b if b > 0.0 else math.nan

    row: dict[str, Any] = {
        "case": case.name,
        "refrigerant": case.refrigerant.name,
        "valves": case.options.valves,
        "heat_transfer": case.options.heat_transfer,
        "leakage": case.options.leakage,
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
        "suction_mass_flow [kg/s]": m_suc * freq,
        "discharge_mass_flow [kg/s]": mdot_dis,
        "leakage_mass_flow [kg/s]": m_leak * freq,
        "suction_backflow_mass_flow [kg/s]": y[cyl.Q_MSUC_OUT] * freq,
        "discharge_backflow_mass_flow [kg/s]": y[cyl.Q_MDIS_IN] * freq,
        "cooling_capacity [W]": capacity,
        "indicated_power [W]": p_ind,
        "shaft_power [W]": p_shaft,
        "isentropic_power [W]": p_isen,
        "heat_to_wall [W]": -heat_in * freq,
        "COP [-]": ratio(capacity, p_shaft),
        "volumetric_efficiency [-]": ratio(mdot_dis, suction.density * geo.swept_volume * freq),
        "isentropic_efficiency [-]": ratio(p_isen, p_shaft),
        "indicated_isentropic_efficiency [-]": ratio(p_isen, p_ind),
        "discharge_temperature [K]": t_dis,
        "mass_balance_residual [-]": ratio(m_suc - m_dis - m_leak, m_suc),
        "energy_balance_residual [-]": ratio(work - (h_out - h_in - heat_in), work),
        "revolutions [-]": solution.revolutions,
        "cycle_residual [-]": solution.residual,
        "converged [-]": solution.converged,
        "rhs_evaluations [-]": solution.nfev,
        "steps [-]": solution.steps,
        "rejected_steps [-]": solution.rejected,
        "events [-]": solution.events,
        "wall_time [s]": solution.wall_time,
    }
    if cycle is None:
        cycle = cycle_table(solution)
    angles = cycle["crank_angle [deg]"].to_numpy()
    p = cycle["cylinder_pressure [Pa]"].to_numpy()
    torque = cycle["shaft_torque [N m]"].to_numpy()
    for side in ("suction", "discharge"):
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
    row["mean_shaft_torque [N m]"] = float(shaft / (2.0 * math.pi))
    row["peak_shaft_torque [N m]"] = float(torque.max())
    row["minimum_shaft_torque [N m]"] = float(torque.min())
    return row
