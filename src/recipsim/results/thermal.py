"""Summary columns of the shell thermal network (``options.thermal = "network"``).

The network reported is the one solved from the converged revolution's flows (the
boundary the next revolution would get; at convergence it differs from the one that
revolution ran with by less than the cycle tolerance). Its node balances are checked,
term by term and independently of the Newton solve, against that revolution's own flows
(not the cycle-response-moved ones the solve used), so ``thermal_balance_residual``
measures both the solve and how well cycle and network agree.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from recipsim.model.scenes import named_state
from recipsim.physics.thermo.shell_network import node_residuals
from recipsim.physics.thermo.shell_nodes import NODES, PRESSURES, TEMPERATURES

if TYPE_CHECKING:
    from recipsim.case.case import Case
    from recipsim.solve.periodic import PeriodicSolution

#: Columns of :func:`thermal_columns` (units in the names).
THERMAL_SUMMARY = (
    "thermal",
    "shell_heat_rejection [W]",
    "cylinder_inlet_temperature [K]",
    "suction_plenum_pressure [Pa]",
    "discharge_plenum_pressure [Pa]",
    *(f"node_temperature_{node} [K]" for node in NODES),
    "thermal_balance_residual [-]",
    "thermal_energy_balance_residual [-]",
    "discharge_line_temperature [K]",
)


def thermal_columns(solution: PeriodicSolution | None, case: Case) -> dict[str, Any]:
    """The thermal network's columns of the summary.

    ``fixed_wall`` (or nothing integrated): the cylinder inlet is the operating point's
    suction state and the plenum pressures are the line pressures; the network columns
    are NaN.

    ``thermal_energy_balance_residual`` is the whole compressor's closure: (indicated
    power + friction + motor loss - delivered flow x (h_outlet - h_inlet) - shell heat)
    / (indicated power + friction + motor loss).
    """
    op = case.operating_point
    row: dict[str, Any] = dict.fromkeys(THERMAL_SUMMARY, math.nan)
    row["thermal"] = case.options.thermal
    row["cylinder_inlet_temperature [K]"] = op.suction_temperature
    row["suction_plenum_pressure [Pa]"] = op.suction_pressure
    row["discharge_plenum_pressure [Pa]"] = op.discharge_pressure
    model = None if solution is None else solution.model
    coupling = None if model is None else model.thermal
    if coupling is None or coupling.applied is None or coupling.last_loads is None:
        return row
    if coupling.last_loads.delivered_mass_flow <= 0.0:  # nothing delivered: no network
        return row
    assert solution is not None
    used = coupling.applied
    loads = coupling.last_loads
    net = used.solution
    t = net.temperature
    for i, node in enumerate(NODES):
        row[f"node_temperature_{node} [K]"] = float(t[i])
    nodes = TEMPERATURES.bundle(np.asarray(t))
    pressures = PRESSURES.bundle(np.asarray(used.pressures.node))
    end = named_state(solution.model.scene, solution.final.y_end)
    p_in = end.work_on_gas / solution.final.duration + loads.friction_power + loads.motor_loss_power
    q_shell = net.shell_heat_rejection
    rise = loads.delivered_mass_flow * (net.outlet_enthalpy - net.inlet_enthalpy)
    outlet = solution.model.fluid.state_ph(op.discharge_pressure, net.outlet_enthalpy)
    row.update(
        {
            "shell_heat_rejection [W]": q_shell,
            "cylinder_inlet_temperature [K]": float(nodes.suction_muffler),
            "suction_plenum_pressure [Pa]": pressures.suction_muffler,
            "discharge_plenum_pressure [Pa]": pressures.discharge_chamber,
            "thermal_balance_residual [-]": float(
                np.max(node_residuals(used.parameters, loads, net))
            ),
            "thermal_energy_balance_residual [-]": (p_in - rise - q_shell) / p_in,
            "discharge_line_temperature [K]": float(outlet["T"]),
        }
    )
    return row
