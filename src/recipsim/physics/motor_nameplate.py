"""Motor circuit from nameplate-style data, and the default household compressor motor.

:func:`motor_circuit_from_nameplate` picks the main-winding resistance ``R1``, rotor
resistance ``R2``, leakage reactance ``X2`` (with ``X1 = ratio * X2``) and magnetising
reactance ``Xm`` so that the circuit of :mod:`recipsim.physics.motor_circuit` reproduces
four rated figures exactly: shaft power at rated speed, input power (efficiency), power
factor (or current) and breakdown torque ratio. Core, friction-windage and stray-load
losses are set beforehand from per-unit assumptions (see :class:`MotorNameplate`); the
stator and rotor copper losses then share what the efficiency leaves.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np

from recipsim.physics.motor_circuit import (
    MotorCircuit,
    half_field_impedance,
    motor_breakdown,
    motor_operating_point,
)

#: Misfit returned where trial values give no valid circuit [-].
_INVALID_MISFIT = 1e6


def _require(condition: bool, message: str) -> None:
    if not condition:
        raise ValueError(message)


@dataclass(frozen=True)
class MotorNameplate:
    """Nameplate-style data of a single-phase induction motor and the per-unit
    assumptions that turn it into a circuit (all SI).

    Give exactly one of ``rated_efficiency`` / ``rated_input_power`` and one of
    ``rated_power_factor`` / ``rated_current``.

    Attributes
    ----------
    voltage, frequency, poles : float, float, int
        Supply voltage [V rms], frequency [Hz], number of poles [-].
    rated_output, rated_speed : float
        Shaft power [W] at rated speed [rad/s].
    breakdown_torque_ratio : float
        Breakdown (pull-out) shaft torque over rated torque [-].
    rated_efficiency, rated_input_power : float or None
        Efficiency [-] or electrical input [W] at the rated point.
    rated_power_factor, rated_current : float or None
        Power factor [-] or line current [A rms] at the rated point.
    variant : str
        ``"RSIR"`` or ``"PSC"``. A PSC auxiliary winding is the main winding scaled by
        ``a^2`` (same copper volume) with ``a`` and ``C`` chosen so that the backward
        field vanishes at the rated point.
    core_loss_fraction : float
        Core loss at rated voltage over rated input power [-].
    friction_windage_fraction : float
        Rotor friction and windage at rated speed over rated output [-].
    stray_loss_fraction : float or None
        Stray-load loss over shaft output [-]; None: the IEC 60034-2-1:2014 assigned
        allowance for motors up to 1 kW, 2.5 % of rated input power, as a fraction of
        output.
    leakage_reactance_ratio : float
        ``X1m / X2`` [-] (1: equal split, IEEE 112 and Chapman's convention when the
        split is unknown).
    """

    voltage: float
    frequency: float
    poles: int
    rated_output: float
    rated_speed: float
    breakdown_torque_ratio: float
    rated_efficiency: float | None = None
    rated_input_power: float | None = None
    rated_power_factor: float | None = None
    rated_current: float | None = None
    variant: str = "RSIR"
    core_loss_fraction: float = 0.04
    friction_windage_fraction: float = 0.01
    stray_loss_fraction: float | None = None
    leakage_reactance_ratio: float = 1.0

    @property
    def input_power(self) -> float:
        """Rated electrical input [W]."""
        if self.rated_input_power is not None:
            return self.rated_input_power
        assert self.rated_efficiency is not None
        return self.rated_output / self.rated_efficiency

    @property
    def power_factor(self) -> float:
        """Rated power factor [-]."""
        if self.rated_power_factor is not None:
            return self.rated_power_factor
        assert self.rated_current is not None
        return self.input_power / (self.voltage * self.rated_current)


def _check_nameplate(plate: MotorNameplate) -> None:
    _require(
        (plate.rated_efficiency is None) != (plate.rated_input_power is None),
        "motor nameplate: give exactly one of rated_efficiency and rated_input_power",
    )
    _require(
        (plate.rated_power_factor is None) != (plate.rated_current is None),
        "motor nameplate: give exactly one of rated_power_factor and rated_current",
    )
    w_s = 4.0 * math.pi * plate.frequency / plate.poles
    _require(
        0.0 < plate.rated_speed < w_s,
        f"motor rated speed {plate.rated_speed} rad/s: must lie below synchronous {w_s:.6g}",
    )
    _require(plate.rated_output > 0.0, "motor rated output must be positive")
    efficiency = plate.rated_output / plate.input_power
    _require(0.0 < efficiency < 1.0, f"motor rated efficiency {efficiency:.6g}: must be in (0, 1)")
    _require(0.0 < plate.power_factor <= 1.0, "motor rated power factor must be in (0, 1]")
    _require(plate.breakdown_torque_ratio > 1.0, "motor breakdown torque ratio must exceed 1")


def _nameplate_circuit(plate: MotorNameplate, main: tuple[float, ...]) -> MotorCircuit:
    """Circuit with main-winding values ``(R1, R2, X2, Xm)`` and the nameplate's losses."""
    r1, r2, x2, xm = main
    w_s = 4.0 * math.pi * plate.frequency / plate.poles
    stray = plate.stray_loss_fraction
    if stray is None:
        stray = 0.025 * plate.input_power / plate.rated_output
    circuit = MotorCircuit(
        voltage=plate.voltage,
        frequency=plate.frequency,
        poles=plate.poles,
        main_resistance=r1,
        main_leakage_reactance=plate.leakage_reactance_ratio * x2,
        magnetising_reactance=xm,
        rotor_resistance=r2,
        rotor_leakage_reactance=x2,
        core_conductance=plate.core_loss_fraction * plate.input_power / plate.voltage**2,
        friction_windage_loss=plate.friction_windage_fraction
        * plate.rated_output
        * (w_s / plate.rated_speed) ** 2,
        stray_loss_fraction=stray,
    )
    if plate.variant == "RSIR":
        return circuit
    # Balance at the rated slip with Z1a = a^2 Z1m: from I_b = 0 (I_a = j I_m / a),
    # a = Im(Z) / Re(Z) and X_C = a |Z|^2 / Re(Z), Z = Z1m + 2 Z_f.
    slip = 1.0 - plate.rated_speed / w_s
    z = complex(r1, circuit.main_leakage_reactance) + 2.0 * half_field_impedance(slip, circuit)
    a = z.imag / z.real
    capacitance = z.real / (2.0 * math.pi * plate.frequency * a * abs(z) ** 2)
    return replace(
        circuit,
        variant="PSC",
        aux_turns_ratio=a,
        aux_resistance=a * a * r1,
        aux_leakage_reactance=a * a * circuit.main_leakage_reactance,
        run_capacitance=capacitance,
    )


