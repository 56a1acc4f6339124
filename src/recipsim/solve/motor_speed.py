"""The constant-speed cycle at the motor's own speed (``options.speed = "motor_slip"``).

An induction motor turns slower the more torque it carries. With ``options.speed =
"case"`` the cycle runs at ``operating_point.shaft_speed`` and the equivalent circuit's
slip at the cycle's load only gives the reported ``motor_speed_at_load``. With
``"motor_slip"`` the speed is a fixed point instead: the cycle is solved at a speed, its
mean load torque ``T = P_shaft / omega`` (drive work plus ``mean`` friction) gives the
circuit's speed at that torque, and the cycle is solved again there, until the speed
changes by less than ``solver.cycle_tolerance`` (relative).

The load torque rises slowly with speed while the circuit's speed falls steeply with
torque near synchronism, so the plain iteration contracts by about
``|dT/domega| / |dT_motor/domega|`` (a few per cent on a household RSIR motor): two or
three solves, each after the first started from the previous periodic state.

Where the cycle's response jumps with speed (a valve that flutters on a period of two
revolutions above a speed and not below it), the load torque jumps too and the iteration
would swing between the two sides for ever. The speeds solved at bracket the balance
(those whose load asks for more speed below it, the others above); a step that reverses
the last one without halving it is itself halved from then on, and the speed is settled
once the bracket is narrower than the tolerance: the torques balance at the jump, within
that bracket.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from recipsim.case.case import Case
from recipsim.errors import SolverError
from recipsim.model.build import Model, WorkingModel
from recipsim.model.loss_sources import (
    constant_speed_mean_friction,
    friction_oil_temperature,
    revolution_shaft_power,
)
from recipsim.physics.friction_models import FRICTION_MODELS
from recipsim.physics.motor_circuit import motor_operating_point_at_torque
from recipsim.solve.drive import build_model_for
from recipsim.solve.periodic import PeriodicSolution, solve_periodic

#: Solves of the cycle before the speed iteration gives up.
MAX_SPEED_SOLVES = 16


@dataclass(frozen=True)
class MotorSpeedSolution:
    """The periodic cycle at the motor's speed at load.

    Attributes
    ----------
    case : Case
        The case with ``operating_point.shaft_speed`` at the speed found [rad/s].
    solution : PeriodicSolution
        The periodic solution at that speed.
    speeds : tuple of float
        The speeds solved at, in order [rad/s].
    residual : float
        Relative change of the speed at the last solve [-].
    revolutions : int
        Revolutions integrated over all the solves.
    """

    case: Case
    solution: PeriodicSolution
    speeds: tuple[float, ...]
    residual: float
    revolutions: int


def motor_speed_at_load(model: Model, solution: PeriodicSolution) -> float:
    """Speed [rad/s] at which the equivalent circuit carries the load torque of ``solution``.

    The load torque is the revolution's shaft power (drive work, plus the ``mean``
    friction at the model's speed) over its mean speed.

    Raises
    ------
    SolverError
        If that torque exceeds the motor's breakdown torque (the motor stalls).
    """
    case = model.case
    circuit = case.motor_circuit
    assert circuit is not None
    rev = solution.final
    friction = 0.0
    if FRICTION_MODELS[
        case.options.friction
    ].mean_laws:  # the films at the oil temperature the cycle ran with
        oil = friction_oil_temperature(solution.model)
        friction = constant_speed_mean_friction(case, oil_temperature=oil)
    shaft, _ = revolution_shaft_power(model, rev.y_end, rev.duration, friction)
    omega = 2.0 * math.pi / rev.duration
    try:
        point = motor_operating_point_at_torque(circuit, shaft / omega)
    except ValueError as exc:
        raise SolverError(
            f"options.speed = 'motor_slip': {exc} (load {shaft:.4g} W at "
            f"{omega * 30.0 / math.pi:.1f} rpm)"
        ) from None
    return float(point.speed)


def _warm_started(model: Model, old: PeriodicSolution) -> WorkingModel:
    """A working copy of ``model`` started from the periodic state ``old`` of the
    previous speed: the cylinder's state at the start angle and the discharge plenum
    (and the thermal network's boundary, where there is one)."""
    old_model = old.model
    model = model.for_solve()
    model.y0[:] = old.final.y_end
    model.mode0[:] = old.final.mode_end
    model.set_discharge_enthalpy(old_model.discharge.enthalpy)
    if model.thermal is not None and old_model.thermal is not None:
        model.thermal.continue_from(model, old_model.thermal)
    return model


def solve_at_motor_speed(case: Case) -> MotorSpeedSolution:
    """Periodic cycle of ``case`` at the equivalent circuit's speed at load.

    Starts at ``operating_point.shaft_speed`` (the nameplate speed is a good guess) and
    iterates the speed until its relative change is below ``solver.cycle_tolerance``.

    Raises
    ------
    SolverError
        If a solve fails, the load stalls the motor, or the speed does not settle in
        :data:`MAX_SPEED_SOLVES` solves.
    """
    tolerance = case.solver.cycle_tolerance
    speed = case.operating_point.shaft_speed
    speeds: list[float] = []
    revolutions = 0
    previous: PeriodicSolution | None = None
    below, above = 0.0, math.inf  # the speeds known to be below and above the balance
    relaxation = 1.0
    last_step = 0.0
    for _ in range(MAX_SPEED_SOLVES):
        current = case.with_({"operating_point.shaft_speed": speed})
        model: Model = build_model_for(current)
        if previous is not None:
            model = _warm_started(model, previous)
        solution = solve_periodic(model)
        revolutions += solution.revolutions
        speeds.append(speed)
        following = motor_speed_at_load(model, solution)
        residual = abs(following - speed) / speed
        if following > speed:
            below = max(below, speed)
        else:
            above = min(above, speed)
        if residual < tolerance or (above - below) / speed < tolerance:
            return MotorSpeedSolution(current, solution, tuple(speeds), residual, revolutions)
        step = following - speed
        if step * last_step < 0.0 and abs(step) > 0.5 * abs(last_step):
            relaxation *= 0.5  # reversed without shrinking: a jump between the two
        last_step = step
        previous = solution
        speed = speed + relaxation * step
        if not below < speed < above:  # outside the bracket: its middle
            speed = 0.5 * (below + above)
    raise SolverError(
        f"options.speed = 'motor_slip': the speed did not settle in {MAX_SPEED_SOLVES} solves "
        f"(last {speeds[-1] * 30.0 / math.pi:.2f} rpm, relative change {residual:.2e})"
    )
