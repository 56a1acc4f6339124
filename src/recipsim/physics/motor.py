"""Single-phase induction motor drive: torque-speed curve from a few datasheet values.

The motor of a hermetic compressor is a two-pole single-phase induction motor whose
rotor is the crankshaft's rotor (its inertia is the rotor body's polar inertia in
``[mechanism.rotor]``). Its steady-state torque follows the double revolving field
picture: the pulsating stator field is a forward field turning at synchronous speed
and a backward one turning against it. Each acts like a polyphase motor with the Kloss
curve ``K(s) = 2 s s_k / (s^2 + s_k^2)`` (peak 1 at the breakdown slip ``s_k``), the
backward field at slip ``2 - s``::

    T(omega) = T_k [K(s) - u K(2 - s)],   s = (omega_s - omega) / omega_s,
    omega_s = 4 pi f / poles.

``u`` is the ratio of backward to forward field strength: 0 for a capacitor motor
balanced at its running point (PSC, the default), up to 1 for a split-phase motor on
its main winding alone (no starting torque). ``s_k`` is fitted so that the curve
passes through the rated point. The torque acts about the rotor axis between housing
and rotor; the speed in the slip is the rotor's spin rate.

Not modelled: the torque pulsation at twice the line frequency (it is not periodic in
crank angle, so the response would not be a periodic steady state), stator losses
(``motor_input_power`` is the air-gap power), electrical transients, start-winding
switching.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit


@dataclass(frozen=True)
class MotorSpec:
    """An induction motor's torque-speed curve (all SI).

    Attributes
    ----------
    line_frequency : float
        Supply frequency [Hz].
    poles : int
        Number of poles (2 for household hermetic compressors).
    rated_speed, rated_torque : float
        A point on the curve [rad/s], [N m] (the nameplate rating).
    breakdown_torque : float
        Peak torque of the forward field [N m].
    backward_field_ratio : float
        Backward to forward field strength [-].
    breakdown_slip : float
        Slip of the forward field's peak torque, fitted to the rated point [-].
    """

    line_frequency: float
    poles: int
    rated_speed: float
    rated_torque: float
    breakdown_torque: float
    backward_field_ratio: float
    breakdown_slip: float

    @property
    def synchronous_speed(self) -> float:
        """Speed of the forward field [rad/s]."""
        return 4.0 * math.pi * self.line_frequency / self.poles

    def torque(self, speed: float) -> float:
        """Motor torque at rotor speed ``speed`` [rad/s] -> [N m]."""
        return float(
            induction_motor_torque(
                speed,
                self.synchronous_speed,
                self.breakdown_torque,
                self.breakdown_slip,
                self.backward_field_ratio,
            )
        )


@njit(cache=True)
def kloss(slip: float, breakdown_slip: float) -> float:
    """Normalised Kloss curve ``2 s s_k / (s^2 + s_k^2)`` (1 at ``s = s_k``)."""
    return 2.0 * slip * breakdown_slip / (slip * slip + breakdown_slip * breakdown_slip)


@njit(cache=True)
def induction_motor_torque(
    speed: float,
    synchronous_speed: float,
    breakdown_torque: float,
    breakdown_slip: float,
    backward_field_ratio: float,
) -> float:
    """Torque of the single-phase induction motor at rotor speed ``speed`` [rad/s].

    Returns
    -------
    float
        ``T_k [K(s) - u K(2 - s)]`` [N m]; positive drives the rotor forward.
    """
    s = (synchronous_speed - speed) / synchronous_speed
    forward = kloss(s, breakdown_slip)
    backward = kloss(2.0 - s, breakdown_slip)
    return breakdown_torque * (forward - backward_field_ratio * backward)