def _rated_residuals(plate: MotorNameplate, log_main: np.ndarray) -> np.ndarray:
    """Relative misfit of the four rated figures for main-winding values ``exp(log_main)``
    (a large misfit where those values give no valid circuit)."""
    try:
        circuit = _nameplate_circuit(plate, tuple(float(v) for v in np.exp(log_main)))
        point = motor_operating_point(circuit, plate.rated_speed)
        breakdown = motor_breakdown(circuit)[1]
    except (ArithmeticError, ValueError):
        return np.full(4, _INVALID_MISFIT)
    rated_torque = plate.rated_output / plate.rated_speed
    misfit = np.array(
        [
            point.shaft_power / plate.rated_output - 1.0,
            point.electrical_power / plate.input_power - 1.0,
            point.power_factor - plate.power_factor,
            breakdown / rated_torque - plate.breakdown_torque_ratio,
        ]
    )
    return misfit if np.all(np.isfinite(misfit)) else np.full(4, _INVALID_MISFIT)


def motor_circuit_from_nameplate(plate: MotorNameplate) -> MotorCircuit:
    """Equivalent circuit that reproduces the nameplate's rated point exactly.

    Parameters
    ----------
    plate : MotorNameplate
        Rated figures and per-unit loss assumptions.

    Returns
    -------
    MotorCircuit
        Circuit whose shaft power, input power, power factor at rated speed and
        breakdown torque ratio match the nameplate to about 1e-12 relative.

    Raises
    ------
    ValueError
        If the data are inconsistent or no circuit of this form reproduces them (for
        example an efficiency that leaves no room for the rotor copper loss the slip
        implies).
    """
    from scipy.optimize import least_squares  # a heavy import, needed only to fit

    _check_nameplate(plate)
    w_s = 4.0 * math.pi * plate.frequency / plate.poles
    slip = 1.0 - plate.rated_speed / w_s
    # Starts: input resistance R_in = V^2 pf^2 / P_in shared between stator and a
    # forward field at about 45 degrees (Xm ~ R2/s), leakage a fraction of |Z_in|; the
    # later starts only matter where the first does not converge.
    z_in = plate.voltage**2 * plate.power_factor / plate.input_power
    r_in = z_in * plate.power_factor
    # the impedances stay within 1e-6..1e6 of the input impedance (log bounds)
    bounds = (math.log(z_in) - 14.0, math.log(z_in) + 14.0)
    best, misfit = np.zeros(4), math.inf
    for stator, leakage in ((0.25, 0.1), (0.05, 0.2), (0.5, 0.05), (0.1, 0.4)):
        start = np.log([stator * r_in, 3.0 * slip * r_in, leakage * z_in, 3.0 * r_in])
        trial = least_squares(
            lambda x: _rated_residuals(plate, x),
            start,
            bounds=bounds,
            xtol=1e-15,
            ftol=1e-15,
            gtol=1e-15,
        )
        trial_misfit = float(np.max(np.abs(trial.fun)))
        if trial_misfit < misfit:
            best, misfit = trial.x, trial_misfit
        if misfit < 1e-12:
            break
    names = ("R1", "R2", "X2", "Xm")
    vanishing = [name for name, x in zip(names, best, strict=True) if x < bounds[0] + 2.0]
    _require(
        misfit < 1e-10,
        f"motor nameplate: no circuit reproduces the rated point (misfit {misfit:.3g}"
        + (f"; the closest one has {', '.join(vanishing)} near zero" if vanishing else "")
        + "): the efficiency, power factor, speed and breakdown ratio are not consistent "
        "with this circuit and its loss assumptions",
    )
    return _nameplate_circuit(plate, tuple(float(v) for v in np.exp(best)))


