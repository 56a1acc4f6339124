"""Shooting on the n-revolution map (solve/subharmonic.py): on a synthetic revolution map
with a known period-2 attractor, and on a physical period-2 response (a bouncing
discharge reed that is still open at the 270 deg section, at the end of this file).

No shipped case settles on a period-n orbit (docs/sweeps.md, "Statuses"): their reeds
are on their seats at the section, so a revolution carries over only the gas state and
the discharge plenum's enthalpy, whose multipliers are 0.41 and below. The synthetic
tests drive the solver with a revolution integrator of the real reference model whose
gas temperature at the section follows the cubic map

    x -> -lam x + c x^3,  x = (T / T_ref - 1) / 0.01,  lam = 1.95, c = 0.95

(every other state and the cycle's quadratures those of the converged reference
revolution). Its fixed point x = 0 is unstable (multiplier -1.95); its period-2 orbit
x = +-1 (T = T_ref (1 +- 1 %)) is stable, with multiplier (2 lam - 3)^2 = 0.81 over two
revolutions: revolution iteration approaches it geometrically and slowly, and Newton
on the one-revolution map would find the unstable x = 0.
"""

import dataclasses
import math

import numpy as np
import pytest

from recipsim.api import load_case, simulate
from recipsim.model.build import build_model
from recipsim.physics.thermo import cylinder as cyl
from recipsim.solve.periodic import solve_revolutions
from recipsim.solve.residual import closures, state_change
from recipsim.solve.revolution import integrate_revolution
from recipsim.solve.subharmonic import candidate_period, period_change

LAM, C, SCALE = 1.95, 0.95, 0.01


class CubicMap:
    """Revolution integrator: the reference revolution with T mapped by the cubic map."""

    def __init__(self, model):
        y, mode, h = model.y0.copy(), model.mode0.copy(), model.period * 1e-4
        for _ in range(6):  # the converged reference revolution as the template
            rev, h = integrate_revolution(model, y, mode, h, 360)
            y, mode = rev.y_end.copy(), rev.mode_end.copy()
        # its balances closed exactly (a real revolution closes them to about 3e-5, which
        # the cycle residual, with the closures, would not pass at a tolerance of 1e-8)
        q = rev.y_end
        m_leak = q[cyl.Q_MLEAK_OUT] - q[cyl.Q_MLEAK_IN]
        q[cyl.Q_MDIS_OUT] = q[cyl.Q_MSUC_IN] - q[cyl.Q_MSUC_OUT] + q[cyl.Q_MDIS_IN] - m_leak
        h_out = q[cyl.Q_HDIS_OUT] - q[cyl.Q_HDIS_IN] + q[cyl.Q_HLEAK_OUT] - q[cyl.Q_HLEAK_IN]
        q[cyl.Q_HEAT] = h_out - (q[cyl.Q_HSUC_IN] - q[cyl.Q_HSUC_OUT]) - q[cyl.Q_WORK]
        assert np.allclose(closures(model, q), 0.0, atol=1e-14)
        self.template = rev
        self.t_ref = rev.y_end[cyl.Y_T]
        self.calls = 0

    def x(self, y):
        return (y[cyl.Y_T] / self.t_ref - 1.0) / SCALE

    def __call__(self, model, y, mode, h, samples):
        self.calls += 1
        x = self.x(y)
        y_end = self.template.y_end.copy()
        y_end[: model.n_err] = y[: model.n_err]
        y_end[cyl.Y_T] = self.t_ref * (1.0 + SCALE * (-LAM * x + C * x**3))
        rev = dataclasses.replace(self.template, y_start=y.copy(), y_end=y_end)
        rev.duration = self.template.duration
        return rev, h


@pytest.fixture()
def model():
    case = load_case("reference_r134a_lbp_ideal", {"solver.max_revolutions": 400})
    return build_model(case).for_solve()  # the fake integrator runs it directly


def _start_at(model, fake, x0):
    model.y0 = fake.template.y_end.copy()
    model.mode0 = fake.template.mode_end.copy()
    model.y0[cyl.Y_T] = fake.t_ref * (1.0 + SCALE * x0)


