"""The periodic iteration of :mod:`recipsim.solve.periodic` with ``scipy.integrate.solve_ivp``.

Same scene (right-hand side, events, event actions), same revolutions from 270 deg,
same cycle residual and discharge-plenum update; only the integrator differs. It serves
two rungs of the benchmark:

- a scipy method driving the *compiled* right-hand side from Python (what the compiled
  integrator itself gains over scipy's);
- with ``NUMBA_DISABLE_JIT=1`` (:mod:`recipsim.studies.bench.baseline`) every compiled function
  runs as plain Python and properties come from the CoolProp object called from Python:
  the model as a user would write it with ``solve_ivp``.

Events are handled as the compiled integrator does: each event function of the current
modes fires on a crossing from <= 0 to > 0 (``direction = +1``, terminal); at the event
the right-hand side is evaluated (the actions read its outputs), the scene's action
switches modes or applies the impact, and ``solve_ivp`` restarts from there.

Tolerances: ``rtol`` as given, ``atol * scale`` per controlled state; quadratures (zero
scale) get an absolute tolerance of 1e30, i.e. no error control, as in the compiled
integrator. scipy's error norms (RMS over all states for the Runge-Kutta methods, the
methods' own for LSODA and BDF) differ from the compiled one's, so equal ``rtol`` does
not mean equal error: the benchmark compares at equal measured error.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np
from numba import njit, types
from numba.experimental import jitclass

from recipsim.errors import SolverError
from recipsim.model import scenes
from recipsim.model.build import Model, WorkingModel
from recipsim.physics.thermo.properties import PROPS_SIGNATURE
from recipsim.physics.thermo.valve_models import VALVE_MODELS
from recipsim.solve.integrator import (
    N_STATS,
    ST_NACCEPT,
    ST_NEVENTS,
    ST_NFEV,
    ST_NREJECT,
    ST_NSAMPLES,
    ST_T,
)
from recipsim.solve.periodic import (
    PeriodicSolution,
    Revolution,
    revolution_setup,
    solve_revolutions,
)

#: scipy methods the benchmark drives
METHODS = ("RK45", "DOP853", "LSODA", "Radau", "BDF")
_NO_CONTROL = 1e30  # absolute tolerance of an uncontrolled state (a quadrature)
_MAX_EVENTS_AT_ONE_INSTANT = 50

_F64 = types.float64[::1]
_I64 = types.int64[::1]


@jitclass(
    [
        ("props", types.FunctionType(PROPS_SIGNATURE)),
        ("par", _F64),
        ("ipar", _I64),
        ("pbuf", _F64),
        ("mode", _I64),
        ("aux", _F64),
        ("scratch", _F64),
        ("failures", types.int64),
    ]
)
class SceneContext:
    """Everything the compiled right-hand side needs but the time and the state.

    One object unboxed per call from Python (a first-class function argument costs a
    type dispatch on every call, a jitclass instance much less).
    """

    def __init__(self, props, par, ipar, pbuf, mode, aux, scratch):  # type: ignore[no-untyped-def]
        self.props = props
        self.par = par
        self.ipar = ipar
        self.pbuf = pbuf
        self.mode = mode
        self.aux = aux
        self.scratch = scratch
        self.failures = 0


@njit
def _rhs(t, y, ctx):  # type: ignore[no-untyped-def]
    """dy/dt as a new array (NaN where the property call failed: the step is rejected)."""
    dydt = np.empty(y.shape[0])
    status = scenes.scene_rhs(t, y, ctx.mode, ctx.par, ctx.ipar, ctx.props, ctx.pbuf, dydt, ctx.aux)
    if status != 0:
        ctx.failures += 1
        dydt[:] = np.nan
    return dydt


@njit
def _events(t, y, ctx, g):  # type: ignore[no-untyped-def]
    """Event functions of the current modes at (t, y) (the right-hand side fills ``aux``)."""
    scenes.scene_rhs(t, y, ctx.mode, ctx.par, ctx.ipar, ctx.props, ctx.pbuf, ctx.scratch, ctx.aux)
    scenes.scene_event_values(y, ctx.mode, ctx.par, ctx.ipar, ctx.aux, g)


@njit
def _act(k, t, y, ctx):  # type: ignore[no-untyped-def]
    """Apply event ``k`` at (t, y) in place; True when it ends the revolution."""
    scenes.scene_rhs(t, y, ctx.mode, ctx.par, ctx.ipar, ctx.props, ctx.pbuf, ctx.scratch, ctx.aux)
    return scenes.scene_event_action(k, y, ctx.mode, ctx.par, ctx.ipar, ctx.aux)


def active_events(model: Model) -> list[int]:
    """Indices of the scene's event functions that can fire (the others are constant -1)."""
    active: list[int] = []
    ipar = scenes.IPAR.bundle(model.ipar)
    if model.has_gas:
        active += list(VALVE_MODELS.by_code(int(ipar.valves)).event_functions)
    if ipar.stop_on_angle != 0 and model.scene != scenes.SCENE_CYLINDER:
        active.append(scenes.EV_THETA_END)
    return active


