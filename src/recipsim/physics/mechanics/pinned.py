"""Pinned (rigid) mechanism: slider-crank inverse dynamics.

All bearings are rigid; the crank turns about the fixed Z axis at speed ``omega``
(and, optionally, angular acceleration). The kinematics is exact
(:mod:`recipsim.physics.kinematics`); every reaction follows from Newton-Euler body by body:

- piston (translation along X only): the pin's X force from Newton along X; its
  side force is shared between ``piston_top`` and ``piston_skirt`` by moment balance
  (no tilt, so the moments about the centre of mass cancel);
- rod (planar): the pin's side force from the rod's moment balance, the eccentric
  force from its force balance;
- rotor (fixed axis, balanced): the two radial bearings share the eccentric load by
  moment balance about X and Y (the eccentric is at z = 0), and the driving torque is
  the moment of the eccentric force about Z plus ``I_polar * crank_acceleration``.

Forces are reported on the journal-side body (rotor for primary, secondary and
eccentric; piston for pin, piston_top and piston_skirt), inertial X, Y, Z [N]. There
is no gravity, so all Z components are zero.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from recipsim.physics.kinematics import piston_displacement, rod_angle, rod_centre_of_mass
from recipsim.physics.layout_table import Layout
from recipsim.physics.mechanics import layout as lay

#: Output row of :func:`pinned_reactions`: bearing i's force component k at
#: ``PIN_BEARING_FORCE + 3 * i + k`` (as the mechanism's aux), then torque, force, pose.
OUTPUTS = Layout("pinned mechanism outputs")
_a = OUTPUTS.add
PIN_BEARING_FORCE = OUTPUTS.add_series(
    "bearing_force_{}",
    tuple(f"{b}_{ax}" for b in lay.BEARING_NAMES for ax in "xyz"),
    "N",
    "force on the journal-side body, inertial X, Y, Z (as the flexible mechanism's)",
)
PIN_DRIVE_TORQUE = _a("drive_torque", "N m", "driving torque about the rotor axis")
PIN_GAS_TORQUE = _a("gas_torque", "N m", "(p - p_shell) A dx/dtheta")
PIN_GAS_FORCE = _a("gas_force", "N", "-(p - p_shell) A, along X on the piston")
PIN_PISTON_DISPLACEMENT = _a("piston_displacement", "m", "piston displacement from TDC")
N_PIN_OUT = OUTPUTS.size


@njit(cache=True)
def pinned_reactions(
    theta: float,
    omega: float,
    crank_acceleration: float,
    gas_pressure: float,
    par: np.ndarray,
    out: np.ndarray,
) -> None:
    """Bearing reactions and driving torque of the rigid mechanism at one crank angle.

    Parameters
    ----------
    theta : float
        Crank angle from TDC [rad].
    omega : float
        Crank speed [rad/s].
    crank_acceleration : float
        Crank angular acceleration [rad/s^2] (0 for constant speed).
    gas_pressure : float
        Cylinder pressure [Pa].
    par : numpy.ndarray
        Parameter array (:func:`recipsim.model.mechanism_parameters.mechanism_parameters`).
    out : numpy.ndarray
        Output row of length ``N_PIN_OUT``, overwritten: forces on the journal side of
        bearing i at ``3 i + (0, 1, 2)`` [N], then ``PIN_DRIVE_TORQUE``,
        ``PIN_GAS_TORQUE`` [N m], ``PIN_GAS_FORCE`` [N], ``PIN_PISTON_DISPLACEMENT`` [m].
    """
    r = par[lay.P_CRANK_RADIUS]
    big_l = par[lay.P_ROD_LENGTH]
    a = par[lay.P_ROD_COM_FRACTION]
    w2 = omega * omega
    acc = crank_acceleration

    # piston: X only
    x, dx, d2x = piston_displacement(theta, r, big_l)
    a_piston = -(d2x * w2 + dx * acc)  # d2/dt2 of X_pin = r + L - x
    gas_force = -(gas_pressure - par[lay.P_SHELL_PRESSURE]) * par[lay.P_PISTON_AREA]
    pin_x = par[lay.P_PISTON_MASS] * a_piston - gas_force  # force on piston from rod

    # rod: moment balance about its centre of mass gives the pin side force
    phi, dphi, d2phi = rod_angle(theta, r, big_l)
    _, _, dgx, dgy, d2gx, d2gy = rod_centre_of_mass(theta, r, big_l, a)
    agx = d2gx * w2 + dgx * acc
    agy = d2gy * w2 + dgy * acc
    phidd = d2phi * w2 + dphi * acc
    cph = math.cos(phi)
    sph = math.sin(phi)
    m_rod = par[lay.P_ROD_MASS]
    # I phi'' = (-a L e) x E - ((1 - a) L e) x P with E = m a_G + P
    #        = -a L m (e x a_G) - L (e x P)
    e_cross_p = -(par[lay.P_ROD_INERTIA] * phidd + a * big_l * m_rod * (cph * agy - sph * agx))
    e_cross_p /= big_l
    pin_y = (e_cross_p + sph * pin_x) / cph
    ecc_x = m_rod * agx + pin_x  # force on rod from crank pin
    ecc_y = m_rod * agy + pin_y

    # piston side force shared by top and skirt (moment balance, no tilt)
    u_pin = par[lay.P_PISTON_PIN_U]
    u_top = par[lay.P_PISTON_TOP_U]
    u_skirt = par[lay.P_PISTON_SKIRT_U]
    top_y = pin_y * (u_skirt - u_pin) / (u_top - u_skirt)
    skirt_y = -pin_y - top_y

    # rotor: bearings share the eccentric load by moment balance about X and Y
    z1 = par[lay.P_PRIMARY_Z]
    z2 = par[lay.P_SECONDARY_Z]
    share1 = z2 / (z2 - z1)
    share2 = -z1 / (z2 - z1)
    torque = par[lay.P_ROTOR_POLAR_INERTIA] * acc + r * (
        math.cos(theta) * ecc_y - math.sin(theta) * ecc_x
    )
    # counterweight: the rotor carries its centripetal and tangential inertia force
    m_u = par[lay.P_COUNTERWEIGHT_MASS]
    cw_x = 0.0
    cw_y = 0.0
    cw_z = 0.0
    if m_u > 0.0:
        r_u = par[lay.P_COUNTERWEIGHT_RADIUS]
        ang = theta + par[lay.P_COUNTERWEIGHT_ANGLE]
        cw_x = m_u * r_u * (-w2 * math.cos(ang) - acc * math.sin(ang))
        cw_y = m_u * r_u * (-w2 * math.sin(ang) + acc * math.cos(ang))
        cw_z = par[lay.P_COUNTERWEIGHT_Z]
        torque += m_u * r_u * r_u * acc

    for i in range(N_PIN_OUT):
        out[i] = 0.0
    # f1 + f2 = ecc + F_cw; z1 f1 + z2 f2 = z_cw F_cw (moments about the eccentric plane)
    lever = cw_z / (z2 - z1)
    out[3 * lay.B_PRIMARY] = share1 * (ecc_x + cw_x) - lever * cw_x
    out[3 * lay.B_PRIMARY + 1] = share1 * (ecc_y + cw_y) - lever * cw_y
    out[3 * lay.B_SECONDARY] = share2 * (ecc_x + cw_x) + lever * cw_x
    out[3 * lay.B_SECONDARY + 1] = share2 * (ecc_y + cw_y) + lever * cw_y
    out[3 * lay.B_ECCENTRIC] = -ecc_x
    out[3 * lay.B_ECCENTRIC + 1] = -ecc_y
    out[3 * lay.B_PIN] = pin_x
    out[3 * lay.B_PIN + 1] = pin_y
    out[3 * lay.B_PISTON_TOP + 1] = top_y
    out[3 * lay.B_PISTON_SKIRT + 1] = skirt_y
    out[PIN_DRIVE_TORQUE] = torque
    out[PIN_GAS_TORQUE] = -gas_force * dx
    out[PIN_GAS_FORCE] = gas_force
    out[PIN_PISTON_DISPLACEMENT] = x


@njit(cache=True)
def pinned_reactions_array(
    thetas: np.ndarray,
    omega: float,
    gas_pressures: np.ndarray,
    par: np.ndarray,
    out: np.ndarray,
) -> None:
    """:func:`pinned_reactions` at constant speed for arrays of angles and pressures.

    ``out`` has shape ``(len(thetas), N_PIN_OUT)``.
    """
    for i in range(thetas.shape[0]):
        pinned_reactions(thetas[i], omega, 0.0, gas_pressures[i], par, out[i])


@dataclass(frozen=True)
class PinnedLoads:
    """Pinned-mechanism results over an array of crank angles.

    Attributes
    ----------
    crank_angle : numpy.ndarray
        [rad], shape (n,).
    bearing_force : numpy.ndarray
        Force on the journal side, shape (n, 6, 3), bearings in ``BEARING_NAMES`` order,
        inertial X, Y, Z [N].
    drive_torque, gas_torque : numpy.ndarray
        [N m], shape (n,).
    gas_force : numpy.ndarray
        Axial gas force on the piston [N].
    piston_displacement : numpy.ndarray
        From TDC [m].
    """

    crank_angle: np.ndarray
    bearing_force: np.ndarray
    drive_torque: np.ndarray
    gas_torque: np.ndarray
    gas_force: np.ndarray
    piston_displacement: np.ndarray

    def force(self, name: str) -> np.ndarray:
        """Force of bearing ``name``, shape (n, 3) [N]."""
        return self.bearing_force[:, lay.BEARING_NAMES.index(name), :]

    def force_rms(self) -> np.ndarray:
        """RMS of the force magnitude per bearing over the samples [N], shape (6,).

        Meaningful as a cycle RMS when the angles are uniform over one revolution.
        """
        return force_rms(self.bearing_force)

    def force_peak(self) -> np.ndarray:
        """Largest force magnitude per bearing [N], shape (6,)."""
        return np.linalg.norm(self.bearing_force, axis=2).max(axis=0)


def force_rms(bearing_force: np.ndarray) -> np.ndarray:
    """RMS of the force magnitude over axis 0 of an (n, 6, 3) array [N]."""
    return np.sqrt(np.mean(np.sum(bearing_force**2, axis=2), axis=0))
