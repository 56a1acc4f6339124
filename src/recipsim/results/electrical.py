"""From indicated to electrical: friction, motor losses and the rating standard's capacity.

Summary columns (units in the names; ``reports/README.md`` documents them):

- ``friction_power [W]``: mechanical friction of the bearings and the piston.
  ``options.friction = "off"``: 0. ``"mean"``: Petroff's law for every journal with film
  data (``diameter``, ``length``, ``radial_clearance``; primary and secondary turn at
  the crank speed, the eccentric at crank minus rod spin, the pin at the rod's swing)
  and the concentric skirt's Couette shear (piston length inside the bore, the piston
  film's clearance or else ``leakage.radial_clearance``), time means over the cycle
  (:mod:`recipsim.physics.mean_friction`), added to the shaft power; per bearing as
  ``friction_power_<name> [W]`` and ``piston_friction_power [W]``, the names the film
  scenes use. ``"films"``: the sum of the film scenes' own columns (already in the
  shaft power, which the flexible crank integrates).
- ``motor_electrical_power [W]``, ``motor_efficiency [-]``, ``motor_power_factor [-]``,
  ``motor_loss_power [W]`` (electrical - shaft) and its split
  ``motor_<loss>_loss_power [W]`` (main and auxiliary winding copper, rotor copper, core,
  stray, windage), ``motor_current [A]``, ``motor_speed_at_load [rpm]``.
  ``options.motor = "lossless"``: electrical = shaft power, efficiency 1, no losses,
  except under the induction-motor drive, whose rotor copper loss (air-gap less shaft
  power) is then the motor's loss and is in the electrical power and the COP.
  ``"equivalent_circuit"``: the circuit at the load torque ``T = P_shaft / omega_mean``
  (:func:`recipsim.physics.motor_circuit.motor_operating_point_at_torque`); its losses
  at that point are added to the cycle's shaft power. At constant speed the cycle runs
  at the case's shaft speed; the circuit's slip at that torque gives
  ``motor_speed_at_load``, which may differ (the cycle is not re-run at it). With the
  induction-motor drive the dynamics keep their torque curve and the losses come from
  the circuit at the cycle's mean torque.
- ``COP [-]``: cooling capacity over motor electrical power; ``indicated_COP [-]``:
  over indicated power.
"""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np

from recipsim.case.case import Case
from recipsim.case.rating import SATURATED_LIQUID_BAND
from recipsim.case.sections import OperatingPoint
from recipsim.model.loss_sources import (
    film_viscosity,
    friction_film_temperature,
    mean_friction_powers,
    motor_point,
)
from recipsim.physics.friction_models import FRICTION_MODELS
from recipsim.physics.mean_friction import time_mean
from recipsim.results.sampled import CycleColumns

#: Loss columns of the motor and the operating-point attribute each one reads.
MOTOR_LOSSES = {
    "motor_main_copper_loss_power [W]": "main_copper_loss",
    "motor_auxiliary_copper_loss_power [W]": "auxiliary_copper_loss",
    "motor_rotor_copper_loss_power [W]": "rotor_copper_loss",
    "motor_core_loss_power [W]": "core_loss",
    "motor_stray_loss_power [W]": "stray_loss",
    "motor_windage_loss_power [W]": "windage_loss",
}


def rating_enthalpies(fluid: Any, op: OperatingPoint) -> tuple[float, float]:
    """Suction-gas and liquid enthalpies the capacity is defined with [J/kg].

    The suction gas at the suction pressure and ``op.suction_temperature`` (the
    compressor inlet, or the standard's suction gas); the liquid at the discharge pressure
    and ``op.liquid_temperature``, saturated liquid within 1 uK of the bubble point.
    """
    gas = fluid.state_pt(op.suction_pressure, op.suction_temperature, entropy=False)
    h_gas = float(gas["h"])
    p = op.discharge_pressure
    if not math.isnan(op.condensing_temperature):
        bubble = fluid.saturation_temperature(p, 0.0)
        if op.liquid_temperature >= bubble - SATURATED_LIQUID_BAND:
            return h_gas, float(fluid.saturated_liquid_enthalpy(p))
    return h_gas, float(fluid.liquid_enthalpy(p, op.liquid_temperature))


def _film_friction(cycle: CycleColumns) -> float:
    """Total friction of the film scenes' bearings and piston [W] (time means)."""
    speed = cycle["crank_speed [rad/s]"]
    names = [c for c in cycle if c.startswith("bearing_power_loss_")]
    if "piston_friction_power [W]" in cycle:
        names.append("piston_friction_power [W]")
    return sum(time_mean(cycle[c], speed) for c in names)


def mean_friction_columns(
    case: Case, cycle: CycleColumns, oil_temperature: float | None = None
) -> dict[str, float]:
    """Petroff journals, the viscous skirt, the thrust bearing and the oil pump over the
    cycle's samples [W] (time means, :func:`recipsim.model.loss_sources.
    mean_friction_powers`), the films at ``oil_temperature`` [K] (None: their fixed film
    temperatures)."""
    return mean_friction_powers(
        case,
        np.radians(cycle["crank_angle [deg]"]),
        cycle["crank_speed [rad/s]"],
        cycle["piston_displacement [m]"],
        cycle["piston_velocity [m/s]"],
        oil_temperature,
    )


