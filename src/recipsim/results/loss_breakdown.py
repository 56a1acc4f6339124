"""Where the electrical power goes: the loss chain from the socket to the isentropic
power of the delivered gas.

Summary columns, all time means [W]:

==================================  ================================================
``loss_motor [W]``                  motor losses, electrical - shaft power
``loss_mechanical [W]``             shaft - indicated power: journal and piston
                                    friction, bearing damping
``loss_suction_valve [W]``          p-V area of the suction stroke below the suction
                                    plenum pressure, while the suction valve passes gas
``loss_discharge_valve [W]``        p-V area above the discharge plenum pressure while
                                    the discharge valve passes gas
``loss_mufflers [W]``               flow work of the mufflers' pressure drops,
                                    ``m (dp_s / rho_s + dp_d / rho_d)``
``loss_leakage [W]``                the leaked mass's isentropic work,
                                    ``m_leak dh_s``
``loss_suction_heating [W]``        the delivered gas's extra isentropic work for being
                                    drawn at the cylinder-inlet temperature instead of
                                    the compressor inlet's
``loss_cylinder_heat_and_other [W]`` what the named terms leave of indicated -
                                    isentropic power: heat exchanged in the cylinder,
                                    re-expansion, the valves' dynamics
``isentropic_power [W]``            the delivered gas from the compressor inlet to the
                                    discharge pressure (already in the summary)
==================================  ================================================

They add up to ``motor_electrical_power [W]`` by construction (the last loss is the
remainder); the test of the decomposition is that the remainder vanishes where it must
(ideal valves, adiabatic cylinder, no leakage: the ideal isentropic cycle) and that each
named term matches its own definition.

The suction side also costs capacity, which the power terms do not show: gas drawn
hotter or at a lower pressure is less dense, so the same swept volume delivers less.
Capacity losses [W] (at the rating enthalpies of the cooling capacity ``Q``):

- ``capacity_loss_suction_heating [W]``: ``Q (rho(p_in, T_in) / rho(p_in, T_cyl) - 1)``,
  the capacity the cylinder would deliver if it drew gas at the compressor inlet's
  temperature instead of the cylinder inlet's, at the same volumetric efficiency;
- ``capacity_loss_mufflers [W]``: the same for the suction muffler's pressure drop,
  ``Q_heated (rho(p_in, T_cyl) / rho(p_plenum, T_cyl) - 1)``;
- ``capacity_loss_leakage [W]``: the leaked mass flow at the capacity's enthalpy
  difference.

``cop_<loss> [-]`` is what each loss costs in COP: the COP gained by removing that loss
alone, ``(Q + dQ) / (W - L) - Q / W`` with ``W`` the electrical power, ``L`` the power
term and ``dQ`` the capacity loss (0 for the losses that cost power only). The costs do
not add up exactly to the ideal machine's COP (they are taken one at a time).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from recipsim.model.plenum import isentropic_state
from recipsim.model.scenes import named_state
from recipsim.results.sampled import CycleColumns

if TYPE_CHECKING:  # a type only: reading LOSS_COLUMNS does not import the solver
    from recipsim.solve.periodic import PeriodicSolution

#: Breakdown columns, from the socket down (``isentropic_power [W]`` closes the chain).
LOSS_COLUMNS = (
    "loss_motor [W]",
    "loss_mechanical [W]",
    "loss_suction_valve [W]",
    "loss_discharge_valve [W]",
    "loss_mufflers [W]",
    "loss_leakage [W]",
    "loss_suction_heating [W]",
    "loss_cylinder_heat_and_other [W]",
)


#: Capacity each suction-side loss costs [W].
CAPACITY_LOSS_COLUMNS = {
    "loss_suction_heating [W]": "capacity_loss_suction_heating [W]",
    "loss_mufflers [W]": "capacity_loss_mufflers [W]",
    "loss_leakage [W]": "capacity_loss_leakage [W]",
}
#: COP each loss costs, removed alone [-].
COP_COST_COLUMNS = {c: f"cop_{c.removesuffix(' [W]')} [-]" for c in LOSS_COLUMNS}

_SIDES = ("suction", "discharge")


def _next(a: np.ndarray) -> np.ndarray:
    """``a`` one sample on round the revolution, along its last axis
    (``numpy.roll(a, -1, axis=-1)``)."""
    return np.concatenate((a[..., 1:], a[..., :1]), axis=-1)


def _valve_areas(cycle: CycleColumns, p_suction: float, p_discharge: float) -> tuple[float, float]:
    """p-V areas of one revolution [J]: below ``p_suction`` while the suction valve
    flows, above ``p_discharge`` while the discharge valve flows (trapezoids)."""
    p = cycle["cylinder_pressure [Pa]"]
    v = cycle["cylinder_volume [m3]"]
    dv = _next(v) - v
    p_mid = 0.5 * (p + _next(p))
    # one row per valve: suction (p_s - p) dV with dV > 0; discharge (p - p_d)(-dV), the
    # same form; each row summed as the 1-D array would be
    flows = np.stack([cycle[f"{side}_mass_flow [kg/s]"] for side in _SIDES])
    passing = flows != 0.0
    flowing = passing | _next(passing)
    plenum = np.array([[p_suction], [p_discharge]])
    suction, discharge = np.sum(np.where(flowing, (plenum - p_mid) * dv, 0.0), axis=1).tolist()
    return suction, discharge


def loss_breakdown(
    row: dict[str, Any], cycle: CycleColumns, solution: PeriodicSolution | None
) -> dict[str, float]:
    """The breakdown columns (NaN where the scene has no gas model).

    Parameters
    ----------
    row : dict
        The summary row so far (powers, mass flows, plenum pressures, motor columns).
    cycle : DataFrame
        The cycle table.
    solution : PeriodicSolution or None
        The periodic solution (its model's fluid and plenum states).
    """
    model = None if solution is None else solution.model
    if model is None or not model.has_gas:
        names = (*LOSS_COLUMNS, *CAPACITY_LOSS_COLUMNS.values(), *COP_COST_COLUMNS.values())
        return dict.fromkeys(names, math.nan)
    op = model.case.operating_point
    freq = row["mean_crank_speed [rpm]"] / 60.0
    if model.free_speed:
        freq = 1.0 / solution.final.duration  # type: ignore[union-attr]
    fluid, inlet = model.fluid, model.compressor_inlet
    p_s = row.get("suction_plenum_pressure [Pa]", op.suction_pressure)
    p_d = row.get("discharge_plenum_pressure [Pa]", op.discharge_pressure)
    suction_area, discharge_area = _valve_areas(cycle, p_s, p_d)
    mdot = row["discharge_mass_flow [kg/s]"]
    h_2s = isentropic_state(fluid, inlet, op.discharge_pressure)["h"]
    dh_s_line = h_2s - inlet.enthalpy
    t_in = row.get("cylinder_inlet_temperature [K]", inlet.temperature)
    rho_cyl = inlet.density  # the gas the cylinder draws, at the line pressure
    if abs(t_in - inlet.temperature) > 1e-9:
        heated = fluid.state_pt(op.suction_pressure, t_in)
        dh_s_heated = fluid.state_ps(op.discharge_pressure, heated["s"])["h"] - heated["h"]
        rho_cyl = heated["rho"]
    else:
        dh_s_heated = dh_s_line

    end = named_state(model.scene, solution.final.y_end)  # type: ignore[union-attr]
    suction_flow = (end.suction_mass_in - end.suction_mass_out) * freq
    mufflers = suction_flow * (op.suction_pressure - p_s) / inlet.density
    mufflers += mdot * (p_d - op.discharge_pressure) / model.discharge.density
    out = {
        "loss_motor [W]": row["motor_electrical_power [W]"] - row["shaft_power [W]"],
        "loss_mechanical [W]": row["shaft_power [W]"] - row["indicated_power [W]"],
        "loss_suction_valve [W]": suction_area * freq,
        "loss_discharge_valve [W]": discharge_area * freq,
        "loss_mufflers [W]": mufflers,
        "loss_leakage [W]": row["leakage_mass_flow [kg/s]"] * dh_s_line,
        "loss_suction_heating [W]": mdot * (dh_s_heated - dh_s_line),
    }
    named = sum(out[k] for k in LOSS_COLUMNS[2:-1])
    out["loss_cylinder_heat_and_other [W]"] = (
        row["indicated_power [W]"] - row["isentropic_power [W]"] - named
    )
    out.update(_capacity_losses(row, inlet.density, rho_cyl, model.suction.density, mdot))
    out.update(_cop_costs(row, out))
    return out


def _capacity_losses(
    row: dict[str, Any], rho_inlet: float, rho_cylinder: float, rho_plenum: float, mdot: float
) -> dict[str, float]:
    """Capacity lost to suction heating, the suction muffler and leakage [W] (module
    notes); densities [kg/m3] of the gas at the compressor inlet, at the cylinder inlet's
    temperature and the line pressure, and in the suction plenum."""
    capacity = row["cooling_capacity [W]"]
    per_kg = capacity / mdot if mdot > 0.0 else math.nan
    heated_line = capacity * rho_cylinder / rho_plenum  # without the muffler's drop
    return {
        "capacity_loss_suction_heating [W]": heated_line * (rho_inlet / rho_cylinder - 1.0),
        "capacity_loss_mufflers [W]": heated_line - capacity,
        "capacity_loss_leakage [W]": row["leakage_mass_flow [kg/s]"] * per_kg,
    }


def _cop_costs(row: dict[str, Any], losses: dict[str, float]) -> dict[str, float]:
    """COP each loss costs, removed alone (module notes) [-]."""
    capacity = row["cooling_capacity [W]"]
    power = row["motor_electrical_power [W]"]
    cop = capacity / power
    out = {}
    for column, cost in COP_COST_COLUMNS.items():
        gained = losses.get(CAPACITY_LOSS_COLUMNS.get(column, ""), 0.0)
        out[cost] = (capacity + gained) / (power - losses[column]) - cop
    return out
