"""Periodic steady state of every scene: revolution iteration, and the dispatch to
shooting (:mod:`recipsim.solve.shooting`) by ``solver.periodic``.

Each revolution starts at 270 deg (both valves shut) from the end state of the previous one
(quadratures reset). The cycle residual is the largest of: the change of the
error-controlled states over the revolution (T and rho relative, reed lift and
velocity relative to their scales, mechanism states relative to their largest value
over the revolution) and the relative change of the revolution's suction mass,
indicated work, mass-weighted discharge enthalpy and drive work from the
previous revolution, and the revolution's mass and energy closures over 10
(:mod:`recipsim.solve.residual`: near zero delivery the cylinder keeps many times the
gas it passes, and a state change within tolerance can leave a closure of 2e-3).
On a crank train ``"auto"`` mixes the revolutions (Anderson,
:mod:`.acceleration`): each starts from an extrapolation of the last three, which removes a
slow mode of the bearings' orbit (the piston on its skirt film: 10 revolutions instead of
39); ``"revolutions"`` iterates plainly. Undamped flexible bearings never settle this way
(their free vibration does not decay) and lightly damped ones settle slowly: ``"auto"`` hands
such runs over to shooting (see :func:`solve_periodic`; not before the mixing has started
the revolutions whose decay it judges, :func:`warming_up`), as it does any run whose
residual stalls (:func:`stalled`: no halving over ``STALL_WINDOW`` revolutions), e.g. the
slow settling near zero delivery; ``"revolutions"`` ends them at ``max_revolutions``
unconverged. A period-1 orbit that one-revolution shooting finds on the cylinder scene
is rejected when it repels (a real Floquet multiplier below -1.05: past a period
doubling, :func:`repels`), and revolution iteration goes on from where it handed over.
A stalled run whose end states repeat after n = 2..4 revolutions
(:func:`subharmonic_period`: valve dynamics locked on a subharmonic) ends there, converged
with ``period_revolutions = n`` and the quadratures averaged over the period.
Back-flow through the discharge valve comes from a plenum at
the mass-weighted discharge enthalpy of the previous revolution (Bell et al.).
With ``options.thermal = "network"`` the shell's thermal network is solved after every
revolution (:mod:`recipsim.model.thermal`): its discharge chamber becomes the discharge
plenum, and the relative change of the boundary it gives the cylinder joins the cycle
residual.
"""

from __future__ import annotations

import math
import time

import numpy as np

from recipsim.case.sections import SolverSettings
from recipsim.errors import SolverError
from recipsim.model.build import Model, WorkingModel
from recipsim.model.scenes import SCENE_CYLINDER
from recipsim.solve.acceleration import AndersonMixing
from recipsim.solve.residual import (
    cycle_residual,
    residual_reference,
    stalled,
    state_change,
)
from recipsim.solve.revolution import (
    INTEGRATOR_METHODS,
    PeriodicSolution,
    Revolution,
    _Tally,
    discharge_enthalpy,
    integrate_revolution,
    integrator_method,
    revolution_setup,
    sample_outputs,
    sample_times,
)
from recipsim.solve.shooting import shoot, shooting_cost, solve_shooting
from recipsim.solve.subharmonic import (
    SUBHARMONIC_PERIODS,
    RevolutionIntegrator,
    candidate_period,
    settled_period,
    shoot_subharmonic,
    subharmonic_period,
)

#: The revolution machinery is defined in :mod:`.revolution`; the names are re-exported
#: here, where callers look for a periodic solution.
__all__ = [
    "PeriodicSolution",
    "Revolution",
    "INTEGRATOR_METHODS",
    "cycle_residual",
    "discharge_enthalpy",
    "integrate_revolution",
    "integrator_method",
    "residual_reference",
    "revolution_setup",
    "sample_outputs",
    "sample_times",
    "state_change",
    "predicted_revolutions",
    "stalled",
    "subharmonic_period",
    "SUBHARMONIC_PERIODS",
    "solve_periodic",
    "solve_revolutions",
]

#: ``solver.periodic = "auto"``: revolutions hand over to shooting when the residual's
#: decay over the last ``_RATE_WINDOW`` revolutions predicts more revolutions to the
#: tolerance than shooting needs (one per unknown for the Jacobian plus
#: ``_SHOOTING_OVERHEAD``), and not before ``_AUTO_MIN_REVOLUTIONS`` revolutions.
_RATE_WINDOW = 2
_SHOOTING_OVERHEAD = 4
_AUTO_MIN_REVOLUTIONS = 4


def predicted_revolutions(history: list[float], tolerance: float) -> float:
    """Revolutions still needed if the residual keeps decaying at its recent rate.

    The rate is the geometric mean of the residual's ratio over the last
    ``_RATE_WINDOW`` revolutions; inf if it does not decay.
    """
    if len(history) <= _RATE_WINDOW:
        return math.inf
    now, before = history[-1], history[-1 - _RATE_WINDOW]
    if now < tolerance:
        return 0.0
    if not (0.0 < now < before):
        return math.inf
    rate = (now / before) ** (1.0 / _RATE_WINDOW)
    return math.log(tolerance / now) / math.log(rate)


