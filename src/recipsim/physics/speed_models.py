"""The speed slot (``options.speed``): the crank speed of the constant-speed cycle.

Choices, declared here:

- ``case``: ``operating_point.shaft_speed``;
- ``motor_slip``: the speed at which the equivalent circuit
  (:mod:`.motor_circuit`) carries the cycle's mean load torque, a fixed point solved by
  :mod:`recipsim.solve.motor_speed`; it needs the ``constant_speed`` drive and the
  ``equivalent_circuit`` motor.

The speed is set before the compiled loop, so no compiled code dispatches on this slot.
A new speed rule: its entry here with the flags the pipeline reads, and its solve beside
:mod:`recipsim.solve.motor_speed`.
"""

from __future__ import annotations

from dataclasses import dataclass

from recipsim.slots import ModelChoice, Slot


@dataclass(frozen=True)
class SpeedModel(ModelChoice):
    """A rule for the crank speed.

    Attributes
    ----------
    at_motor_load : bool
        The speed is the motor circuit's at the cycle's load (solved for); False: the
        case's ``operating_point.shaft_speed``.
    """

    at_motor_load: bool = False


CASE_SPEED = SpeedModel(
    name="case",
    code=0,
    summary="operating_point.shaft_speed",
    source="the case",
)
MOTOR_SLIP = SpeedModel(
    name="motor_slip",
    code=1,
    summary="the equivalent circuit's speed at the cycle's load torque (constant speed, "
    "equivalent_circuit motor)",
    source="fixed point of the cycle's load and the circuit's torque-speed curve",
    at_motor_load=True,
)

#: The registry of ``options.speed``.
SPEED_MODELS: Slot[SpeedModel] = Slot(
    option="options.speed",
    doc="crank speed: operating_point.shaft_speed, or the speed at which the equivalent "
    "circuit carries the cycle's load torque (constant speed, equivalent_circuit motor)",
    choices=(CASE_SPEED, MOTOR_SLIP),
    default=CASE_SPEED.name,
)
