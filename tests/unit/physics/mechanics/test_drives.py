"""The drive slot's compiled torque and its registry: each drive applies the torque its
law gives, and the case's drive name reaches the compiled code as the code it
dispatches on."""

from __future__ import annotations

import math

import numpy as np
import pytest

from recipsim.physics.mechanics import layout as lay
from recipsim.physics.mechanics.drives import DRIVES, drive_torque
from recipsim.physics.motor import induction_motor_torque


def _motor_par(sync: float, peak: float, slip_k: float, backward: float) -> np.ndarray:
    par = np.zeros(lay.N_PAR)
    par[lay.P_MOTOR_SYNC_SPEED] = sync
    par[lay.P_MOTOR_BREAKDOWN_TORQUE] = peak
    par[lay.P_MOTOR_BREAKDOWN_SLIP] = slip_k
    par[lay.P_MOTOR_BACKWARD_RATIO] = backward
    return par


def test_induction_motor_drive_applies_the_kloss_curve() -> None:
    """At the breakdown slip of a balanced motor (no backward field) the torque is the
    breakdown torque (Kloss K(s_k) = 1), and it is the motor law's at any speed."""
    sync, peak, slip_k = 2.0 * math.pi * 60.0, 12.0, 0.2
    code = DRIVES.code("induction_motor")
    par = _motor_par(sync, peak, slip_k, 0.0)
    empty = np.zeros(1)
    at_peak = drive_torque(code, 0.3, sync * (1.0 - slip_k), par, empty, empty)
    assert at_peak == pytest.approx(peak, rel=1e-12)  # closed form, rounding only
    par = _motor_par(sync, peak, slip_k, 0.4)
    for speed in (0.0, 0.5 * sync, 0.97 * sync):
        expected = induction_motor_torque(speed, sync, peak, slip_k, 0.4)
        assert drive_torque(code, 1.0, speed, par, empty, empty) == expected


def test_torque_profile_interpolates_its_table_periodically() -> None:
    """Between two table points the torque is their linear interpolation, and the table
    wraps at a full turn."""
    code = DRIVES.code("torque_profile")
    angles = np.array([0.0, math.pi / 2, math.pi, 3 * math.pi / 2])
    torques = np.array([1.0, 3.0, -1.0, 5.0])
    par = np.zeros(lay.N_PAR)
    assert drive_torque(code, math.pi / 4, 100.0, par, angles, torques) == pytest.approx(2.0)
    wrapped = drive_torque(code, 2 * math.pi + math.pi / 4, 100.0, par, angles, torques)
    assert wrapped == pytest.approx(2.0)


def test_prescribed_spin_applies_no_drive_torque() -> None:
    """The constant-speed drive's torque follows from the spin equation, not from here."""
    code = DRIVES.code("constant_speed")
    par = _motor_par(377.0, 12.0, 0.2, 0.0)
    assert drive_torque(code, 0.1, 300.0, par, np.ones(2), np.ones(2)) == 0.0
    assert not DRIVES["constant_speed"].free_speed


def test_unknown_drive_is_named_with_the_closest_choice() -> None:
    with pytest.raises(KeyError, match="did you mean 'induction_motor'"):
        DRIVES["induction_moter"]
