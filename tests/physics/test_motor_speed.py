"""The constant-speed cycle at the induction motor's speed at load (``options.speed =
"motor_slip"``, :mod:`recipsim.solve.motor_speed`).

- The speed found is a fixed point: the equivalent circuit, asked independently for its
  speed at the cycle's load torque (shaft power over speed), returns the speed the cycle
  ran at, to the iteration's tolerance (``solver.cycle_tolerance``, relative) times a few
  (the last solve's own torque moves its circuit speed by the residual left).
- Physics of a loaded induction motor: below synchronous speed (3000 rpm, two poles at
  50 Hz), and the heavier the load the lower the speed: at 55 C condensing the load grows
  with the evaporating temperature, so the speed falls from -35 to -10 C.
- The plain iteration contracts fast (the circuit's torque-speed line is steep near
  synchronism): at most four solves.
- The option is refused where it has no meaning (a lossless motor).
"""

from __future__ import annotations

import math

import pytest

from recipsim.api import load_case
from recipsim.errors import CaseError
from recipsim.model.loss_sources import (
    constant_speed_mean_friction,
    friction_oil_temperature,
    revolution_shaft_power,
)
from recipsim.physics.motor_circuit import motor_operating_point_at_torque
from recipsim.pipeline import simulate_case
from recipsim.solve.drive import build_model_for
from recipsim.solve.motor_speed import solve_at_motor_speed

RPM = 30.0 / math.pi


@pytest.fixture(scope="module")
def tles():
    return load_case("tles5.7kk3_r600a")


@pytest.fixture(scope="module")
def by_evaporating(tles):
    return {
        te: solve_at_motor_speed(tles.with_({"operating_point.evaporating_temperature": te}))
        for te in ("-35 degC", "-10 degC")
    }


def test_speed_is_the_circuits_speed_at_the_cycles_load(by_evaporating):
    for found in by_evaporating.values():
        case, solution = found.case, found.solution
        model = build_model_for(case)  # the same case: model.case and layouts for the totals
        rev = solution.final
        # the mean friction with its films at the oil temperature the cycle ran with
        oil = friction_oil_temperature(solution.model)
        assert oil is not None
        friction = constant_speed_mean_friction(case, oil_temperature=oil)
        shaft, _ = revolution_shaft_power(model, rev.y_end, rev.duration, friction)
        omega = 2.0 * math.pi / rev.duration
        assert omega == pytest.approx(case.operating_point.shaft_speed, rel=1e-9)
        assert case.motor_circuit is not None
        circuit_speed = motor_operating_point_at_torque(case.motor_circuit, shaft / omega).speed
        assert circuit_speed == pytest.approx(omega, rel=3.0 * case.solver.cycle_tolerance)
        assert len(found.speeds) <= 4
        assert found.residual < case.solver.cycle_tolerance


def test_heavier_load_turns_slower_below_synchronous(by_evaporating):
    light = by_evaporating["-35 degC"].case.operating_point.shaft_speed * RPM
    heavy = by_evaporating["-10 degC"].case.operating_point.shaft_speed * RPM
    assert heavy < light < 3000.0
    assert light - heavy > 10.0  # tens of rpm of slip between the two loads


def test_summary_reports_the_speed_it_ran_at(tles):
    row = simulate_case(tles).row
    assert row["motor_speed_at_load [rpm]"] == pytest.approx(
        row["shaft_speed [rpm]"], rel=3.0 * tles.solver.cycle_tolerance
    )
    assert row["shaft_speed [rpm]"] != pytest.approx(2900.0, abs=1.0)  # not the first guess
    # the slip it runs at, against the two-pole 50 Hz synchronous 3000 rpm (the speed's
    # relative tolerance is the slip's absolute one)
    assert row["motor_slip [-]"] == pytest.approx(
        1.0 - row["shaft_speed [rpm]"] / 3000.0, abs=3.0 * tles.solver.cycle_tolerance
    )
    assert 0.005 < row["motor_slip [-]"] < 0.08  # a loaded small induction motor


def test_motor_slip_needs_the_equivalent_circuit():
    with pytest.raises(CaseError, match="options.speed"):
        load_case("reference_r134a_lbp_ideal", {"options.speed": "motor_slip"})


def _fake_loop(monkeypatch, circuit_speed):
    """``solve_at_motor_speed`` with the cycle replaced by ``circuit_speed(omega)``: the
    circuit's speed [rad/s] at the load of a cycle run at ``omega``; returns the calls."""
    import recipsim.solve.motor_speed as ms

    class _Solution:
        revolutions = 1

    calls: list[float] = []
    monkeypatch.setattr(ms, "build_model_for", lambda case: case)
    monkeypatch.setattr(ms, "_warm_started", lambda model, old: model)
    monkeypatch.setattr(ms, "solve_periodic", lambda model: _Solution())

    def at_load(model, solution):
        omega = model.operating_point.shaft_speed
        calls.append(omega)
        return circuit_speed(omega)

    monkeypatch.setattr(ms, "motor_speed_at_load", at_load)
    return calls


def test_a_load_that_jumps_with_speed_is_bracketed_to_the_jump(monkeypatch, tles):
    """The cycle's load jumps at 300 rad/s (a valve fluttering on two revolutions above
    it): the circuit's speed is 300.003 rad/s below the jump and 299.997 above, so plain
    iteration swings between them for ever. The bracket closes on the jump within the
    tolerance, in fewer solves than the limit."""
    from recipsim.solve.motor_speed import MAX_SPEED_SOLVES

    jump = 300.0

    def circuit_speed(omega: float) -> float:  # slope -0.03: the steep circuit
        return jump - 0.03 * (omega - jump) + (0.003 if omega < jump else -0.003)

    case = tles.with_({"operating_point.shaft_speed": 2900 / RPM, "solver.cycle_tolerance": 1e-6})
    calls = _fake_loop(monkeypatch, circuit_speed)
    found = solve_at_motor_speed(case)
    speed = found.case.operating_point.shaft_speed
    assert abs(speed - jump) / jump < 2e-6  # within the tolerance (and the last half-step)
    assert len(calls) < MAX_SPEED_SOLVES


def test_a_smooth_load_still_takes_the_plain_steps(monkeypatch, tles):
    """Without a jump the iteration is the plain one, contracting by the slope 0.03 a
    solve: from 2900 rpm to 1e-6 in four solves, not slowed by the bracket."""

    def circuit_speed(omega: float) -> float:
        return 305.0 - 0.03 * (omega - 305.0)

    case = tles.with_({"operating_point.shaft_speed": 2900 / RPM, "solver.cycle_tolerance": 1e-6})
    calls = _fake_loop(monkeypatch, circuit_speed)
    found = solve_at_motor_speed(case)
    assert abs(found.case.operating_point.shaft_speed - 305.0) / 305.0 < 1e-6
    assert len(calls) <= 4
