"""The entry type of the valve models' slot (``options.valves``): what a valve model
declares besides its name and code (:mod:`recipsim.physics.thermo.valve_models` is the
registry)."""

from __future__ import annotations

from dataclasses import dataclass

from recipsim.slots import ModelChoice


@dataclass(frozen=True)
class ValveModel(ModelChoice):
    """A valve model (see :class:`~recipsim.slots.ModelChoice` for the common fields).

    Attributes
    ----------
    moves_reeds : bool
        Its reeds have lift and velocity states, seat and stop events (the reed
        dynamics of ``cylinder_rhs``); the periodic solver's unknowns include a free
        reed's states.
    uses_valve_data : bool
        It reads the ``[valves.suction]`` and ``[valves.discharge]`` reed tables (the
        ideal valves do not: the case may leave them out).
    event_functions : tuple of int
        The cylinder's event functions that can fire with it (the others stay -1).
    fidelity : int
        Rank from the cheapest model up (the bench ladder's cheaper-valve rungs).
    """

    moves_reeds: bool = False
    uses_valve_data: bool = True
    event_functions: tuple[int, ...] = ()
    fidelity: int = 0
