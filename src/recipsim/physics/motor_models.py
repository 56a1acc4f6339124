"""The motor slot (``options.motor``): the motor's losses and the electrical power.

Choices, declared here beside the models they pick:

- ``lossless``: the electrical input is the shaft power (efficiency 1, no losses);
- ``equivalent_circuit``: the single-phase induction motor's equivalent circuit
  (:mod:`.motor_circuit`) at the cycle's mean load torque gives the losses, the input
  power and the speed at load; it reads the circuit's keys of ``[motor]``.

The motor is evaluated after the cycle (numpy, never in the compiled loop), so no
compiled code dispatches on this slot. A new motor model: its entry here with the flags
the case reader and the results read, and its evaluation beside
:mod:`.motor_circuit`.
"""

from __future__ import annotations

from dataclasses import dataclass

from recipsim.slots import ModelChoice, Slot


@dataclass(frozen=True)
class MotorModel(ModelChoice):
    """A motor-loss model.

    Attributes
    ----------
    circuit : bool
        It reads the equivalent circuit of ``[motor]`` and its losses enter the
        electrical power and the shell's motor node (False: electrical = shaft power).
    """

    circuit: bool = False


LOSSLESS = MotorModel(
    name="lossless",
    code=0,
    summary="electrical input = shaft power, no motor losses",
    source="ideal motor (the indicated and shaft figures alone)",
)
EQUIVALENT_CIRCUIT = MotorModel(
    name="equivalent_circuit",
    code=1,
    summary="single-phase induction motor's double-revolving-field equivalent circuit "
    "([motor]): losses, electrical power, speed at load",
    source="Veinott; Fitzgerald & Kingsley, Electric Machinery",
    circuit=True,
)

#: The registry of ``options.motor``.
MOTOR_MODELS: Slot[MotorModel] = Slot(
    option="options.motor",
    doc="motor losses and electrical power",
    choices=(LOSSLESS, EQUIVALENT_CIRCUIT),
    default=LOSSLESS.name,
)