#: Rough cost of one integration step [s], for the estimate of a refused solve.
STEP_COST_ESTIMATE = 5e-6


def check_step_budget(settings: SolverSettings) -> None:
    """Refuse, before integrating, a solve whose largest crank-angle step alone needs
    more steps than ``solver.step_budget`` over ``solver.min_revolutions`` revolutions,
    with an estimate of what it would take.

    Raises
    ------
    SolverError
        Naming ``solver.max_step``, the steps it needs and the budget.
    """
    per_revolution = math.ceil(2.0 * math.pi / settings.max_step)
    needed = settings.min_revolutions * per_revolution
    if needed > settings.step_budget:
        hours = needed * STEP_COST_ESTIMATE / 3600.0
        raise SolverError(
            f"solver.max_step = {settings.max_step:.3g} rad needs at least {needed:,} steps "
            f"({settings.min_revolutions} revolutions of {per_revolution:,}), over "
            f"solver.step_budget = {settings.step_budget:,} (roughly {hours:.2g} h at "
            f"{STEP_COST_ESTIMATE * 1e6:.0f} us a step): raise solver.max_step, or "
            "solver.step_budget to run it anyway"
        )


def solve_periodic(model: Model) -> PeriodicSolution:
    """Periodic steady state with the solver of ``model.case.solver.periodic``.

    ``"revolutions"``: revolution iteration (:func:`solve_revolutions`);
    ``"shooting"``: Newton on the one-revolution map
    (:func:`recipsim.solve.shooting.solve_shooting`); ``"auto"``: revolutions that
    hand over to shooting (from the state reached) when the residual's decay rate
    predicts more revolutions than shooting costs: undamped or lightly damped
    flexible bearings, whose free vibration decays slowly or not at all.

    ``revolutions`` of the result counts every integrated revolution, those of the
    shooting Jacobians included. ``model`` is not changed: the solve moves a working
    copy of it (:meth:`~recipsim.model.build.Model.for_solve`), which the result carries.

    Raises
    ------
    SolverError
        If a revolution fails (with crank angle and state).
    """
    method = model.case.solver.periodic
    if method == "shooting":
        return solve_shooting(model)
    return solve_revolutions(model, hand_over=method == "auto")


def solve_revolutions(
    model: Model,
    hand_over: bool = False,
    integrate: RevolutionIntegrator = integrate_revolution,
) -> PeriodicSolution:
    """Iterate revolutions until the cycle residual is below the case's tolerance.

    Parameters
    ----------
    model : Model
        Not changed: the revolutions move a working copy of it
        (:meth:`~recipsim.model.build.Model.for_solve`), which the result carries.
    hand_over : bool
        Hand over to shooting when revolutions converge too slowly (``"auto"``).
    integrate : callable
        ``integrate(model, y, mode, h, samples) -> (revolution, next first step)``:
        :func:`~recipsim.solve.revolution.integrate_revolution` (the compiled
        integrator) or another driver of the same scene, e.g. the benchmark's
        ``solve_ivp`` one (:mod:`recipsim.studies.bench.ivp`).

    Raises
    ------
    SolverError
        If a revolution fails (with crank angle and state).
    """
    return _iterate(model.for_solve(), hand_over, integrate)


def _iterate(
    model: WorkingModel, hand_over: bool, integrate: RevolutionIntegrator
) -> PeriodicSolution:
    """:func:`solve_revolutions` on the working copy ``model``, which it moves."""
    s = model.case.solver
    start = time.perf_counter()
    y = model.y0.copy()
    mode = model.mode0.copy()
    h = model.period * 1e-4
    previous: Revolution | None = None
    history: list[float] = []
    tally = _Tally(s.step_budget)
    rev: Revolution | None = None
    recent: list[Revolution] = []
    residual = math.inf
    converged = False
    period = 1
    tried: set[int] = set()  # hand-overs tried: 1 (one-revolution shooting) or n
    mixing = accelerated(model) if hand_over else None
    for count in range(1, s.max_revolutions + 1):
        if tally.revolutions >= s.max_revolutions:
            break  # spent, shooting's revolutions included
        rev, h = integrate(model, y, mode, h, s.samples_per_revolution)
        tally.add(rev)
        enthalpy = discharge_enthalpy(model, rev)
        if enthalpy is not None:
            model.set_discharge_enthalpy(enthalpy)
        # the shell's thermal network (if any) follows the revolution like the discharge
        # plenum, and the next start follows the network's suction plenum
        y = rev.y_end.copy()
        residual = max(
            cycle_residual(model, rev, previous),
            model.update_thermal(rev.y_end, rev.duration, y_next=y),
        )
        history.append(residual)
        mode = rev.mode_end.copy()
        previous = rev
        recent = [*recent[-2 * SUBHARMONIC_PERIODS[-1] :], rev]
        if residual < s.cycle_tolerance and count >= s.min_revolutions:
            converged = True
            break
        if stalled(history):
            mixing = None
            period, average = settled_period(model, recent, s.cycle_tolerance)
            if average is not None:  # a period of n revolutions: report its average
                rev, converged = average, True
                break
        if hand_over and count >= _AUTO_MIN_REVOLUTIONS and not warming_up(mixing):
            handed = _hand_over(model, recent, (rev, h), history, tally, start, integrate, tried)
            if handed is not None:
                return handed
        if mixing is not None:
            mixing.next_start(rev, y)
    assert rev is not None
    method = "revolutions, shooting's period-1 orbit repels" if 1 in tried else "revolutions"
    solution = PeriodicSolution(model, rev, tally.revolutions, residual, converged, history)
    return _tallied(solution, tally, start, method, period)


