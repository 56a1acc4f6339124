"""Summary metrics of a converged cycle (the cycle table itself: :mod:`.cycle`, whose
names this module re-exports).

Every key carries its unit (``cooling_capacity [W]``); the meaning of each is declared
in :mod:`.summary_docs` (``reports/README.md``'s tables are generated from it). The
summary reads the cycle table as numpy columns (:data:`~recipsim.results.sampled.CycleColumns`).

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
from recipsim.model.build import scenes
from recipsim.model.loss_sources import friction_oil_temperature
from recipsim.model.plenum import isentropic_state
from recipsim.physics.mechanics.drives import DRIVES
from recipsim.results.bearings import film_laws, film_summary, mechanism_summary
from recipsim.results.cycle import (  # re-exported (__all__): the cycle table is in .cycle
    CYCLE_COLUMNS,
    GAS_COLUMNS,
    cycle_columns,
    cycle_table,
    pinned_tabulated_columns,
    pinned_tabulated_cycle,
)
from recipsim.results.cycle_metrics import pressure_and_torque, valve_timing
from recipsim.results.electrical import loss_columns, rating_enthalpies
from recipsim.results.loss_breakdown import loss_breakdown
from recipsim.results.outcome import (
    discharge_valve_never_opens,
    property_error,
    state_or_explain,
)
from recipsim.results.sampled import CycleColumns
from recipsim.results.thermal import thermal_columns
from recipsim.results.valve_metrics import valve_summary
from recipsim.solve.periodic import PeriodicSolution
from recipsim.solve.residual import closures

__all__ = [
    "CYCLE_COLUMNS",
    "GAS_COLUMNS",
    "GAS_SUMMARY",
    "cycle_columns",
    "cycle_table",
    "pinned_tabulated_columns",
    "pinned_tabulated_cycle",
    "summary",
    "summary_row",
]


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
    end = scenes.named_state(model.scene, y)
    m_suc = end.suction_mass_in - end.suction_mass_out
    m_dis = end.discharge_mass_out - end.discharge_mass_in
    m_leak = end.leakage_mass_out - end.leakage_mass_in
    work = end.work_on_gas
    heat_in = end.heat_to_gas
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
        h_mix = end.discharge_enthalpy_out / end.discharge_mass_out
        what = "the discharge temperature (mass-weighted discharge enthalpy)"
        discharge = state_or_explain(fluid, "ph", op.discharge_pressure, h_mix, what, False)
        t_dis = discharge["T"]
    else:
        t_dis = math.nan
    return {
        "suction_mass_flow [kg/s]": m_suc * freq,
        "discharge_mass_flow [kg/s]": mdot_dis,
        "leakage_mass_flow [kg/s]": m_leak * freq,
        "suction_backflow_mass_flow [kg/s]": end.suction_mass_out * freq,
        "discharge_backflow_mass_flow [kg/s]": end.discharge_mass_in * freq,
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


def _loop_work(cycle: CycleColumns) -> float:
    """-closed integral of p dV over the cycle table [J] (trapezoid, periodic)."""
    p = cycle["cylinder_pressure [Pa]"]
    v = cycle["cylinder_volume [m3]"]
    dv = np.roll(v, -1) - v
    return float(-np.sum(0.5 * (p + np.roll(p, -1)) * dv))


def summary_row(solution: PeriodicSolution) -> tuple[dict[str, Any], CycleColumns]:
    """:func:`summary` of ``solution`` read from only the cycle table's columns that it
    needs (:func:`cycle_columns` with ``full=False``: the same values); returns the row
    and those columns."""
    cycle = cycle_columns(solution, full=False)
    return summary(solution, cycle), cycle


def summary(
    solution: PeriodicSolution | None,
    cycle: CycleColumns | pd.DataFrame | None = None,
    case: Case | None = None,
) -> dict[str, Any]:
    """Summary metrics of the converged revolution (units in the keys).

    ``cycle`` is its cycle table, or the table's columns (built here from the columns it
    reads if left out). ``solution`` is None for the pinned mechanism under a tabulated
    pressure (nothing integrated); ``cycle`` and ``case`` are then required.
    """
    if isinstance(cycle, pd.DataFrame):
        cycle = {name: cycle[name].to_numpy() for name in cycle.columns}
    if solution is not None:
        case = solution.model.case
        if cycle is None:
            cycle = cycle_columns(solution, full=False)
    assert case is not None and cycle is not None
    row = _operating_columns(case)
    model = solution.model if solution is not None else None
    # the pinned mechanism (a rigid crank, or the tabulated pressure's): no orbits
    mech = mechanism_summary(cycle, model is None or model.scene == scenes.SCENE_CYLINDER)
    # one revolution's frequency: the mean crank speed when the speed is free
    drive_work, bearing_loss, freq = _drive_work(
        solution, cycle, mech["mean_crank_speed [rpm]"] / 60.0
    )
    p_drive = drive_work * freq
    motor = _motor_metrics(case, cycle, freq, p_drive)
    rotor_loss = motor["motor_rotor_loss_power [W]"]
    oil = friction_oil_temperature(model)
    losses = loss_columns(case, cycle, p_drive, freq, oil, rotor_loss)
    p_shaft = losses.pop("shaft_power [W]")
    row.update(_gas_summary(solution, cycle, freq, p_shaft, losses["motor_electrical_power [W]"]))
    row.update(valve_summary(case.name, solution))
    row["shaft_power [W]"] = p_shaft
    row["bearing_dissipation_power [W]"] = bearing_loss * freq
    row.update(motor)
    row.update(losses)
    row["motor_slip [-]"] = _slip_at_load(case, row["motor_slip [-]"], row)
    row.update(mech)
    flexible = model if model is not None and model.scene != scenes.SCENE_CYLINDER else None
    # the flexible crank's bearings on oil films: their laws' summary columns
    row.update(film_summary(cycle, {} if flexible is None else film_laws(flexible.mechanism_par)))
    if flexible is not None:
        row["mechanical_efficiency [-]"] = _ratio(row["indicated_power [W]"], p_shaft)
        # drive power = indicated power + friction and bearing losses, over the revolution
        row["mechanical_balance_residual [-]"] = _ratio(
            p_drive - row["indicated_power [W]"] - bearing_loss * freq, p_drive
        )
    row.update(_solver_metrics(solution))
    row.update(thermal_columns(solution, case))
    row.update(loss_breakdown(row, cycle, solution))
    row.update(valve_timing(solution, case, cycle))
    row.update(pressure_and_torque(case, cycle, drive_work, p_shaft, p_drive, freq))
    return row


def _drive_work(
    solution: PeriodicSolution | None, cycle: CycleColumns, freq: float
) -> tuple[float, float, float]:
    """Work of the drive and of the bearings over the revolution, and its frequency.

    Parameters
    ----------
    solution : PeriodicSolution or None
        As in :func:`summary` (None: the pinned mechanism under a tabulated pressure).
    cycle : CycleColumns
        The cycle table (its shaft torque is read when ``solution`` is None).
    freq : float
        Revolutions per second from the mean crank speed [1/s].

    Returns
    -------
    drive_work, bearing_loss : float
        Work of the drive and work dissipated in the bearings per revolution [J].
    freq : float
        Revolutions per second: ``freq``, or one over the revolution's duration when the
        speed is free.
    """
    model = solution.model if solution is not None else None
    if model is not None and model.scene != scenes.SCENE_CYLINDER:
        end = scenes.named_state(model.scene, solution.final.y_end)  # type: ignore[union-attr]
        drive_work, bearing_loss = end.drive_work, end.bearing_dissipation
        freq = 1.0 / solution.final.duration if model.free_speed else freq  # type: ignore[union-attr]
    elif model is not None:
        drive_work = scenes.named_state(model.scene, solution.final.y_end).shaft_work  # type: ignore[union-attr]
        bearing_loss = 0.0
    else:
        torque = cycle["shaft_torque [N m]"]
        drive_work = float(np.mean(torque)) * 2.0 * math.pi
        bearing_loss = 0.0
    return drive_work, bearing_loss, freq


def _gas_summary(
    solution: PeriodicSolution | None,
    cycle: CycleColumns,
    freq: float,
    p_shaft: float,
    p_electrical: float,
) -> dict[str, Any]:
    """The :data:`GAS_SUMMARY` columns; without a gas state, only the indicated power.

    Parameters
    ----------
    solution : PeriodicSolution or None
        As in :func:`summary`.
    cycle : CycleColumns
        The cycle table (its p-V loop gives the indicated power when ``solution`` is
        None).
    freq : float
        Revolutions per second [1/s].
    p_shaft, p_electrical : float
        Shaft power and motor electrical power [W].

    Returns
    -------
    dict
        Column name to value, in :data:`GAS_SUMMARY`'s order.
    """
    model = solution.model if solution is not None else None
    if model is not None and model.has_gas:
        return _gas_metrics(solution, freq, p_shaft, p_electrical)  # type: ignore[arg-type]
    gas = dict.fromkeys(GAS_SUMMARY, math.nan)
    if model is not None:  # work of the gas on the piston, integrated with the motion
        end = scenes.named_state(model.scene, solution.final.y_end)  # type: ignore[union-attr]
        gas["indicated_power [W]"] = -end.gas_work_on_piston * freq
    else:
        gas["indicated_power [W]"] = _loop_work(cycle) * freq
    return gas


MOTOR_SUMMARY = ("motor_input_power [W]", "motor_rotor_loss_power [W]", "motor_slip [-]")


def _motor_metrics(case: Case, cycle: CycleColumns, freq: float, p_shaft: float) -> dict[str, Any]:
    """Air-gap power, rotor copper loss and slip of the induction motor drive (NaN for
    other drives). The air-gap power ``omega_s * mean(T)`` (time mean) is the motor's
    input less its stator losses, which are not modelled."""
    if not DRIVES[case.options.drive].motor_curve or case.motor is None:
        return dict.fromkeys(MOTOR_SUMMARY, math.nan)
    sync = case.motor.synchronous_speed
    torque = cycle["shaft_torque [N m]"]
    speed = cycle["crank_speed [rad/s]"]
    # time mean of T over one revolution from uniform crank-angle samples: dt = dtheta/omega
    mean_torque = float(np.mean(torque / speed)) * 2.0 * math.pi * freq
    p_in = sync * mean_torque
    return {
        "motor_input_power [W]": p_in,
        "motor_rotor_loss_power [W]": p_in - p_shaft,
        "motor_slip [-]": 1.0 - 2.0 * math.pi * freq / sync,
    }


def _slip_at_load(case: Case, drive_slip: float, row: dict[str, Any]) -> float:
    """The motor's slip: the induction-motor drive's (``drive_slip``), else the equivalent
    circuit's at the cycle's load, ``1 - motor_speed_at_load / synchronous speed`` (NaN
    without a circuit)."""
    at_load = row.get("motor_speed_at_load [rpm]", math.nan)
    if not math.isnan(drive_slip) or case.motor_circuit is None or math.isnan(at_load):
        return drive_slip
    return 1.0 - at_load * math.pi / 30.0 / case.motor_circuit.synchronous_speed


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
