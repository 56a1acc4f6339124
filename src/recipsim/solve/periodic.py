"""Periodic steady state of every scene: revolution iteration, and the dispatch to
shooting (:mod:`recipsim.solve.shooting`) by ``solver.periodic``.

Each revolution starts at 270 deg (both valves shut) from the end state of the previous one
(quadratures reset). The cycle residual is the largest of: the change of the
error-controlled states over the revolution (T and rho relative, reed lift and
velocity relative to their scales, mechanism states relative to their largest value
over the revolution) and the relative change of the revolution's suction mass,
indicated work, mass-weighted discharge enthalpy and drive work from the
previous revolution. Undamped flexible bearings never settle this way (their free
vibration does not decay) and lightly damped ones settle slowly: ``"auto"`` hands
such runs over to shooting (see :func:`solve_periodic`), as it does any run whose
residual stalls (:func:`stalled`: no halving over ``STALL_WINDOW`` revolutions), e.g. the
slow settling near zero delivery; ``"revolutions"`` ends them at ``max_revolutions``
unconverged. A stalled run whose end states repeat after n = 2..4 revolutions
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
from collections.abc import Callable

import numpy as np

from recipsim.model.build import Model
from recipsim.solve.residual import cycle_residual, residual_reference, state_change
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
from recipsim.solve.shooting import shooting_cost, solve_shooting

#: ``integrate(model, y, mode, h, samples) -> (revolution, next first step [s])``
RevolutionIntegrator = Callable[
    [Model, np.ndarray, np.ndarray, float, int], tuple[Revolution, float]
]

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
#: The residual has stalled when its best over the last ``STALL_WINDOW`` revolutions is
#: no better than ``STALL_GAIN`` times its best before them.
STALL_WINDOW = 8
STALL_GAIN = 0.5
#: Periods (in revolutions) looked for when the iteration stalls.
SUBHARMONIC_PERIODS = (2, 3, 4)


def stalled(history: list[float]) -> bool:
    """Whether the cycle residual stopped decaying (see :data:`STALL_WINDOW`)."""
    if len(history) <= STALL_WINDOW:
        return False
    return min(history[-STALL_WINDOW:]) >= STALL_GAIN * min(history[:-STALL_WINDOW])


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
        the last two periods) while one revolution changes them by more; 1 otherwise.
    """
    judged = reference > 0.0

    def change(a: np.ndarray, b: np.ndarray) -> float:
        return float(np.max(np.abs(a[judged] - b[judged]) / reference[judged]))

    if len(ends) < 2 or change(ends[-1], ends[-2]) < tolerance:
        return 1
    for n in SUBHARMONIC_PERIODS:
        if len(ends) < 2 * n + 1:
            break
        if all(change(ends[-1 - k], ends[-1 - k - n]) < tolerance for k in range(n + 1)):
            return n
    return 1


def _period_average(revs: list[Revolution], n_err: int) -> Revolution:
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


def solve_periodic(model: Model) -> PeriodicSolution:
    """Periodic steady state with the solver of ``model.case.solver.periodic``.

    ``"revolutions"``: revolution iteration (:func:`solve_revolutions`);
    ``"shooting"``: Newton on the one-revolution map
    (:func:`recipsim.solve.shooting.solve_shooting`); ``"auto"``: revolutions that
    hand over to shooting (from the state reached) when the residual's decay rate
    predicts more revolutions than shooting costs: undamped or lightly damped
    flexible bearings, whose free vibration decays slowly or not at all.

    ``revolutions`` of the result counts every integrated revolution, those of the
    shooting Jacobians included.

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
    s = model.case.solver
    start = time.perf_counter()
    y = model.y0.copy()
    mode = model.mode0.copy()
    h = model.period * 1e-4
    previous: Revolution | None = None
    history: list[float] = []
    tally = _Tally()
    rev: Revolution | None = None
    recent: list[Revolution] = []
    residual = math.inf
    converged = False
    period = 1
    for count in range(1, s.max_revolutions + 1):
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
            ref = residual_reference(model, rev) * (model.scale[: model.n_err] > 0.0)
            ends = [r.y_end[: model.n_err] for r in recent]
            period = subharmonic_period(ends, ref, s.cycle_tolerance)
            if period > 1:  # a period of n revolutions: report its average
                rev = _period_average(recent[-period:], model.n_err)
                converged = True
                break
        if hand_over and count >= _AUTO_MIN_REVOLUTIONS:
            cost = shooting_cost(model, mode)
            slow = predicted_revolutions(history, s.cycle_tolerance) > cost or stalled(history)
            if cost < s.max_revolutions - count and slow:
                return solve_shooting(model, start=(rev, h), history=history, tally=tally, t0=start)
    assert rev is not None
    return PeriodicSolution(
        period_revolutions=period,
        model=model,
        final=rev,
        revolutions=tally.revolutions,
        residual=residual,
        converged=converged,
        residual_history=history,
        nfev=tally.nfev,
        steps=tally.steps,
        rejected=tally.rejected,
        events=tally.events,
        wall_time=time.perf_counter() - start,
    )