def accelerated(model: WorkingModel) -> AndersonMixing | None:
    """Anderson mixing (:mod:`.acceleration`) for a crank train's revolutions (a scene
    with a mechanism, without the shell's thermal network, whose state the mixing does not
    see); None for the cylinder on the rigid crank, whose slowest multiplier (about 0.4)
    leaves little to gain."""
    if model.scene == SCENE_CYLINDER or model.thermal is not None:
        return None
    return AndersonMixing(model)


def warming_up(mixing: AndersonMixing | None) -> bool:
    """Whether the mixing has yet to start the last ``_RATE_WINDOW`` revolutions, whose
    decay the hand-over to shooting judges (:func:`predicted_revolutions`): before that
    the rate is the plain iteration's. On the skirt film at 6000 rpm the plain rate
    (0.78 a revolution) predicted 27 revolutions against shooting's 27 after the first
    mixed start; two mixed starts later the mixing's rate was 0.4 (12 revolutions in all,
    shooting 37)."""
    return mixing is not None and mixing.mixed < _RATE_WINDOW


def _tallied(
    solution: PeriodicSolution, tally: _Tally, t0: float, method: str, period: int
) -> PeriodicSolution:
    """``solution`` with the counters of ``tally``, its wall time, method and period."""
    solution.nfev, solution.steps = tally.nfev, tally.steps
    solution.rejected, solution.events = tally.rejected, tally.events
    solution.wall_time = time.perf_counter() - t0
    solution.method, solution.period_revolutions = method, period
    return solution


def _hand_over(
    model: WorkingModel,
    recent: list[Revolution],
    start: tuple[Revolution, float],
    history: list[float],
    tally: _Tally,
    t0: float,
    integrate: RevolutionIntegrator,
    tried: set[int],
) -> PeriodicSolution | None:
    """Shooting from the revolution iteration's state, if it converges slowly: on the
    n-revolution map when the end states approach a period of n revolutions
    (:mod:`.subharmonic`), else (or if that finds no period-n orbit) on the one-revolution
    map. None (revolution iteration goes on) if it is not slow, if each kind of shooting
    was tried, or if the one-revolution orbit found repels (:func:`repels`)."""
    s = model.case.solver
    rev, _ = start
    cost = shooting_cost(model, rev.mode_end)
    slow = predicted_revolutions(history, s.cycle_tolerance) > cost or stalled(history)
    if not (slow and cost < s.max_revolutions - tally.revolutions):
        return None
    ref = residual_reference(model, rev) * (model.scale[: model.n_err] > 0.0)
    n = candidate_period([r.y_end[: model.n_err] for r in recent], ref)
    if n > 1 and n not in tried:
        tried.add(n)
        solution = shoot_subharmonic(model, n, start, history, tally, t0, integrate)
        if solution is not None:
            return solution
    if 1 in tried:
        return None
    tried.add(1)
    solution = shoot(model, start=start, history=history, tally=tally, t0=t0)
    if not repels(model, solution):
        return solution
    enthalpy = discharge_enthalpy(model, rev)  # back to the iteration's plenum
    if enthalpy is not None:
        model.set_discharge_enthalpy(enthalpy)
    return None


#: A real Floquet multiplier below ``-REPEL`` makes a period-1 orbit repel (period
#: doubling): the response settles elsewhere, e.g. on a period of two revolutions.
REPEL = 1.05


def repels(model: Model, solution: PeriodicSolution) -> bool:
    """Whether the converged one-revolution orbit of ``solution`` repels: a real
    multiplier (:attr:`PeriodicSolution.multipliers`) below ``-REPEL``. Judged on the
    cylinder scene with a fixed wall only (the multipliers of a mechanism's vibration lie
    on or near the unit circle and their estimate is noisy; the shell's network is held
    fixed over a Newton solve)."""
    mu = solution.multipliers
    if not solution.converged or mu is None or model.scene != SCENE_CYLINDER:
        return False
    if model.thermal is not None:
        return False
    real = np.abs(mu.imag) <= 1e-3 * np.abs(mu)
    return bool(np.any(real & (mu.real < -REPEL)))
