"""Layout of the shell thermal network (:mod:`.shell_network`): its node temperatures
and gas-node pressures, each declared once in a table
(:class:`~recipsim.physics.layout_table.Layout`: name, unit, meaning) that hands out the
index constants.
"""

from __future__ import annotations

from recipsim.physics.layout_table import Layout

#: The node temperatures, in solution order (``node_temperature_<name> [K]`` in the summary).
TEMPERATURES = Layout("thermal network nodes")
_t = TEMPERATURES.add
SM = _t("suction_muffler", "K", "the gas the suction valve draws")
SG = _t("shell_gas", "K", "the gas around the motor that the piston gap draws from")
CW = _t("cylinder_wall", "K", "the wall temperature the heat-transfer correlation sees")
DC = _t("discharge_chamber", "K", "the discharge plenum, source of the discharge back-flow")
DM = _t("discharge_muffler", "K", "muffler and internal line, the gas leaving the compressor")
MO = _t("motor", "K", "the motor, where its losses go")
OIL = _t("oil", "K", "the oil sump, where the friction not on the cylinder wall goes")
SH = _t("shell", "K", "the shell, cooled by the ambient")
N_NODES = TEMPERATURES.size
NODES = tuple(e.name for e in TEMPERATURES.entries)
#: Pressures of the gas nodes (``NetworkPressures.node`` of :mod:`.shell_network`); the
#: node of slot ``GP_*`` is ``GAS_NODES[GP_*]``.
PRESSURES = Layout("thermal network gas-node pressures")
GP_SM = PRESSURES.add("suction_muffler", "Pa", "suction plenum: line pressure - muffler drop")
GP_SG = PRESSURES.add("shell_gas", "Pa", "shell pressure")
GP_DC = PRESSURES.add("discharge_chamber", "Pa", "discharge plenum: line pressure + muffler drop")
GP_DM = PRESSURES.add("discharge_muffler", "Pa", "discharge line pressure")
GAS_NODES = (SM, SG, DC, DM)
