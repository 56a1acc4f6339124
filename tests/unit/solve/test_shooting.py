"""Periodic steady state by shooting (Newton on the one-revolution map) against
revolution iteration, closed forms and an independent extra revolution.

Tolerances: a converged run's last revolution changes every state by less than
``tol`` (the cycle tolerance) relative to its residual reference. For a fixed-point
iteration contracting at rate ``rho`` that puts the state within ``tol / (1 - rho)``
of the periodic state, so two solvers that both converged agree within
``(tol_a + tol_b) / (1 - rho)``; ``rho`` is measured from the revolution history.
Undamped runs use ``rtol = 1e-7``: at the default 1e-6 the end state of an undamped
revolution jumps by ~1e-4 of the vibration amplitude with the integrator's step
sequence (the module docstring of :mod:`recipsim.solve.shooting`).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from helpers import CASES, REFERENCE
from recipsim.case.load import load_case
from recipsim.errors import CaseError
from recipsim.model.build import build_model
from recipsim.physics.mechanics import layout as mlay
from recipsim.physics.mechanics.layout import BEARING_NAMES
from recipsim.results.tables import cycle_table, summary
from recipsim.solve.newton import newton_fixed_point
from recipsim.solve.periodic import (
    cycle_residual,
    integrate_revolution,
    residual_reference,
    solve_periodic,
    state_change,
)
from recipsim.solve.shooting import shooting_unknowns

PAPER = CASES / "paper_tabulated.toml"
CONSTANT = ['options.drive="constant_speed"']
UNDAMPED_RTOL = ["solver.rtol=1e-7"]
TOL = 1e-4  # the cases' cycle tolerance


def damping(factor: float) -> list[str]:
    """Every bearing's damping times ``factor`` (0: undamped)."""
    case = load_case(PAPER)
    return [
        f"bearings.{name}.damping={b.damping * factor}"
        for name, b in zip(BEARING_NAMES, case.mechanism.bearings, strict=True)
    ]


def solve(path, overrides):
    return solve_periodic(build_model(load_case(path, overrides)))


def rate(history: list[float]) -> float:
    """Contraction per revolution of revolution iteration: geometric mean over its
    last revolutions (up to 9; the residual of a pair of complex multipliers beats)."""
    n = min(9, len(history) - 2)
    return float((history[-1] / history[-1 - n]) ** (1.0 / n))


def rms(row: dict) -> np.ndarray:
    return np.array([row[f"bearing_rms_{b} [N]"] for b in BEARING_NAMES])


def controlled_difference(sol_a, sol_b) -> float:
    """Largest difference of the error-controlled start states, relative to the
    cycle residual's reference."""
    model = sol_a.model
    ref = residual_reference(model, sol_a.final)
    on = model.scale[: model.n_err] > 0.0
    d = np.abs(sol_a.final.y_start[: model.n_err] - sol_b.final.y_start[: model.n_err])
    return float(np.max(d[on] / ref[on]))


# ------------------------------------------------------------------------ damped cases


@pytest.mark.parametrize(
    ("path", "overrides"),
    [(REFERENCE, []), (PAPER, CONSTANT + damping(0.01))],
    ids=["cylinder_reference", "mechanism_damping_1pc"],
)
def test_damped_case_same_periodic_state_both_ways(path, overrides):
    """Both solvers converge to the same periodic state and summary. The cylinder's
    slowest multiplier is 0.41, the mechanism's with 1 % damping ~0.8: bound
    (tol_rev + tol_shoot) / (1 - rho) with rho measured."""
    rev = solve(path, [*overrides, 'solver.periodic="revolutions"'])
    shot = solve(path, [*overrides, 'solver.periodic="shooting"'])
    assert rev.converged and shot.converged
    assert rev.method == "revolutions" and shot.method == "shooting"
    assert shot.newton_iterations >= 1 and shot.jacobians >= 1
    # Jacobian columns are counted in the revolutions
    assert (
        shot.revolutions
        > shot.jacobian_revolutions
        >= len(shooting_unknowns(shot.model, shot.final.mode_start))
    )
    rho = rate(rev.residual_history)
    assert 0.0 < rho < 1.0
    bound = (rev.residual + shot.residual) / (1.0 - rho)
    assert controlled_difference(rev, shot) < 2.0 * bound
    # summary metrics: the totals of each final revolution follow the state
    row_r, row_s = summary(rev, cycle_table(rev)), summary(shot, cycle_table(shot))
    keys = ["shaft_power [W]"]
    keys += (
        ["discharge_mass_flow [kg/s]", "indicated_power [W]", "discharge_temperature [K]"]
        if path == REFERENCE
        else []
    )
    for key in keys:
        assert row_s[key] == pytest.approx(row_r[key], rel=4.0 * bound), key
    if path != REFERENCE:
        np.testing.assert_allclose(rms(row_s), rms(row_r), rtol=4.0 * bound)