def test_shooting_on_the_two_revolution_map_finds_the_period_2_orbit(model):
    fake = CubicMap(model)
    _start_at(model, fake, 0.6)
    sol = solve_revolutions(model, hand_over=True, integrate=fake)
    tol = model.case.solver.cycle_tolerance
    assert sol.converged and sol.period_revolutions == 2
    assert sol.method == "shooting on the 2-revolution map"
    # the orbit x = +-1 (analytic): states that repeat over two revolutions to the
    # tolerance are within tol / (1 - 0.81) of it (relative T), x within that / SCALE
    end = sol.final.y_end.copy()
    assert abs(abs(fake.x(end)) - 1.0) < tol / (1.0 - (2 * LAM - 3) ** 2) / SCALE
    # two revolutions from the end close within the tolerance, one does not (2 % in T)
    one, _ = fake(model, end, sol.final.mode_end, 0.0, 0)
    two, _ = fake(model, one.y_end.copy(), one.mode_end, 0.0, 0)
    assert period_change(model, [one, two]) < tol
    assert state_change(model, one) == pytest.approx(2 * SCALE, rel=0.02)


def test_revolution_iteration_alone_needs_many_more_revolutions():
    """At cycle tolerance 1e-8 revolution iteration reaches the period-2 test (end states
    repeating within the tolerance) only after the orbit's 0.81 per two revolutions has
    shrunk the error (relative T) from about 3e-4 after the first revolutions to
    1e-8 / (1 - 0.81) = 5e-8: 2 ln(5e-8 / 3e-4) / ln(0.81) = 83 revolutions (measured 88);
    shooting on the two-revolution map (quadratic) needs a fraction."""
    runs = []
    for hand_over in (False, True):
        case = load_case(
            "reference_r134a_lbp_ideal",
            {"solver.max_revolutions": 400, "solver.cycle_tolerance": 1e-8},
        )
        model = build_model(case).for_solve()
        fake = CubicMap(model)
        _start_at(model, fake, 0.6)
        runs.append(solve_revolutions(model, hand_over=hand_over, integrate=fake))
    plain, shot = runs
    assert plain.converged and plain.period_revolutions == 2
    assert shot.converged and shot.period_revolutions == 2
    assert plain.revolutions > 2 * math.log(5e-8 / 3e-4) / math.log(0.81)
    assert shot.revolutions < plain.revolutions / 4, (shot.revolutions, plain.revolutions)


def test_a_candidate_period_is_the_one_the_end_states_approach():
    ref = np.array([1.0, 1.0])
    x = 0.6
    ends = []
    for _ in range(6):
        x = -LAM * x + C * x**3
        ends.append(np.array([1.0 + SCALE * x, 2.0]))
    assert candidate_period(ends, ref) == 2
    settled = [np.array([1.0 + 1e-3 * 0.5**k, 2.0]) for k in range(6)]
    assert candidate_period(settled, ref) == 1  # decaying monotonically: period 1


#: A physical period-2 response (found by a sweep of speeds and reed restitution): the
#: AC compressor (r32_ac) at a low pressure ratio (15 C / 30 C, 1.6), where the discharge
#: reed opens at 256 deg, before the 270 deg section, so its motion carries over from
#: one revolution to the next; both reeds lightly damped (0.001) and the discharge reed
#: bouncing (restitution 0.9) at 5000 rpm. (At 4000 and 6000 rpm, or with restitution
#: 0.3, it converges on period 1.)
PERIOD_TWO = {
    "operating_point.evaporating_temperature": "15 degC",
    "operating_point.condensing_temperature": "30 degC",
    "operating_point.suction_temperature": "18.3 degC",
    "operating_point.liquid_temperature": "20 degC",
    "operating_point.shaft_speed": "5000 rpm",
    "valves.discharge.damping_ratio": 0.001,
    "valves.suction.damping_ratio": 0.001,
    "valves.discharge.restitution": 0.9,
    "solver.envelope": "ignore",
}


def _two_revolutions(model, y, mode):
    revs, h = [], model.period * 1e-4
    for _ in range(2):
        rev, h = integrate_revolution(model, y, mode, h, model.case.solver.samples_per_revolution)
        revs.append(rev)
        y, mode = rev.y_end.copy(), rev.mode_end.copy()
    return revs


def test_a_bouncing_discharge_reed_settles_on_period_two():
    """End to end (``solver.periodic = "auto"``): one-revolution shooting finds the
    period-1 orbit, but it repels (a Floquet multiplier of -1.23, below -1.05), so the
    iteration goes on and settles on period 2. From the reported state two revolutions
    close within the cycle tolerance, one does not (1.2e-3, 12 tolerances)."""
    result = simulate(load_case("r32_ac", PERIOD_TWO))
    s, sol = result.summary, result.solution
    assert s["status"] == "subharmonic" and "every 2 revolutions" in s["status_message"]
    assert sol.period_revolutions == 2
    model, tol = sol.model, sol.model.case.solver.cycle_tolerance
    revs = _two_revolutions(model, sol.final.y_end.copy(), sol.final.mode_end.copy())
    assert period_change(model, revs) < tol
    assert state_change(model, revs[0]) > 5 * tol
    assert abs(s["mass_balance_residual [-]"]) < 1e-3
    assert abs(s["energy_balance_residual [-]"]) < 1e-3