def friction_columns(
    case: Case, cycle: CycleColumns, oil_temperature: float | None = None
) -> dict[str, float]:
    """``friction_power [W]`` (and, for ``mean``, per source, with the film temperature
    and viscosity used) of ``options.friction``; ``oil_temperature`` [K]: the thermal
    network's oil node temperature the friction was taken at (None: the fixed film
    temperatures)."""
    option = FRICTION_MODELS[case.options.friction]
    if option.mean_laws:
        row = mean_friction_columns(case, cycle, oil_temperature)
        t = friction_film_temperature(case, oil_temperature)
        row["friction_film_temperature [K]"] = t
        row["friction_film_viscosity [Pa*s]"] = film_viscosity(case, t)
        return row
    if option.on_films:
        return {"friction_power [W]": _film_friction(cycle)}
    return {"friction_power [W]": 0.0}


def _lossless(shaft_power: float, rotor_loss: float = 0.0) -> dict[str, float]:
    """A motor whose only loss is the dynamic drive's rotor copper (0 for other drives)."""
    electrical = shaft_power + rotor_loss
    row = {
        "motor_electrical_power [W]": electrical,
        "motor_efficiency [-]": shaft_power / electrical if electrical > 0.0 else 1.0,
        "motor_power_factor [-]": math.nan,
        "motor_loss_power [W]": rotor_loss,
    }
    row.update(dict.fromkeys(MOTOR_LOSSES, 0.0))
    row["motor_rotor_copper_loss_power [W]"] = rotor_loss
    row["motor_current [A]"] = math.nan
    row["motor_speed_at_load [rpm]"] = math.nan
    return row


def motor_columns(
    case: Case, shaft_power: float, mean_speed: float, rotor_loss: float = math.nan
) -> dict[str, float]:
    """Electrical power, efficiency, power factor and losses at the cycle's load.

    Parameters
    ----------
    case : Case
        Its ``options.motor`` and ``motor_circuit``.
    shaft_power : float
        Mean power the shaft takes [W].
    mean_speed : float
        Mean crank speed [rad/s] (one revolution over its duration).
    rotor_loss : float
        Rotor copper loss of the induction-motor drive integrated with the motion [W]
        (NaN for other drives): with ``options.motor = "lossless"`` it is the motor's
        only loss, so that every electrical COP counts it.
    """
    try:
        point = motor_point(case, shaft_power, mean_speed)
    except ValueError as exc:  # past breakdown: the motor stalls
        warnings.warn(f"{case.name}: {exc}", stacklevel=2)
        return {k: math.nan for k in _lossless(shaft_power)}
    if point is None:
        return _lossless(shaft_power, 0.0 if math.isnan(rotor_loss) else rotor_loss)
    # the circuit's own input less output: its losses at this load, added to the cycle's
    # shaft power (the same as the circuit's input when it turns at the cycle's speed)
    electrical = shaft_power + (point.electrical_power - point.shaft_power)
    row = {
        "motor_electrical_power [W]": electrical,
        "motor_efficiency [-]": shaft_power / electrical,
        "motor_power_factor [-]": point.power_factor,
        "motor_loss_power [W]": electrical - shaft_power,
    }
    row.update({column: float(getattr(point, name)) for column, name in MOTOR_LOSSES.items()})
    row["motor_current [A]"] = point.line_current
    row["motor_speed_at_load [rpm]"] = point.speed * 30.0 / math.pi
    return row


def loss_columns(
    case: Case,
    cycle: CycleColumns,
    drive_power: float,
    freq: float,
    oil_temperature: float | None = None,
    rotor_loss: float = math.nan,
) -> dict[str, Any]:
    """The case's options, friction and motor columns, and ``shaft_power [W]``.

    Parameters
    ----------
    case : Case
        The case.
    cycle : DataFrame
        Its cycle table (uniform crank-angle samples).
    drive_power : float
        Mean power of the drive integrated with the motion [W] (the shaft power without
        mean friction).
    freq : float
        Revolutions per second [1/s].
    oil_temperature : float or None
        The films' temperature of the ``mean`` friction [K] (the thermal network's oil
        node, as the network took it); None: the fixed film temperatures.
    rotor_loss : float
        The induction-motor drive's rotor copper loss [W] (NaN for other drives).
    """
    row: dict[str, Any] = {
        "standard": case.operating_point.standard,
        "ambient_temperature [K]": case.operating_point.ambient_temperature,
        "friction": case.options.friction,
        "motor": case.options.motor,
    }
    row.update(friction_columns(case, cycle, oil_temperature))
    mean_laws = FRICTION_MODELS[case.options.friction].mean_laws
    shaft = drive_power + (row["friction_power [W]"] if mean_laws else 0.0)
    row["shaft_power [W]"] = shaft
    row.update(motor_columns(case, shaft, 2.0 * math.pi * freq, rotor_loss))
    return row
