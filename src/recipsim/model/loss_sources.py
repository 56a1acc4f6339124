"""Friction and motor losses of a case as functions of the solved motion: shared by the
summary (:mod:`recipsim.results.electrical`) and by the shell's thermal network, which
takes them as heat sources after every revolution (:class:`recipsim.model.thermal.
ThermalCoupling.loss_sources`).

``options.friction = "mean"``: Petroff's law for every journal with film data (primary
and secondary turn at the crank speed, the eccentric at crank minus rod spin, the pin at
the rod's swing), the concentric skirt's Couette shear (piston length inside the
bore, the piston film's clearance or else ``leakage.radial_clearance``), the thrust
bearing (a flat collar's viscous torque or a ball bearing's) and the oil pump's
hydraulic power (``[friction]``), time means (:mod:`recipsim.physics.mean_friction`).
The films' viscosity is the oil's law at the thermal network's oil node temperature
when the case runs the network, else at the fixed film temperatures; diluted by the
dissolved refrigerant of ``[oil]``. ``options.motor = "equivalent_circuit"``: the
circuit's losses at the load torque ``P_shaft / omega_mean``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from recipsim.case.load import Case
from recipsim.case.lubrication import OilSpec, parse_oil
from recipsim.model.scenes import MQ_BEARINGS, MQ_DRIVE, SCENE_CYLINDER
from recipsim.physics.friction_models import FRICTION_MODELS
from recipsim.physics.kinematics import piston_displacement_array, piston_velocity_array
from recipsim.physics.lubricant import diluted_viscosity, refrigerant_liquid_viscosity
from recipsim.physics.mean_friction import (
    journal_petroff_power,
    oil_pump_power,
    rod_swing_rate,
    skirt_viscous_force,
    thrust_ball_torque,
    thrust_collar_torque,
    time_mean,
    wetted_skirt_length,
)
from recipsim.physics.mechanics import layout as mlay
from recipsim.physics.motor_circuit import MotorOperatingPoint, motor_operating_point_at_torque
from recipsim.physics.motor_models import MOTOR_MODELS
from recipsim.physics.thermo import cylinder as cyl
from recipsim.physics.thermo.shell_nodes import OIL

#: Journals and the spin of journal relative to sleeve, in units of the crank speed, as a
#: function of the rod angle's crank-angle derivative.
JOURNAL_SPINS: dict[str, Callable[[np.ndarray], np.ndarray]] = {
    "primary": lambda dphi: np.ones_like(dphi),
    "secondary": lambda dphi: np.ones_like(dphi),
    "eccentric": lambda dphi: 1.0 - dphi,
    "pin": lambda dphi: dphi,
}


def _case_oil(case: Case) -> OilSpec:
    mech = case.mechanism
    return mech.oil if mech.oil is not None else parse_oil(None, case.path)


def film_viscosity(case: Case, temperature: float) -> float:
    """The oil's dynamic viscosity at ``temperature`` [K] by its fitted law (Walther for
    the shipped ISO VG 10), lowered by the dissolved refrigerant of ``[oil]``
    (:func:`recipsim.physics.lubricant.diluted_viscosity`) [Pa s]."""
    oil = _case_oil(case)
    mu = oil.viscosity(temperature)
    w = oil.dissolved_refrigerant_fraction
    if w == 0.0:
        return mu
    mu_r, molar_mass = refrigerant_liquid_viscosity(case.refrigerant.coolprop_name, temperature)
    return diluted_viscosity(mu, mu_r, w, oil.molar_mass, molar_mass)


def _journal_powers(
    case: Case, dphi: np.ndarray, speed: np.ndarray, oil_temperature: float | None
) -> dict[str, float]:
    row: dict[str, float] = {}
    for name, relative in JOURNAL_SPINS.items():
        film = case.mechanism.bearing(name).film
        if film is None:
            continue
        t = film.film_temperature if oil_temperature is None else oil_temperature
        power = journal_petroff_power(
            film_viscosity(case, t), film.diameter, film.length, film.radial_clearance,
            relative(dphi) * speed,
        )  # fmt: skip
        row[f"friction_power_{name} [W]"] = time_mean(power, speed)
    return row


def _thrust_and_pump_powers(case: Case, speed: np.ndarray, viscosity: float) -> dict[str, float]:
    """The thrust bearing and the oil pump of ``[friction]`` [W] (time means)."""
    spec = case.friction
    row: dict[str, float] = {}
    if spec.thrust_bearing == "collar":
        torque = thrust_collar_torque(
            viscosity, spec.thrust_inner_diameter, spec.thrust_outer_diameter,
            spec.thrust_film_thickness, speed,
        )  # fmt: skip
        row["friction_power_thrust [W]"] = time_mean(torque * speed, speed)
    elif spec.thrust_bearing == "ball":
        pitch = 0.5 * (spec.thrust_inner_diameter + spec.thrust_outer_diameter)
        load = spec.thrust_force(case.mechanism.rotor.mass)
        ball = thrust_ball_torque(spec.thrust_ball_friction_coefficient, load, pitch)
        row["friction_power_thrust [W]"] = time_mean(ball * np.asarray(speed), speed)
    density = _case_oil(case).oil.density
    pump = oil_pump_power(
        density, spec.oil_pump_flow, np.asarray(speed), spec.oil_pump_outlet_radius,
        spec.oil_pump_lift,
    )  # fmt: skip
    row["friction_power_oil_pump [W]"] = time_mean(pump, speed)
    return row


def mean_friction_powers(
    case: Case,
    theta: np.ndarray,
    speed: np.ndarray,
    displacement: np.ndarray,
    velocity: np.ndarray,
    oil_temperature: float | None = None,
) -> dict[str, float]:
    """Petroff journals, the viscous skirt, the thrust bearing and the oil pump [W], time
    means over crank-angle samples.

    Parameters
    ----------
    case : Case
        Geometry, bearings' film data, oil, leakage clearance, ``[friction]``.
    theta, speed : ndarray
        Crank angle [rad] and crank speed [rad/s] at uniform crank-angle samples.
    displacement, velocity : ndarray
        Piston displacement from top dead centre [m] and its velocity [m/s].
    oil_temperature : float or None
        Temperature of every film [K] (the thermal network's oil node); None: each film
        at its own film temperature (``oil.film_temperature`` where it gives none).

    Returns
    -------
    dict
        ``friction_power_<name> [W]`` per journal with film data (the pin among them),
        ``piston_friction_power [W]``, ``friction_power_thrust [W]`` (unless
        ``friction.thrust_bearing = "none"``), ``friction_power_oil_pump [W]`` and their
        sum ``friction_power [W]``.
    """
    geo = case.geometry
    mech = case.mechanism
    dphi = rod_swing_rate(theta, geo.crank_radius, geo.connecting_rod_length)
    row = _journal_powers(case, dphi, speed, oil_temperature)
    fixed = _case_oil(case).film_temperature
    piston_film = mech.bearing("piston_skirt").film
    if piston_film is not None:
        clearance = piston_film.radial_clearance
        t_skirt = piston_film.film_temperature if oil_temperature is None else oil_temperature
    else:
        clearance = case.leakage.radial_clearance
        t_skirt = fixed if oil_temperature is None else oil_temperature
    # the whole piston inside the bore at each crank angle (with the default liner, the
    # whole piston at every angle)
    crown = geo.clearance_volume / geo.piston_area + displacement
    wetted = wetted_skirt_length(mech.piston.length, geo.liner_length, crown)
    force = skirt_viscous_force(
        film_viscosity(case, t_skirt), geo.bore, wetted, clearance, velocity
    )
    row["piston_friction_power [W]"] = time_mean(-force * velocity, speed)
    t_bulk = fixed if oil_temperature is None else oil_temperature
    row.update(_thrust_and_pump_powers(case, speed, film_viscosity(case, t_bulk)))
    row["friction_power [W]"] = float(sum(row.values()))
    return row


def friction_film_temperature(case: Case, oil_temperature: float | None) -> float:
    """The temperature the mean friction takes its films at [K] (those without a film
    temperature of their own, without the network): the oil node's, or
    ``oil.film_temperature``."""
    return _case_oil(case).film_temperature if oil_temperature is None else oil_temperature


def constant_speed_mean_friction(
    case: Case, samples: int = 360, oil_temperature: float | None = None
) -> float:
    """``friction_power [W]`` of ``mean`` friction at the case's constant shaft speed
    (rigid slider-crank kinematics on ``samples`` uniform angles), the films at
    ``oil_temperature`` [K] (None: their fixed film temperatures)."""
    geo = case.geometry
    theta = np.linspace(0.0, 2.0 * math.pi, samples, endpoint=False)
    omega = case.operating_point.shaft_speed
    x = piston_displacement_array(theta, geo.crank_radius, geo.connecting_rod_length)
    dx = piston_velocity_array(theta, geo.crank_radius, geo.connecting_rod_length)
    speed = np.full(samples, omega)
    row = mean_friction_powers(case, theta, speed, x, dx * omega, oil_temperature)
    return row["friction_power [W]"]


def network_oil_temperature(model: Any) -> float | None:
    """The oil node temperature [K] of the network solution ``model`` runs with (None
    without a network, or before its first solution)."""
    thermal = getattr(model, "thermal", None)
    if thermal is None or thermal.applied is None:
        return None
    return float(thermal.applied.solution.temperature[OIL])


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
    if not MOTOR_MODELS[case.options.motor].circuit or circuit is None:
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
    if FRICTION_MODELS[case.options.friction].mean_laws:
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

    The ``mean`` friction is taken with the films at the oil node temperature of the
    network solution the model runs with (:func:`network_oil_temperature`; before the
    first one, at the fixed film temperatures), so friction and oil temperature converge
    together with the cycle; :attr:`oil_temperature` is the temperature of the last call
    (None: the fixed ones), which the summary's friction columns use.

    Parameters
    ----------
    case : Case
        Its ``options.friction`` and the friction model's data.
    """

    def __init__(self, case: Case) -> None:
        self.friction_on = FRICTION_MODELS[case.options.friction].mean_laws
        self.oil_temperature: float | None = None
        self._slip: float | None = None
        self._friction: tuple[float | None, float] | None = None

    def mean_friction(self, case: Case, oil_temperature: float | None) -> float:
        """The ``mean`` friction [W] with the films at ``oil_temperature`` [K] (0 with
        another friction option); the last value is kept for the same temperature."""
        if not self.friction_on:
            return 0.0
        if self._friction is None or self._friction[0] != oil_temperature:
            friction = constant_speed_mean_friction(case, oil_temperature=oil_temperature)
            self._friction = (oil_temperature, friction)
        return self._friction[1]

    def __call__(
        self,
        model: Any,
        y_end: np.ndarray | None,
        duration: float,
        drive_power: float | None = None,
    ) -> tuple[float, float]:
        case: Case = model.case
        self.oil_temperature = network_oil_temperature(model)
        mean = self.mean_friction(case, self.oil_temperature)
        if y_end is not None:
            shaft, friction = revolution_shaft_power(model, y_end, duration, mean)
        else:
            assert drive_power is not None
            friction = mean
            shaft = drive_power + friction
        try:
            point = motor_point(case, shaft, 2.0 * math.pi / duration, self._slip)
        except ValueError:
            return 0.0, friction
        if point is None:
            return 0.0, friction
        self._slip = point.slip if point.slip > 0.0 else None
        return point.electrical_power - point.shaft_power, friction


def friction_oil_temperature(model: Any) -> float | None:
    """The oil temperature [K] the ``mean`` friction of ``model``'s last network update
    was taken at (None: without a network, the fixed film temperatures)."""
    thermal = getattr(model, "thermal", None)
    sources = None if thermal is None else thermal.loss_sources
    return sources.oil_temperature if isinstance(sources, NetworkLossSources) else None