class _SceneFunctions:
    """The right-hand side and event functions of a model, as ``solve_ivp`` calls them."""

    def __init__(self, model: Model, mode: np.ndarray) -> None:
        n = model.y0.shape[0]
        self.ctx = SceneContext(
            model.props,
            model.par,
            model.ipar,
            model.props.buffer,
            mode,
            np.zeros(scenes.N_AUX),
            np.zeros(n),
        )
        self.g = np.zeros(scenes.N_EVENTS)
        self.n_event_evaluations = 0
        self._last_t = math.nan
        self._last_y: np.ndarray | None = None
        self.events = [self._event(k) for k in active_events(model)]

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        return _rhs(t, np.ascontiguousarray(y), self.ctx)  # type: ignore[no-any-return]

    def _values(self, t: float, y: np.ndarray) -> np.ndarray:
        # solve_ivp evaluates every event function at the same (t, y) after a step
        if not (y is self._last_y and t == self._last_t):
            _events(t, np.ascontiguousarray(y), self.ctx, self.g)
            self.n_event_evaluations += 1
            self._last_t, self._last_y = t, y
        return self.g

    def _event(self, k: int) -> Any:
        def event(t: float, y: np.ndarray) -> float:
            return float(self._values(t, y)[k])

        event.terminal = True  # type: ignore[attr-defined]
        event.direction = 1.0  # type: ignore[attr-defined]
        return event

    def forget(self) -> None:
        """Drop the cached event values (the mode changed)."""
        self._last_y = None


def _tolerances(model: Model) -> np.ndarray:
    s = model.case.solver
    n = model.y0.shape[0]
    controlled = (np.arange(n) < model.n_err) & (model.scale > 0.0)
    return np.where(controlled, s.atol * model.scale, _NO_CONTROL)


@dataclass
class _Progress:
    """Where a revolution under ``solve_ivp`` stands: time, state, counters."""

    y: np.ndarray
    t: float = 0.0
    i_sample: int = 0
    nfev: int = 0
    n_events: int = 0
    same_instant: int = 0
    t_last_event: float = -math.inf
    finished_by_event: bool = False


def integrate_revolution_ivp(
    model: WorkingModel, y: np.ndarray, mode: np.ndarray, n_samples: int, method: str
) -> Revolution:
    """One revolution from ``y`` with ``solve_ivp`` (mirrors ``periodic.integrate_revolution``).

    Each call of ``solve_ivp`` (:func:`_solve_piece`) runs to the revolution's end or to
    the first event; its samples are kept and the event applied (:func:`_apply_event`)
    before the next piece starts from it.
    """
    y_start = y.copy()
    mode_start = mode.copy()
    y_run, mode_run, t_end, times, samples, sample_modes = revolution_setup(
        model, y, mode, n_samples
    )
    funcs = _SceneFunctions(model, np.ascontiguousarray(mode_run, dtype=np.int64))
    mode_run = funcs.ctx.mode  # the array the compiled code sees (the same buffer)
    limits = (_tolerances(model), model.case.solver.max_step / model.shaft_speed)
    run = _Progress(y=y_run)
    while run.t < t_end:
        pending = times[run.i_sample :]
        pending = pending[(pending >= run.t) & (pending < t_end)]
        sol = _solve_piece(model, funcs, run, np.append(pending, t_end), limits, method)
        run.nfev += int(sol.nfev)
        got = len(sol.t)  # a list when no point of t_eval was reached
        n_keep = got - 1 if sol.status == 0 else got  # the last point of a full run is t_end
        for j in range(n_keep):
            samples[run.i_sample + j] = sol.y[:, j]
            sample_modes[run.i_sample + j] = mode_run
        run.i_sample += n_keep
        if sol.status == 0:
            run.y = np.array(sol.y[:, -1])
            run.t = t_end
            break
        if _apply_event(model, funcs, sol, run):
            run.finished_by_event = True
            break
    run.nfev += funcs.n_event_evaluations
    return _revolution(model, run, (y_start, mode_start, mode_run), (times, samples, sample_modes))