# ----------------------------------------------------------------------- undamped cases


@pytest.fixture(scope="module")
def undamped():
    """The paper case, undamped bearings, constant speed: shooting."""
    return solve(PAPER, CONSTANT + damping(0.0) + UNDAMPED_RTOL + ['solver.periodic="shooting"'])


def test_undamped_revolutions_never_settle():
    """Revolution iteration of undamped bearings does not converge (|mu| = 1)."""
    sol = solve(
        PAPER,
        CONSTANT
        + damping(0.0)
        + UNDAMPED_RTOL
        + ['solver.periodic="revolutions"', "solver.max_revolutions=30"],
    )
    assert not sol.converged and sol.revolutions == 30
    assert min(sol.residual_history[-10:]) > 10 * TOL


def test_undamped_shooting_is_periodic_checked_independently(undamped):
    """Shooting converges; one more revolution integrated from its end state repeats
    every state to the tolerance and its totals match the reported revolution."""
    sol = undamped
    assert sol.converged and sol.method == "shooting"
    assert sol.residual < TOL and sol.revolutions <= 40
    model = sol.model
    extra, _ = integrate_revolution(
        model, sol.final.y_end.copy(), sol.final.mode_end.copy(), model.period * 1e-4, 720
    )
    assert state_change(model, extra) < TOL
    assert cycle_residual(model, extra, sol.final) < TOL
    # the response is a real vibration: orbit radii well above the quasi-static ones
    assert np.max(np.abs(sol.final.samples[:, mlay.Y_ROTOR_X])) > 1e-6


def test_auto_hands_undamped_runs_to_shooting():
    """``auto`` runs revolutions, sees them not settle and finishes by shooting."""
    sol = solve(PAPER, CONSTANT + damping(0.0) + UNDAMPED_RTOL)
    assert sol.converged and sol.method == "shooting"
    assert sol.residual_history[0] >= 1.0 and len(sol.residual_history) >= 5


def test_light_damping_tends_to_the_undamped_response(undamped):
    """Continuity in the damping: the RMS bearing loads at 0.1 % and 0.01 % of the
    case's damping approach the undamped ones (measured largest gaps 12 % and 0.23 %,
    and 72 % at 1 %: near-resonant modes respond as 1 / |(1 - r^2) + 2 i zeta r|, whose
    gap to the undamped response falls like zeta^2 away from resonance)."""
    base = rms(summary(undamped, cycle_table(undamped)))
    gaps = []
    for factor in (1e-3, 1e-4):
        sol = solve(PAPER, CONSTANT + damping(factor) + UNDAMPED_RTOL)
        assert sol.converged
        gaps.append(np.max(np.abs(rms(summary(sol, cycle_table(sol))) / base - 1.0)))
    assert gaps[1] < 0.1 * gaps[0], gaps
    assert gaps[1] < 0.01, gaps


# ------------------------------------------------------------------------- closed form


def test_newton_finds_the_forced_undamped_oscillator_response():
    """x'' + wn^2 x = a cos(W t), undamped: the periodic response is
    x = a / (wn^2 - W^2) cos(W t). Its one-period map (integrated by scipy) has
    multipliers on the unit circle, so plain iteration only circles; Newton lands on
    the closed form (to the integration tolerance)."""
    wn, w, a = 2.7, 1.0, 1.0
    period = 2.0 * math.pi / w

    def one_period(z: np.ndarray) -> tuple[np.ndarray, None]:
        sol = solve_ivp(
            lambda t, y: [y[1], -(wn**2) * y[0] + a * math.cos(w * t)],
            (0.0, period),
            z,
            rtol=1e-11,
            atol=1e-13,
        )
        return sol.y[:, -1].copy(), None

    exact = np.array([a / (wn**2 - w**2), 0.0])
    z = np.zeros(2)
    g, _ = one_period(z)
    # plain iteration from rest stays away from the periodic state
    plain = z
    for _ in range(20):
        plain = one_period(plain)[0]
    assert np.abs(plain - exact).max() > 0.1 * abs(exact[0])
    ref = np.array([abs(exact[0]), wn * abs(exact[0])])
    result = newton_fixed_point(
        one_period,
        z,
        (g, None),
        ref,
        np.full(2, 1e-3),
        lambda zz, gg, _: bool(np.max(np.abs(gg - zz) / ref) < 1e-9),
        max_evaluations=20,
    )
    assert result.converged and result.jacobians == 1
    np.testing.assert_allclose(result.z, exact, atol=1e-8 * abs(exact[0]))


def test_periodic_option_is_validated():
    with pytest.raises(CaseError, match="solver.periodic"):
        load_case(REFERENCE, ['solver.periodic="newton"'])