def test_shooting_on_the_two_revolution_map_finds_the_physical_orbit():
    """solve_subharmonic from the state after 6 revolutions of iteration (before it has
    settled): the orbit it returns closes over two revolutions within the tolerance and
    not over one."""
    import time

    from recipsim.solve.revolution import _Tally, discharge_enthalpy
    from recipsim.solve.subharmonic import solve_subharmonic

    model = build_model(load_case("r32_ac", PERIOD_TWO)).for_solve()
    y, mode, h = model.y0.copy(), model.mode0.copy(), model.period * 1e-4
    for _ in range(6):
        rev, h = integrate_revolution(model, y, mode, h, model.case.solver.samples_per_revolution)
        model.set_discharge_enthalpy(discharge_enthalpy(model, rev))
        y, mode = rev.y_end.copy(), rev.mode_end.copy()
    sol = solve_subharmonic(model, 2, (rev, h), [], _Tally(), time.perf_counter())
    assert sol is not None and sol.converged and sol.period_revolutions == 2
    assert sol.method == "shooting on the 2-revolution map"
    model = sol.model  # the working copy the solve moved (its discharge plenum)
    tol = model.case.solver.cycle_tolerance
    revs = _two_revolutions(model, sol.final.y_end.copy(), sol.final.mode_end.copy())
    assert period_change(model, revs) < tol
    assert state_change(model, revs[0]) > 5 * tol


def test_a_tolerance_below_the_noise_is_not_taken_for_a_subharmonic() -> None:
    """``cycle_tolerance = 1e-12`` on the reference case: the residual stalls near 2e-7
    (the revolution's closures) and the end states jitter at round-off; the run is
    reported not converged, never as a period of n revolutions by a chance match."""
    from helpers import REFERENCE
    from recipsim.case.load import load_case
    from recipsim.pipeline import simulate_row

    case = load_case(
        REFERENCE,
        {
            "solver.cycle_tolerance": 1e-12,
            "solver.periodic": "revolutions",
            "operating_point.evaporating_temperature": "-30 degC",
        },
    )
    row = simulate_row(case)
    assert row["status"] == "not_converged" and not row["converged [-]"]
    assert row["periodic_method"] == "revolutions" and "stalled" in row["status_message"]


#: A TLES10KK.3 point (a trial of a family calibration) whose thermally coupled cycle at
#: 2918.945 rpm settles on a period of several revolutions: the residual falls to 4e-6,
#: then one-revolution shooting lands on an orbit whose states alternate by about 4e-4.
SHELL_PERIOD_TWO = {
    "operating_point.standard": "EN12900",
    "operating_point.evaporating_temperature": "-15 degC",
    "operating_point.condensing_temperature": "55 degC",
    "operating_point.suction_temperature": "32 degC",
    "operating_point.liquid_temperature": "55 degC",
    "operating_point.ambient_temperature": "32 degC",
    "geometry.other_dead_volume": "4.53e-8 m^3",
    "leakage.radial_clearance": "1.15e-5 m",
    "solver.cycle_tolerance": 1e-6,
    "solver.max_revolutions": 400,
    "options.speed": "case",
    "operating_point.shaft_speed": "2918.945272 rpm",
}


def test_shooting_that_lands_on_a_period_two_orbit_ends_as_revolution_iteration_does():
    """Revolution iteration alone settles this case on a period of n > 1 revolutions (the
    premise, checked first). With ``auto`` the hand-over to one-revolution shooting used to
    chord-step for its whole budget (400 revolutions, unconverged at 4.5e-4): Newton now
    gives up when the residual stalls, and the revolutions that follow end on a period of
    n > 1 revolutions, converged, in a fifth of the budget."""
    from recipsim.solve.drive import build_model_for
    from recipsim.solve.periodic import solve_periodic

    plain = load_case("tles10kk3_r600a", {**SHELL_PERIOD_TWO, "solver.periodic": "revolutions"})
    premise = solve_periodic(build_model_for(plain))
    assert premise.converged and premise.period_revolutions > 1

    auto = load_case("tles10kk3_r600a", {**SHELL_PERIOD_TWO, "solver.periodic": "auto"})
    solution = solve_periodic(build_model_for(auto))
    assert solution.converged and solution.period_revolutions > 1
    assert solution.revolutions < 40 * 2  # 46 here; the budget is 400
    assert "fell back to revolutions" in solution.method
