"""Subharmonic responses: valve dynamics that repeat every n = 2..4 revolutions.

Detection. Revolution iteration (:mod:`.periodic`) keeps the end states of its last
revolutions; they *repeat with period n* when the states after n revolutions agree
within the cycle tolerance while those after one do not (:func:`subharmonic_period`).
An iteration that has settled on such an orbit ends there, converged with
``period_revolutions = n``.

Shooting on the n-revolution map. An iteration that is still *approaching* a period-n
orbit (the n-revolution change of the end states well below the one-revolution change,
:func:`candidate_period`, but not yet within tolerance) is handed to
:func:`solve_subharmonic`: Newton (:func:`recipsim.solve.newton.newton_fixed_point`) on
the map ``G^n`` that takes the unknowns at the section (those of one-revolution shooting,
:func:`recipsim.solve.shooting.shooting_unknowns`, with the discharge plenum's
enthalpy) over n chained revolutions, each revolution's discharge enthalpy feeding the
next one's back-flow as in revolution iteration. Its fixed points are the period-n
orbits (and the period-1 orbit, a fixed point of every ``G^n``). Newton stops when the
states after n revolutions repeat to half the cycle tolerance, or stalls where the
map's valve impacts make it rough (the bouncing discharge reed of the period-2 test
case: at about 1e-5); then plain periods of n revolutions from its best point are each
judged by :func:`period_residual` (the n-revolution state change, the change of each
revolution's totals from the same revolution one period before, and the period's
closures over 10, as :func:`.residual.cycle_residual` judges one revolution). The
solution is accepted when that is below ``solver.cycle_tolerance`` and the
one-revolution change is not (else it is the period-1 orbit: ``None`` is returned
and the caller goes on with one-revolution shooting). The summary then holds the
averages over the period (:func:`period_average`).
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np

from recipsim.errors import SolverError
from recipsim.model.build import Model, WorkingModel
from recipsim.solve.newton import newton_fixed_point
from recipsim.solve.residual import (
    CLOSURE_ALLOWANCE,
    closures,
    residual_reference,
    revolution_totals,
    state_change,
)
from recipsim.solve.revolution import (
    PeriodicSolution,
    Revolution,
    _Tally,
    discharge_enthalpy,
    integrate_revolution,
)
from recipsim.solve.shooting_map import RevolutionMap

#: ``integrate(model, y, mode, h, samples) -> (revolution, next first step [s])``
RevolutionIntegrator = Callable[
    [WorkingModel, np.ndarray, np.ndarray, float, int], tuple[Revolution, float]
]

#: Periods (in revolutions) looked for.
SUBHARMONIC_PERIODS = (2, 3, 4)
#: A candidate period n: the end states after n revolutions differ by less than this
#: fraction of their one-revolution change.
CANDIDATE_RATIO = 0.1
#: Newton's aim for the n-revolution state change, in cycle tolerances; then at most
#: ``_PLAIN_PERIODS`` plain periods until the period residual is within tolerance.
_TARGET = 0.5
_PLAIN_PERIODS = 8


def _change(a: np.ndarray, b: np.ndarray, reference: np.ndarray) -> float:
    judged = reference > 0.0
    return float(np.max(np.abs(a[judged] - b[judged]) / reference[judged]))


#: How much better a period of n revolutions must repeat than one revolution does.
SUBHARMONIC_CONTRAST = 100.0


def subharmonic_period(ends: list[np.ndarray], reference: np.ndarray, tolerance: float) -> int:
    """Smallest n in :data:`SUBHARMONIC_PERIODS` with which the end states repeat.

    Parameters
    ----------
    ends : list of ndarray
        Error-controlled states at the end of each revolution, oldest first.
    reference : ndarray
        Size against which a change is judged (0 for states not judged).
    tolerance : float
        Largest relative change of a repeating state [-].

    Returns
    -------
    int
        n if the states after n revolutions repeat within ``tolerance`` (checked over
        the last two periods) while one revolution changes them by more, and by
        :data:`SUBHARMONIC_CONTRAST` times more; 1 otherwise.
    """
    if len(ends) < 2:
        return 1
    one = _change(ends[-1], ends[-2], reference)
    if one < tolerance:
        return 1
    for n in SUBHARMONIC_PERIODS:
        if len(ends) < 2 * n + 1:
            break
        changes = [_change(ends[-1 - k], ends[-1 - k - n], reference) for k in range(n + 1)]
        # a period of n revolutions repeats far better than one revolution does: where
        # both are at the integration's noise (a tolerance below what the solve can
        # reach), a chance match is not a subharmonic
        if max(changes) < tolerance and one >= SUBHARMONIC_CONTRAST * max(changes):
            return n
    return 1


def candidate_period(ends: list[np.ndarray], reference: np.ndarray) -> int:
    """Smallest n in :data:`SUBHARMONIC_PERIODS` whose n-revolution changes of the end
    states (every pair available, at most n + 1) are below :data:`CANDIDATE_RATIO` times
    the last one-revolution change; 1 if none."""
    if len(ends) < 3:
        return 1
    one = _change(ends[-1], ends[-2], reference)
    if one <= 0.0:
        return 1
    for n in SUBHARMONIC_PERIODS:
        pairs = min(n + 1, len(ends) - n)
        if pairs < 1:
            break
        limit = CANDIDATE_RATIO * one
        if all(_change(ends[-1 - k], ends[-1 - k - n], reference) < limit for k in range(pairs)):
            return n
    return 1


def period_average(revs: list[Revolution], n_err: int) -> Revolution:
    """The last revolution with its quadratures averaged over ``revs`` (one period)."""
    last = revs[-1]
    y_end = last.y_end.copy()
    y_end[n_err:] = np.mean([r.y_end[n_err:] for r in revs], axis=0)
    rev = Revolution(
        last.y_start,
        y_end,
        last.mode_start,
        last.mode_end,
        last.times,
        last.samples,
        last.sample_modes,
        last.stats,
    )
    rev.duration = float(np.mean([r.duration for r in revs]))
    return rev


def settled_period(
    model: Model, revs: list[Revolution], tolerance: float
) -> tuple[int, Revolution | None]:
    """The period n > 1 on which the revolutions ``revs`` (run end to end, oldest first)
    repeat (:func:`subharmonic_period`, judged against the last one's scale) and the last
    period's average (:func:`period_average`); ``(1, None)`` where they do not."""
    ref = residual_reference(model, revs[-1]) * (model.scale[: model.n_err] > 0.0)
    period = subharmonic_period([r.y_end[: model.n_err] for r in revs], ref, tolerance)
    if period == 1:
        return 1, None
    return period, period_average(revs[-period:], model.n_err)


def period_change(model: Model, revs: list[Revolution]) -> float:
    """Change of the error-controlled states from the start of ``revs[0]`` to the end of
    ``revs[-1]`` relative to :func:`.residual.residual_reference`; at least 1 if the
    discrete modes differ."""
    n = model.n_err
    ref = residual_reference(model, revs[0]) * (model.scale[:n] > 0.0)
    res = _change(revs[-1].y_end[:n], revs[0].y_start[:n], ref)
    if not np.array_equal(revs[0].mode_start, revs[-1].mode_end):
        res = max(res, 1.0)
    return res


def period_residual(model: Model, revs: list[Revolution], previous: list[Revolution]) -> float:
    """The cycle residual of a period (module docstring)."""
    res = period_change(model, revs)
    for rev, before in zip(revs, previous, strict=True):
        for q, floor in revolution_totals(model):
            a, b = rev.y_end[q], before.y_end[q]
            res = max(res, abs(a - b) / max(abs(a), abs(b), floor, 1e-300))
    mass, energy = closures(model, period_average(revs, model.n_err).y_end)
    return max(res, abs(mass) / CLOSURE_ALLOWANCE, abs(energy) / CLOSURE_ALLOWANCE)


class _PeriodRepeats:
    """Newton's convergence test: the states repeat after the period to ``target``."""

    def __init__(self, model: Model, target: float) -> None:
        self.model = model
        self.target = target

    def __call__(self, z: np.ndarray, g: np.ndarray, revs: list[Revolution]) -> bool:
        return period_change(self.model, revs) < self.target


class _PeriodMap(RevolutionMap):
    """``z -> G^n(z)``: n chained revolutions from the unknowns ``z`` at the section."""

    def __init__(self, model: WorkingModel, tally: _Tally, n: int, integrate: RevolutionIntegrator):
        super().__init__(model, tally)
        self.n = n
        self.integrate = integrate

    def __call__(self, z: np.ndarray) -> tuple[np.ndarray, list[Revolution]]:  # type: ignore[override]
        model = self.model
        k = self.idx.size
        y = self.y_base.copy()
        y[self.idx] = z[:k]
        if self.gas:
            model.set_discharge_enthalpy(float(z[k]))
        mode = self.mode.copy()
        revs: list[Revolution] = []
        enthalpy = float(z[k]) if self.gas else 0.0
        samples = model.case.solver.samples_per_revolution
        for _ in range(self.n):
            rev, self.h = self.integrate(model, y, mode, self.h, samples)
            self.tally.add(rev)
            revs.append(rev)
            delivered = discharge_enthalpy(model, rev)
            if delivered is not None:
                enthalpy = delivered
                model.set_discharge_enthalpy(delivered)
            y, mode = rev.y_end.copy(), rev.mode_end.copy()
        g = revs[-1].y_end[self.idx]
        if self.gas:
            g = np.append(g, enthalpy)
        return g, revs


def solve_subharmonic(
    model: Model,
    n: int,
    start: tuple[Revolution, float],
    history: list[float],
    tally: _Tally,
    t0: float,
    integrate: RevolutionIntegrator = integrate_revolution,
) -> PeriodicSolution | None:
    """The period-``n`` orbit by Newton on the n-revolution map (module docstring).

    Parameters
    ----------
    model : Model
        Not changed: Newton moves a working copy of it
        (:meth:`~recipsim.model.build.Model.for_solve`), which the result carries.
    n : int
        The candidate period (:func:`candidate_period`).
    start : (Revolution, float)
        The last revolution run and the integrator's step [s]; the model's discharge
        enthalpy must be the one that revolution delivered.
    history, tally, t0
        Residual history, counters and start time of the revolutions already run.
    integrate : callable
        The revolution integrator (:func:`.periodic.solve_revolutions`' ``integrate``).

    Returns
    -------
    PeriodicSolution or None
        Converged with ``period_revolutions = n``, or None when Newton stalls, the
        budget runs out or the orbit found repeats after one revolution.
    """
    return shoot_subharmonic(model.for_solve(), n, start, history, tally, t0, integrate)


def shoot_subharmonic(
    model: WorkingModel,
    n: int,
    start: tuple[Revolution, float],
    history: list[float],
    tally: _Tally,
    t0: float,
    integrate: RevolutionIntegrator = integrate_revolution,
) -> PeriodicSolution | None:
    """:func:`solve_subharmonic` on the working copy ``model`` itself, which it moves
    (the hand-over from revolution iteration, which goes on with the same copy when no
    period-n orbit is found)."""
    s = model.case.solver
    tol = s.cycle_tolerance
    fmap = _PeriodMap(model, tally, n, integrate)
    fmap.set_base(start[0].y_end, start[0].mode_end)
    fmap.h = start[1]
    z = fmap.pack(start[0].y_end)
    try:
        first = fmap(z)
    except SolverError:
        return None
    ref = fmap.reference(first[1][0])
    counts = np.zeros(3, dtype=np.int64)  # Newton iterations, Jacobians, their revolutions
    result = newton_fixed_point(
        fmap,
        z,
        first,
        ref,
        fmap.fd_step,
        _PeriodRepeats(model, _TARGET * tol),
        (s.max_revolutions - tally.revolutions) // n,
        same_branch=lambda a, b: np.array_equal(a[-1].mode_end, b[-1].mode_end),
    )
    counts += (result.iterations, result.jacobians, result.jacobian_evaluations * n)
    if not (result.converged or result.stalled):
        return None  # the budget is spent
    # plain periods from the end of Newton's best (the map's impacts make it rough at
    # the level of the tolerance, where Newton may stall), the enthalpy following
    revs, z = result.payload, result.g.copy()
    for _ in range(_PLAIN_PERIODS):
        if fmap.set_base(revs[-1].y_end, revs[-1].mode_end):
            return None  # other modes at the section after n revolutions: not period n
        if s.max_revolutions - tally.revolutions < n:
            return None
        try:
            g, period = fmap(z)
        except SolverError:
            return None
        residual = period_residual(model, period, revs)
        history.append(residual)
        if residual < tol:
            if state_change(model, period[-1]) < tol:
                return None  # the period-1 orbit
            return _solution(model, n, period, residual, history, tally, t0, counts)
        revs, z = period, g
    return None


def _solution(
    model: WorkingModel,
    n: int,
    revs: list[Revolution],
    residual: float,
    history: list[float],
    tally: _Tally,
    t0: float,
    counts: np.ndarray,
) -> PeriodicSolution:
    return PeriodicSolution(
        model=model,
        final=period_average(revs, model.n_err),
        revolutions=tally.revolutions,
        residual=residual,
        converged=True,
        residual_history=history,
        nfev=tally.nfev,
        steps=tally.steps,
        rejected=tally.rejected,
        events=tally.events,
        wall_time=time.perf_counter() - t0,
        method=f"shooting on the {n}-revolution map",
        newton_iterations=int(counts[0]),
        jacobians=int(counts[1]),
        jacobian_revolutions=int(counts[2]),
        period_revolutions=n,
    )
