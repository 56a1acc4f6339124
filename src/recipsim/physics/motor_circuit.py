"""Single-phase induction motor: equivalent circuit, losses and electrical input power.

Steady state at a given rotor speed by the double-revolving-field equivalent circuit
(Veinott; Fitzgerald & Kingsley, *Electric Machinery*, unsymmetrical two-phase machine;
Chapman, *Electric Machinery Fundamentals*, ch. 9). The pulsating main-winding field is
split into a forward field (slip ``s``) and a backward field (slip ``2 - s``); each
sees the half impedance ``Z_f = 0.5 (R2/s + jX2) || 0.5 jXm`` and
``Z_b = 0.5 (R2/(2-s) + jX2) || 0.5 jXm`` (rotor referred to the main winding).

Variants:

- ``"RSIR"`` (resistance start, induction run): in run only the main winding carries
  current, ``I_m = V / (R1m + jX1m + Z_f + Z_b)``. The start winding and its PTC or
  relay are a start-up device; they are open in steady state and not modelled.
- ``"PSC"`` (permanent split capacitor): an auxiliary winding in space quadrature with
  ``a = N_aux / N_main`` turns, resistance ``R1a``, leakage ``X1a`` and the run
  capacitor ``C`` in series, on the same supply. With the symmetrical components
  ``I_f = (I_m - j a I_a) / 2``, ``I_b = (I_m + j a I_a) / 2`` the two stator equations
  are ``V = (Z1m + Z_f + Z_b) I_m - j a (Z_f - Z_b) I_a`` and
  ``V = j a (Z_f - Z_b) I_m + (Z1a + a^2 (Z_f + Z_b)) I_a``; the air-gap powers are
  ``P_f = 4 Re(Z_f) |I_f|^2``, ``P_b = 4 Re(Z_b) |I_b|^2`` (RSIR: ``|I_m|^2 Re(Z)``).

Losses: stator copper ``R1 |I|^2`` per winding; rotor copper ``s P_f + (2 - s) P_b``;
core loss as a conductance ``G_c`` across the supply (a loss in W at rated voltage
that scales with the voltage squared, ``G_c V^2``); friction and windage of the rotor
in the shell gas, ``P_fw0 (omega / omega_s)^2`` (a viscous drag torque); stray-load
loss a fraction ``k`` of the shaft output power. Electromagnetic torque
``T = (P_f - P_b) / omega_s``, shaft torque ``(T - T_fw) / (1 + k)``. Input power is
``Re(V I_line*)`` with ``I_line = I_m + I_a + G_c V``.

Speed and torques are positive in the forward field's direction, slip
``s = (omega_s - omega) / omega_s``, ``omega_s = 4 pi f / poles``. Plain complex Python:
called by the summary, by the thermal network after each revolution (the motor's heat)
and by the slip-speed iteration, never in an ODE; the inverse at a torque (a bracketing
march in slip, then Brent's method, ``scipy.optimize.brentq``, to 1e-15 in slip) takes
about 13 evaluations.

Size (over the project's 400 lines): the circuit's solution at a slip, its inverse at a
torque and the breakdown search share the private winding-current and impedance helpers
and the one ``MotorCircuit``; split apart, each half would import the other's privates.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

VARIANTS = ("RSIR", "PSC")
#: Slip at which the forward march of the torque inverse starts [-].
_FIRST_SLIP = 1e-4
#: Ratio between successive slips of the march and of the breakdown scan [-].
_SLIP_STEP = 1.4
#: Slip at which the torque's slope near synchronism is sampled [-].
_LINEAR_SLIP = 1e-3


def _require(condition: bool, message: str) -> None:
    if not condition:
        raise ValueError(message)


@dataclass(frozen=True)
class MotorCircuit:
    """Equivalent-circuit parameters of a single-phase induction motor (all SI).

    Attributes
    ----------
    voltage : float
        Supply voltage, rms [V].
    frequency : float
        Supply frequency [Hz].
    poles : int
        Number of poles [-].
    main_resistance, main_leakage_reactance : float
        Main-winding resistance ``R1m`` and leakage reactance ``X1m`` [ohm].
    magnetising_reactance : float
        Magnetising reactance ``Xm`` [ohm].
    rotor_resistance, rotor_leakage_reactance : float
        Rotor ``R2`` and ``X2`` referred to the main winding [ohm].
    core_conductance : float
        Core-loss conductance across the supply [S]: core loss ``G_c V^2`` [W].
    friction_windage_loss : float
        Friction and windage of the motor's rotor at synchronous speed [W], scaling
        with speed squared.
    stray_loss_fraction : float
        Stray-load loss as a fraction of the shaft output power [-], below 1.
    variant : str
        ``"RSIR"`` (main winding alone in run) or ``"PSC"``.
    aux_turns_ratio : float
        ``a = N_aux / N_main`` [-] (PSC only).
    aux_resistance, aux_leakage_reactance : float
        Auxiliary winding ``R1a``, ``X1a`` [ohm] (PSC only).
    run_capacitance : float
        Run capacitor in series with the auxiliary winding [F] (PSC only).
    """

    voltage: float
    frequency: float
    poles: int
    main_resistance: float
    main_leakage_reactance: float
    magnetising_reactance: float
    rotor_resistance: float
    rotor_leakage_reactance: float
    core_conductance: float = 0.0
    friction_windage_loss: float = 0.0
    stray_loss_fraction: float = 0.0
    variant: str = "RSIR"
    aux_turns_ratio: float = 0.0
    aux_resistance: float = 0.0
    aux_leakage_reactance: float = 0.0
    run_capacitance: float = 0.0

    def __post_init__(self) -> None:
        _require(self.variant in VARIANTS, f"motor variant {self.variant!r}: use RSIR or PSC")
        _require(
            int(self.poles) == self.poles and self.poles >= 2 and self.poles % 2 == 0,
            f"motor poles = {self.poles}: must be an even integer >= 2",
        )
        for name, value in vars(self).items():
            if name not in ("variant", "poles"):
                _require(
                    math.isfinite(value) and value >= 0.0,
                    f"motor {name} = {value}: must be finite and not negative",
                )
        positive = ["voltage", "frequency", "magnetising_reactance", "rotor_resistance"]
        if self.variant == "PSC":
            positive += ["aux_turns_ratio", "run_capacitance"]
        for name in positive:
            _require(getattr(self, name) > 0.0, f"motor {name}: must be positive ({self.variant})")
        _require(self.stray_loss_fraction < 1.0, "motor stray_loss_fraction must be below 1")

    @property
    def synchronous_speed(self) -> float:
        """Speed of the forward field [rad/s]."""
        return 4.0 * math.pi * self.frequency / self.poles


@dataclass(frozen=True)
class MotorOperatingPoint:
    """Steady operating point of the motor (every power in W, currents rms in A).

    Attributes
    ----------
    speed, slip : float
        Rotor speed [rad/s] and slip of the forward field [-].
    electromagnetic_torque, shaft_torque : float
        Air-gap torque and torque delivered to the crankshaft [N m].
    shaft_power : float
        Mechanical output ``shaft_torque * speed`` [W].
    forward_air_gap_power, backward_air_gap_power : float
        Power crossing the air gap into each field [W] (both >= 0).
    main_current, auxiliary_current, line_current : float
        Winding and supply currents [A] (the line current includes the core branch).
    forward_current, backward_current : float
        Symmetrical-component currents referred to the main winding [A].
    main_copper_loss, auxiliary_copper_loss, stator_copper_loss : float
        Stator copper losses per winding and their sum [W].
    forward_rotor_copper_loss, backward_rotor_copper_loss, rotor_copper_loss : float
        Rotor copper losses of each field and their sum [W].
    core_loss, stray_loss, windage_loss : float
        Core, stray-load, and friction and windage losses [W].
    electrical_power : float
        Active input power [W].
    power_factor : float
        ``electrical_power / (V * line_current)`` [-].
    efficiency : float
        ``shaft_power / electrical_power`` [-].
    """

    speed: float
    slip: float
    electromagnetic_torque: float
    shaft_torque: float
    shaft_power: float
    forward_air_gap_power: float
    backward_air_gap_power: float
    main_current: float
    auxiliary_current: float
    line_current: float
    forward_current: float
    backward_current: float
    main_copper_loss: float
    auxiliary_copper_loss: float
    stator_copper_loss: float
    forward_rotor_copper_loss: float
    backward_rotor_copper_loss: float
    rotor_copper_loss: float
    core_loss: float
    stray_loss: float
    windage_loss: float
    electrical_power: float
    power_factor: float
    efficiency: float


def half_field_impedance(rotor_slip: float, circuit: MotorCircuit) -> complex:
    """``0.5 (R2/s + jX2) || 0.5 jXm`` [ohm] at rotor slip ``s`` [-] (forward: s, backward:
    2 - s), written with the rotor admittance so that ``s = 0`` is regular."""
    rotor_admittance = rotor_slip / (
        circuit.rotor_resistance + 1j * rotor_slip * circuit.rotor_leakage_reactance
    )
    return 0.5 / (rotor_admittance - 1j / circuit.magnetising_reactance)


def _winding_currents(circuit: MotorCircuit, slip: float) -> tuple[complex, ...]:
    """Main and auxiliary currents and the half-field impedances at ``slip`` [A, A, ohm, ohm]."""
    z_f = half_field_impedance(slip, circuit)
    z_b = half_field_impedance(2.0 - slip, circuit)
    z_main = circuit.main_resistance + 1j * circuit.main_leakage_reactance + z_f + z_b
    v = circuit.voltage
    if circuit.variant == "RSIR":
        return v / z_main, 0j, z_f, z_b
    a = circuit.aux_turns_ratio
    capacitor = 1.0 / (2.0 * math.pi * circuit.frequency * circuit.run_capacitance)
    z_aux = circuit.aux_resistance + 1j * (circuit.aux_leakage_reactance - capacitor)
    coupling = 1j * a * (z_f - z_b)
    a22 = z_aux + a * a * (z_f + z_b)
    det = z_main * a22 + coupling * coupling
    return v * (a22 + coupling) / det, v * (z_main - coupling) / det, z_f, z_b


def _air_gap(
    circuit: MotorCircuit, slip: float
) -> tuple[complex, complex, complex, complex, float, float, float]:
    """Main, auxiliary, forward and backward currents [A], forward and backward air-gap
    powers [W] and the shaft torque [N m] at ``slip`` [-]: the part of the operating
    point that the torque needs (the torque inverse calls only this)."""
    i_m, i_a, z_f, z_b = _winding_currents(circuit, slip)
    a = circuit.aux_turns_ratio
    i_f = 0.5 * (i_m - 1j * a * i_a)
    i_b = 0.5 * (i_m + 1j * a * i_a)
    p_f = 4.0 * z_f.real * abs(i_f) ** 2
    p_b = 4.0 * z_b.real * abs(i_b) ** 2
    w_s = circuit.synchronous_speed
    windage_torque = circuit.friction_windage_loss * (1.0 - slip) * w_s / (w_s * w_s)
    k = circuit.stray_loss_fraction
    net = (p_f - p_b) / w_s - windage_torque
    t_shaft = net / (1.0 + k) if net >= 0.0 else net / (1.0 - k)
    return i_m, i_a, i_f, i_b, p_f, p_b, t_shaft


def motor_operating_point_at_slip(circuit: MotorCircuit, slip: float) -> MotorOperatingPoint:
    """Operating point at forward slip ``slip`` [-], ``-1 < slip <= 1``.

    Returns
    -------
    MotorOperatingPoint
        Currents, powers, losses and torques (see :class:`MotorOperatingPoint`).
    """
    _require(-1.0 < slip <= 1.0, f"motor slip {slip}: must lie in (-1, 1] (0 <= speed < 2 w_s)")
    i_m, i_a, i_f, i_b, p_f, p_b, t_shaft = _air_gap(circuit, slip)
    v = circuit.voltage
    i_line = i_m + i_a + circuit.core_conductance * v
    w_s = circuit.synchronous_speed
    speed = (1.0 - slip) * w_s
    t_em = (p_f - p_b) / w_s
    windage_torque = circuit.friction_windage_loss * speed / (w_s * w_s)
    k = circuit.stray_loss_fraction
    cu_main = circuit.main_resistance * abs(i_m) ** 2
    cu_aux = circuit.aux_resistance * abs(i_a) ** 2
    p_in = v * i_line.real
    p_out = t_shaft * speed
    return MotorOperatingPoint(
        speed=speed,
        slip=slip,
        electromagnetic_torque=t_em,
        shaft_torque=t_shaft,
        shaft_power=p_out,
        forward_air_gap_power=p_f,
        backward_air_gap_power=p_b,
        main_current=abs(i_m),
        auxiliary_current=abs(i_a),
        line_current=abs(i_line),
        forward_current=abs(i_f),
        backward_current=abs(i_b),
        main_copper_loss=cu_main,
        auxiliary_copper_loss=cu_aux,
        stator_copper_loss=cu_main + cu_aux,
        forward_rotor_copper_loss=slip * p_f,
        backward_rotor_copper_loss=(2.0 - slip) * p_b,
        rotor_copper_loss=slip * p_f + (2.0 - slip) * p_b,
        core_loss=circuit.core_conductance * v * v,
        stray_loss=k * abs(t_shaft) * speed,
        windage_loss=windage_torque * speed,
        electrical_power=p_in,
        power_factor=p_in / (v * abs(i_line)),
        efficiency=p_out / p_in,
    )


def motor_operating_point(circuit: MotorCircuit, speed: float) -> MotorOperatingPoint:
    """Operating point at rotor speed ``speed`` [rad/s], ``0 <= speed < 2 omega_s``.

    Returns
    -------
    MotorOperatingPoint
        Currents, powers, losses and torques (see :class:`MotorOperatingPoint`).
    """
    w_s = circuit.synchronous_speed
    _require(
        math.isfinite(speed) and 0.0 <= speed < 2.0 * w_s,
        f"motor speed {speed} rad/s: must lie in [0, {2.0 * w_s:.6g}) (twice synchronous)",
    )
    return motor_operating_point_at_slip(circuit, (w_s - speed) / w_s)


def _shaft_torque(circuit: MotorCircuit, slip: float) -> float:
    return _air_gap(circuit, slip)[6]  # [N m]


def _refine_peak(circuit: MotorCircuit, low: float, high: float) -> tuple[float, float]:
    """Slip and value of the shaft-torque maximum inside ``[low, high]`` [-, N m]."""
    from scipy.optimize import minimize_scalar  # a heavy import, needed only here

    best = minimize_scalar(
        lambda s: -_shaft_torque(circuit, s),
        bounds=(low, high),
        method="bounded",
        options={"xatol": 1e-13 * max(high, 1e-3)},
    )
    return float(best.x), -float(best.fun)


def motor_breakdown(circuit: MotorCircuit) -> tuple[float, float]:
    """Breakdown (pull-out) point: the largest shaft torque for ``0 < s <= 1``.

    Returns
    -------
    tuple of float
        Breakdown slip [-] and breakdown shaft torque [N m].
    """
    slips = [_FIRST_SLIP * _SLIP_STEP**n for n in range(28)] + [1.0]
    torques = [_shaft_torque(circuit, s) for s in slips]
    top = max(range(len(slips)), key=torques.__getitem__)
    if top == len(slips) - 1:
        return 1.0, torques[-1]
    return _refine_peak(circuit, slips[max(top - 1, 0)], slips[top + 1])


def _slip_near(excess: Callable[[float], float], guess: float) -> float | None:
    """Root of ``excess`` by the secant method from a slip ``guess`` on the stable branch
    (0 < s < breakdown), or None where it does not settle there: the slope at the guess
    is not positive, the iterate leaves ``(guess / 4, 4 guess)``, or 12 steps pass."""
    if not 0.0 < guess < 1.0:
        return None
    s0, s1 = guess, guess * (1.0 + 1e-4)
    f0, f1 = excess(s0), excess(s1)
    if f1 <= f0:  # the torque falls with slip here: past breakdown
        return None
    for _ in range(12):
        if f1 == f0:
            break
        s2 = s1 - f1 * (s1 - s0) / (f1 - f0)
        if not 0.25 * guess < s2 < min(4.0 * guess, 1.0):
            return None
        s0, f0, s1 = s1, f1, s2
        if abs(s1 - s0) <= 1e-15 * s1:
            return s1
        f1 = excess(s1)
        if f1 == 0.0:
            return s1
    return None


def motor_operating_point_at_torque(
    circuit: MotorCircuit, load_torque: float, slip_guess: float | None = None
) -> MotorOperatingPoint:
    """Operating point on the stable branch where the shaft torque equals ``load_torque``.

    Parameters
    ----------
    circuit : MotorCircuit
        The motor.
    load_torque : float
        Mean torque the load needs at the shaft [N m].
    slip_guess : float, optional
        A slip near the answer on the stable branch (the last answer of a load that
        changes little, e.g. from one revolution to the next): the secant method from
        there, about 6 circuit evaluations instead of about 13; the bracketing march
        where it does not settle.

    Returns
    -------
    MotorOperatingPoint
        The point with ``0 < s < s_breakdown`` (a load below the no-load torque: ``s <= 0``).

    Raises
    ------
    ValueError
        If the load exceeds the breakdown torque (the motor stalls) or lies beyond the
        generating range.
    """
    _require(math.isfinite(load_torque), f"motor load torque {load_torque}: must be finite")

    def excess(s: float) -> float:
        return _shaft_torque(circuit, s) - load_torque

    if slip_guess is not None:
        near = _slip_near(excess, slip_guess)
        if near is not None:
            return motor_operating_point_at_slip(circuit, near)
    low, high = 0.0, _FIRST_SLIP
    if excess(0.0) > 0.0:
        high, low = 0.0, -_FIRST_SLIP
        while excess(low) > 0.0:
            _require(low > -0.5, f"motor load torque {load_torque} N m: beyond generating range")
            high, low = low, low * 2.0
    else:
        # from the torque's slope near synchronism: on the rising branch the torque is
        # concave in slip, so the linear estimate lies below the root and the march
        # below starts one step short of it instead of at _FIRST_SLIP
        previous = excess(0.0)
        probe = excess(_LINEAR_SLIP)
        if probe >= 0.0:
            high = _LINEAR_SLIP
        else:
            estimate = _LINEAR_SLIP * previous / (previous - probe)
            low, previous = _LINEAR_SLIP, probe
            high = min(max(estimate, _LINEAR_SLIP * _SLIP_STEP), 1.0)
        while high > _LINEAR_SLIP:
            current = excess(high)
            if current >= 0.0:
                break
            if current < previous or high >= 1.0:  # past the peak, or standstill reached
                low /= _SLIP_STEP  # the peak may lie before the last slip
                peak_slip, peak = _refine_peak(circuit, low, high)
                _require(
                    peak >= load_torque,
                    f"motor load torque {load_torque:.6g} N m exceeds the breakdown torque "
                    f"{peak:.6g} N m (at slip {peak_slip:.4g}): the motor stalls",
                )
                high = peak_slip
                break
            low, previous, high = high, current, min(high * _SLIP_STEP, 1.0)
    from scipy.optimize import brentq  # a heavy import, needed only here

    slip = brentq(excess, low, high, xtol=1e-15, rtol=1e-15, maxiter=200)
    return motor_operating_point_at_slip(circuit, float(slip))


def motor_loss_columns(point: MotorOperatingPoint) -> dict[str, float]:
    """Report columns of a motor operating point, units in the names.

    Returns
    -------
    dict of str to float
        Electrical power, efficiency, power factor, currents, losses, slip, speed.
    """
    return {
        "motor_electrical_power [W]": point.electrical_power,
        "motor_shaft_power [W]": point.shaft_power,
        "motor_efficiency [-]": point.efficiency,
        "motor_power_factor [-]": point.power_factor,
        "motor_current [A]": point.line_current,
        "motor_main_current [A]": point.main_current,
        "motor_auxiliary_current [A]": point.auxiliary_current,
        "motor_stator_copper_loss [W]": point.stator_copper_loss,
        "motor_main_copper_loss [W]": point.main_copper_loss,
        "motor_auxiliary_copper_loss [W]": point.auxiliary_copper_loss,
        "motor_rotor_copper_loss [W]": point.rotor_copper_loss,
        "motor_core_loss [W]": point.core_loss,
        "motor_stray_loss [W]": point.stray_loss,
        "motor_windage_loss [W]": point.windage_loss,
        "motor_slip [-]": point.slip,
        "motor_speed [rad/s]": point.speed,
    }
