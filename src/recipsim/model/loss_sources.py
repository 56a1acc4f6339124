"""Friction and motor losses of a case as functions of the solved motion: shared by the
summary (:mod:`recipsim.results.electrical`) and by the shell's thermal network, which
takes them as heat sources after every revolution (:class:`recipsim.model.thermal.
ThermalCoupling.loss_sources`).

``options.friction = "mean"``: Petroff's law for every journal with film data (primary
and secondary turn at the crank speed, the eccentric at crank minus rod spin, the pin at
the rod's swing) and the concentric skirt's Couette shear (piston length inside the
bore, the piston film's clearance or else ``leakage.radial_clearance``), time means
(:mod:`recipsim.physics.mean_friction`). ``options.motor = "equivalent_circuit"``: the
circuit's losses at the load torque ``P_shaft / omega_mean``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from recipsim.case.load import Case
from recipsim.case.lubrication import parse_oil
from recipsim.model.scenes import MQ_BEARINGS, MQ_DRIVE, SCENE_CYLINDER
from recipsim.physics.kinematics import piston_displacement_array, piston_velocity_array
from recipsim.physics.mean_friction import (
    journal_petroff_power,
    rod_swing_rate,
    skirt_viscous_force,
    time_mean,
    wetted_skirt_length,
)
from recipsim.physics.mechanics import layout as mlay
from recipsim.physics.motor_circuit import MotorOperatingPoint, motor_operating_point_at_torque
from recipsim.physics.thermo import cylinder as cyl

#: Journals and the spin of journal relative to sleeve, in units of the crank speed, as a
#: function of the rod angle's crank-angle derivative.
JOURNAL_SPINS: dict[str, Callable[[np.ndarray], np.ndarray]] = {
    "primary": lambda dphi: np.ones_like(dphi),
    "secondary": lambda dphi: np.ones_like(dphi),
    "eccentric": lambda dphi: 1.0 - dphi,
    "pin": lambda dphi: dphi,
}


def mean_friction_powers(
    case: Case,
    theta: np.ndarray,
    speed: np.ndarray,
    displacement: np.ndarray,
    velocity: np.ndarray,
) -> dict[str, float]:
    """Petroff journals and the viscous skirt [W], time means over crank-angle samples.

    Parameters
    ----------
    case : Case
        Geometry, bearings' film data, oil, leakage clearance.
    theta, speed : ndarray
        Crank angle [rad] and crank speed [rad/s] at uniform crank-angle samples.
    displacement, velocity : ndarray
        Piston displacement from top dead centre [m] and its velocity [m/s].

    Returns
    -------
    dict
        ``friction_power_<name> [W]`` per journal with film data,
        ``piston_friction_power [W]`` and their sum ``friction_power [W]``.
    """
    geo = case.geometry
    mech = case.mechanism
    dphi = rod_swing_rate(theta, geo.crank_radius, geo.connecting_rod_length)
    row: dict[str, float] = {}
    for name, relative in JOURNAL_SPINS.items():
        film = mech.bearing(name).film
        if film is None:
            continue
        power = journal_petroff_power(
            film.viscosity, film.diameter, film.length, film.radial_clearance,
            relative(dphi) * speed,
        )  # fmt: skip
        row[f"friction_power_{name} [W]"] = time_mean(power, speed)
    piston_film = mech.bearing("piston_skirt").film
    if piston_film is not None:
        viscosity, clearance = piston_film.viscosity, piston_film.radial_clearance
    else:
        oil = mech.oil if mech.oil is not None else parse_oil(None, case.path)
        viscosity = oil.viscosity(oil.film_temperature)
        clearance = case.leakage.radial_clearance
    crown = geo.clearance_volume / geo.piston_area + displacement
    wetted = wetted_skirt_length(mech.piston.length, geo.liner_length, crown)
    force = skirt_viscous_force(viscosity, geo.bore, wetted, clearance, velocity)
    row["piston_friction_power [W]"] = time_mean(-force * velocity, speed)
    row["friction_power [W]"] = float(sum(row.values()))
    return row


def constant_speed_mean_friction(case: Case, samples: int = 360) -> float:
    """``friction_power [W]`` of ``mean`` friction at the case's constant shaft speed
    (rigid slider-crank kinematics on ``samples`` uniform angles)."""
    geo = case.geometry
    theta = np.linspace(0.0, 2.0 * math.pi, samples, endpoint=False)
    omega = case.operating_point.shaft_speed
    x = piston_displacement_array(theta, geo.crank_radius, geo.connecting_rod_length)
    dx = piston_velocity_array(theta, geo.crank_radius, geo.connecting_rod_length)
    speed = np.full(samples, omega)
    return mean_friction_powers(case, theta, speed, x, dx * omega)["friction_power [W]"]


def motor_point(
    case: Case, shaft_power: float, mean_speed: float, slip_guess: float | None = None
) -> MotorOperatingPoint | None:
    """The equivalent circuit at the load torque ``shaft_power / mean_speed`` (None for a
    lossless motor); ``slip_guess``: a slip near the answer (the last one), see
    :func:`~recipsim.physics.motor_circuit.motor_operating_point_at_torque`.

    Raises
    ------
    ValueError
        If the torque exceeds the motor's breakdown torque.
    """
    circuit = case.motor_circuit
    if case.options.motor == "lossless" or circuit is None:
        return None
    return motor_operating_point_at_torque(circuit, shaft_power / mean_speed, slip_guess)


def revolution_shaft_power(
    model: Any, y_end: np.ndarray, duration: float, mean_friction: float = 0.0
) -> tuple[float, float]:
    """``(shaft power, friction) [W]`` of a revolution: the drive's work over its duration
    (quadratures ``y_end``) plus the ``mean`` friction ``mean_friction`` [W]
    (:func:`constant_speed_mean_friction`, once per model); the friction is that constant,
    or the flexible scenes' bearing dissipation (films, dampers), already in the drive's
    work."""
    case: Case = model.case
    if model.scene == SCENE_CYLINDER:
        drive, films = y_end[cyl.Q_SHAFT], 0.0
    else:  # the crank train integrates the drive's work and the bearings' dissipation
        q = model.mechanism_offset + mlay.N_STATE
        drive, films = y_end[q + MQ_DRIVE], y_end[q + MQ_BEARINGS] / duration
    if case.options.friction == "mean":
        return drive / duration + mean_friction, mean_friction
    return drive / duration, films


class NetworkLossSources:
    """``(motor loss, friction) [W]`` of a revolution for the thermal network
    (:attr:`recipsim.model.thermal.ThermalCoupling.loss_sources`).

    Shaft power and friction from :func:`revolution_shaft_power` (``y_end``: the
    revolution's quadratures, ``duration`` [s]), or before any revolution (``y_end``
    None) from an estimated ``drive_power`` [W] plus the ``mean`` friction; the motor loss
    is the circuit's at that load (0 for a lossless motor or past breakdown, where the
    summary reports NaN and a warning). Each revolution's motor point starts from the
    last one's slip (the load changes little between revolutions).

    Parameters
    ----------
    mean_friction : float
        The ``mean`` friction at the case's constant speed [W]
        (:func:`constant_speed_mean_friction`; 0 without it).
    """

    def __init__(self, mean_friction: float = 0.0) -> None:
        self.mean_friction = mean_friction
        self._slip: float | None = None

    def __call__(
        self,
        model: Any,
        y_end: np.ndarray | None,
        duration: float,
        drive_power: float | None = None,
    ) -> tuple[float, float]:
        case: Case = model.case
        if y_end is not None:
            shaft, friction = revolution_shaft_power(model, y_end, duration, self.mean_friction)
        else:
            assert drive_power is not None
            friction = self.mean_friction if case.options.friction == "mean" else 0.0
            shaft = drive_power + friction
        try:
            point = motor_point(case, shaft, 2.0 * math.pi / duration, self._slip)
        except ValueError:
            return 0.0, friction
        if point is None:
            return 0.0, friction
        self._slip = point.slip if point.slip > 0.0 else None
        return point.electrical_power - point.shaft_power, friction
