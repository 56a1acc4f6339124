"""The drive slot (``options.drive``): what turns the crank of the flexible crank train.

Choices, declared here beside the torque they apply (:func:`drive_torque`):

- ``constant_speed``: the spin is prescribed (crank speed constant, zero crank
  acceleration); the torque that holds it follows from the spin equation in
  :mod:`.flexible`;
- ``torque_profile``: a periodic table of torque against crank angle, the crank speed
  free;
- ``induction_motor``: the motor's torque at the rotor's spin rate
  (:func:`recipsim.physics.motor.induction_motor_torque`), the crank speed free.

The compiled code reads the drive's ``code`` from ``par[layout.P_DRIVE]`` (the
``layout.DRIVE_*`` constants). A new drive: declare its :class:`Drive` here with a new
``layout.DRIVE_*`` code, add one ``if code == ...`` branch to :func:`drive_torque`
(numba needs the dispatch written out) and, if it needs parameters, their
``layout.P_*`` rows and its writer in :mod:`recipsim.model.mechanism_parameters`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from recipsim.physics.mechanics import layout as lay
from recipsim.physics.mechanics.tabulated import periodic_linear_interpolation
from recipsim.physics.motor import induction_motor_torque
from recipsim.slots import ModelChoice, Slot


@dataclass(frozen=True)
class Drive(ModelChoice):
    """A drive of the crank.

    Attributes
    ----------
    free_speed : bool
        The crank speed is a state that the drive's torque accelerates (False: the spin
        is prescribed, the rigid crank's only drive).
    torque_table : bool
        It applies the tabulated torque against crank angle (the model builder makes the
        table from the rigid crank's cycle or the pressure curve).
    motor_curve : bool
        It applies the ``[motor]`` torque-speed curve: the steady speed is the motor's
        own (an unknown of the periodic solve), and it can start the crank from rest.
    """

    free_speed: bool = False
    torque_table: bool = False
    motor_curve: bool = False


CONSTANT_SPEED = Drive(
    name="constant_speed",
    code=lay.DRIVE_CONSTANT_SPEED,
    summary="the crank turns at operating_point.shaft_speed; the torque that holds it is an output",
    source="prescribed spin of the rotor's Newton-Euler equations",
)
TORQUE_PROFILE = Drive(
    name="torque_profile",
    code=lay.DRIVE_TORQUE_PROFILE,
    summary="a periodic torque against crank angle (the rigid crank's, or the tabulated "
    "pressure's), the crank speed free",
    source="Kurka, Paulino & Izuka (ISMA 2010)",
    free_speed=True,
    torque_table=True,
)
INDUCTION_MOTOR = Drive(
    name="induction_motor",
    code=lay.DRIVE_INDUCTION_MOTOR,
    summary="the single-phase induction motor's torque-speed curve ([motor]), the crank speed free",
    source="double revolving field with Kloss curves (recipsim.physics.motor)",
    free_speed=True,
    motor_curve=True,
)

#: The registry of ``options.drive``.
DRIVES: Slot[Drive] = Slot(
    option="options.drive",
    doc="what turns the crank; the speed is a result for the last two (flexible mechanics only)",
    choices=(CONSTANT_SPEED, TORQUE_PROFILE, INDUCTION_MOTOR),
    default=CONSTANT_SPEED.name,
)


@njit(cache=True)
def drive_torque(
    code: int,
    crank_angle: float,
    spin: float,
    par: np.ndarray,
    drive_angles: np.ndarray,
    drive_torques: np.ndarray,
) -> float:
    """The torque a free drive applies about the rotor axis [N m] (0 for the prescribed
    spin, whose torque follows from the spin equation).

    Parameters
    ----------
    code : int
        The drive's code (``par[layout.P_DRIVE]``).
    crank_angle : float
        Crank angle [rad].
    spin : float
        The rotor's spin rate [rad/s].
    par : numpy.ndarray
        The mechanism's parameter array (:mod:`.layout`).
    drive_angles, drive_torques : numpy.ndarray
        The torque table [rad], [N m] (read by ``torque_profile``).
    """
    if code == lay.DRIVE_INDUCTION_MOTOR:
        return induction_motor_torque(
            spin,
            par[lay.P_MOTOR_SYNC_SPEED],
            par[lay.P_MOTOR_BREAKDOWN_TORQUE],
            par[lay.P_MOTOR_BREAKDOWN_SLIP],
            par[lay.P_MOTOR_BACKWARD_RATIO],
        )
    if code == lay.DRIVE_TORQUE_PROFILE:
        return periodic_linear_interpolation(crank_angle, drive_angles, drive_torques)
    return 0.0