def _solve_piece(
    model: Model,
    funcs: _SceneFunctions,
    run: _Progress,
    t_eval: np.ndarray,
    limits: tuple[np.ndarray, float],
    method: str,
) -> Any:
    """``solve_ivp`` from ``run`` to the revolution's end (``t_eval[-1]``) or the first
    event; ``limits``: the absolute tolerances and the largest step [s].

    Raises
    ------
    SolverError
        If ``solve_ivp`` fails or cannot locate an event.
    """
    from scipy.integrate import solve_ivp  # a heavy import, needed by these rungs only

    atol, max_step = limits
    try:
        sol = solve_ivp(
            funcs.rhs,
            (run.t, t_eval[-1]),
            run.y,
            method=method,
            t_eval=t_eval,
            events=funcs.events or None,
            rtol=model.case.solver.rtol,
            atol=atol,
            max_step=max_step,
        )
    except ValueError as exc:  # scipy's event location (brentq) on the step's interpolant
        raise SolverError(
            f"solve_ivp ({method}) failed to locate an event after t = {run.t:.6g} s into the "
            f"revolution: {exc} (the method's interpolant does not reproduce the event "
            "function's sign at the step's ends)"
        ) from exc
    if sol.status == -1:
        raise SolverError(
            f"solve_ivp ({method}) failed at t = {sol.t[-1] if sol.t.size else run.t:.6g} s "
            f"into the revolution: {sol.message}"
        )
    return sol


def _apply_event(model: Model, funcs: _SceneFunctions, sol: Any, run: _Progress) -> bool:
    """Apply the earliest event that ended ``sol`` to ``run`` (state, time, counters);
    True when it ends the revolution.

    Raises
    ------
    SolverError
        On more than :data:`_MAX_EVENTS_AT_ONE_INSTANT` events at one instant.
    """
    fired = [(ev[0], j) for j, ev in enumerate(sol.t_events) if ev.size]
    t_event, j = min(fired)
    k = active_events(model)[j]
    run.y = np.ascontiguousarray(sol.y_events[j][0], dtype=float).copy()
    terminal = bool(_act(k, t_event, run.y, funcs.ctx))
    funcs.forget()
    run.n_events += 1
    if t_event - run.t_last_event < 1e-12 * max(1.0, abs(t_event)):
        run.same_instant += 1
        if run.same_instant > _MAX_EVENTS_AT_ONE_INSTANT:
            raise SolverError(
                f"more than {_MAX_EVENTS_AT_ONE_INSTANT} events at t = {t_event:.6g} s "
                "into the revolution (valve chattering)"
            )
    else:
        run.same_instant = 0
    run.t_last_event = t_event
    run.t = t_event
    return terminal


def _revolution(
    model: Model,
    run: _Progress,
    start: tuple[np.ndarray, np.ndarray, np.ndarray],
    sampled: tuple[np.ndarray, np.ndarray, np.ndarray],
) -> Revolution:
    """The finished revolution: ``start`` (initial state and mode, the final mode's
    buffer), ``sampled`` (times, samples, their modes) and the counters of ``run``.

    Raises
    ------
    SolverError
        If a free-speed crank did not complete the revolution.
    """
    y_start, mode_start, mode_run = start
    times, samples, sample_modes = sampled
    if model.free_speed:
        if not run.finished_by_event:
            raise SolverError(
                "the crank did not complete a revolution in three nominal periods: the drive "
                "torque cannot keep the mechanism turning"
            )
        n = run.i_sample
        times, samples, sample_modes = times[:n], samples[:n], sample_modes[:n]
    if model.scene != scenes.SCENE_CYLINDER:
        model.unwind_crank(run.y)
    stats = np.zeros(N_STATS)
    stats[ST_NFEV] = run.nfev
    stats[ST_NACCEPT] = -1  # solve_ivp does not report its steps with t_eval
    stats[ST_NREJECT] = -1
    stats[ST_NEVENTS] = run.n_events
    stats[ST_T] = run.t
    stats[ST_NSAMPLES] = run.i_sample
    rev = Revolution(
        y_start, run.y, mode_start, mode_run.copy(), times, samples, sample_modes, stats
    )
    rev.duration = run.t
    return rev


def solve_periodic_ivp(model: Model, method: str) -> PeriodicSolution:
    """Iterate revolutions with ``solve_ivp`` until the cycle residual is below tolerance.

    The revolution loop is :func:`recipsim.solve.periodic.solve_revolutions` itself
    (same residual, same plenum update, same stopping rule); only the integrator of a
    revolution is ``solve_ivp``'s. ``steps`` and ``rejected`` are -1 (not reported).

    Raises
    ------
    SolverError
        If ``solve_ivp`` fails or the valves chatter.
    """
    if method not in METHODS:
        raise ValueError(f"unknown solve_ivp method {method!r}; expected one of {METHODS}")

    def integrate(
        model: WorkingModel, y: np.ndarray, mode: np.ndarray, h: float, samples: int
    ) -> tuple[Revolution, float]:
        with warnings.catch_warnings():
            # NaN derivatives of a failed property call are how a step is rejected here
            warnings.simplefilter("ignore", RuntimeWarning)
            return integrate_revolution_ivp(model, y, mode, samples, method), h

    return solve_revolutions(model, integrate=integrate)
