"""The thermal slot (``options.thermal``): where the cylinder's suction gas and wall
temperatures come from.

Choices, declared here beside the models they pick:

- ``fixed_wall``: the suction plenum at the inlet state and the case's wall temperature;
- ``network``: the shell's steady thermal network (:mod:`.shell_network`), solved after
  every cycle, gives the heated suction gas, the wall and the oil temperatures
  (``[thermal]``).

The network couples between cycles (numpy), so no compiled code dispatches on this slot.
A new thermal model: its entry here with the flags the model builder and the solver
read, and its model beside :mod:`.shell_network`.
"""

from __future__ import annotations

from dataclasses import dataclass

from recipsim.slots import ModelChoice, Slot


@dataclass(frozen=True)
class ThermalModel(ModelChoice):
    """A thermal model of the shell.

    Attributes
    ----------
    shell_network : bool
        The shell's thermal network is solved with the cycle: it sets the suction plenum,
        the wall and the oil temperatures, needs a low-side shell (at the suction
        pressure) and the periodic start.
    """

    shell_network: bool = False


FIXED_WALL = ThermalModel(
    name="fixed_wall",
    code=0,
    summary="suction plenum at the inlet state and the given wall temperature",
    source="boundary conditions of the case",
)
SHELL_NETWORK = ThermalModel(
    name="network",
    code=1,
    summary="the shell's steady lumped thermal network ([thermal]), solved after every cycle",
    source="eight-node network of the shell (recipsim.physics.thermo.shell_network)",
    shell_network=True,
)

#: The registry of ``options.thermal``.
THERMAL_MODELS: Slot[ThermalModel] = Slot(
    option="options.thermal",
    doc="suction plenum at the inlet state and the given wall temperature, or the shell's "
    "thermal network ([thermal])",
    choices=(FIXED_WALL, SHELL_NETWORK),
    default=FIXED_WALL.name,
)