#: A household hermetic compressor motor of about 100 W output (1/5-1/4 hp class): a
#: two-pole RSIR motor on 230 V 50 Hz at 2900 rpm under load (the speed the catalogue
#: README gives for Secop LBP compressors). Assumptions, not a datasheet: efficiency
#: 0.80 (the 0.75-0.85 band expected for purpose-built compressor motors; general-
#: purpose 0.25 hp two-pole CSIR motors must reach 66.6 % under 10 CFR 431.446);
#: power factor 0.65 (no run capacitor: Chapman's 1/4 hp split-phase example runs at
#: 0.69); breakdown ratio 2.0 (torque scales with voltage squared, so running at 85 %
#: voltage needs at least 1/0.85^2 = 1.38, plus margin for the cyclic load); core 4 %
#: of input, rotor windage 1 % of output, stray 2.5 % of input (IEC 60034-2-1).
HOUSEHOLD_COMPRESSOR_NAMEPLATE = MotorNameplate(
    voltage=230.0,
    frequency=50.0,
    poles=2,
    rated_output=100.0,
    rated_speed=2900.0 * 2.0 * math.pi / 60.0,
    breakdown_torque_ratio=2.0,
    rated_efficiency=0.80,
    rated_power_factor=0.65,
)


@lru_cache(maxsize=1)
def household_compressor_motor() -> MotorCircuit:
    """Circuit of :data:`HOUSEHOLD_COMPRESSOR_NAMEPLATE` (built once, cached)."""
    return motor_circuit_from_nameplate(HOUSEHOLD_COMPRESSOR_NAMEPLATE)
