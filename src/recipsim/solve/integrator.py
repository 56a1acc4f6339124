"""Compiled adaptive Dormand-Prince 5(4) integrator with events and discrete modes.

One call integrates a scene from ``t0`` to ``t1`` without returning to Python (each scene
has its own compiled entry, so a case compiles only its own scene's code):

- error control on the first ``n_err`` states except those of zero scale (the others
  are quadratures),
  with per-state absolute tolerances ``atol * scale``;
- a trial step whose stages leave the equation of state's domain (property status
  != 0) is rejected and retried with a smaller step, never a crash;
- events: after each accepted step the scene's event functions are evaluated from
  the last stage (first-same-as-last); a crossing from <= 0 to > 0 is located by the
  Illinois method on a cubic Hermite interpolant, the step is cut there and the
  scene's action switches modes or applies an impact (valve seats and stops are
  never clamped inside the right-hand side);
- samples at given times come from the same Hermite interpolant.

Stiff stretches (``method`` = :data:`METHOD_AUTO`, ``solver.method =
"dopri5_stiff"``): after every accepted DOPRI5 step, Hairer's stiffness
test estimates ``h |lambda|`` from the last two stages (both at ``t + h``); once it has
exceeded 3.25 (DOPRI5's stability boundary on the negative real axis) on
:data:`.step_control.STIFF_AFTER` steps without :data:`.step_control.NONSTIFF_RESET`
non-stiff steps in between,
the integrator continues with the L-stable Rosenbrock-W step of
:mod:`recipsim.solve.stiff` (finite-difference Jacobian of the error-controlled
states, kept for as many accepted steps as amortise its cost, see
:data:`JAC_STAGES_PER_STEP`, and refreshed after a rejection), with
the same error norm, events, impacts, re-step to the event and Hermite dense output.
It returns to DOPRI5 once the step the W-method takes would be inside DOPRI5's
stability region (``h * rho(J) <`` :data:`.step_control.BACK_TO_DOPRI5`, ``rho`` bounded by the
scaled infinity norm of the Jacobian) on :data:`.step_control.NONSTIFF_AFTER` consecutive steps.
At tight tolerances DOPRI5's steps stay inside its stability region, the test never
fires and the integration is pure DOPRI5. ``stats`` records whether a run ended on
W-steps: a revolution continues with the method its predecessor ended with
(:data:`METHOD_AUTO_IN_W`, :func:`recipsim.solve.revolution.integrate_revolution`), since
the test misses a strongly damped mode that holds DOPRI5's step below its boundary.
:data:`METHOD_DOPRI5` never switches, :data:`METHOD_ROSW` uses the W-method throughout
(tests).

Size (over the project's 400 lines): the loop of :func:`scene_entry` is one compiled
function (the step, the events, the samples, the method switch and the interrupt check
share its locals); the pieces that can stand alone are in the modules below.

The pieces: :mod:`.dopri5` (the explicit step and the stiffness test),
:mod:`.stiff` (the Rosenbrock-W step and its Jacobian), :mod:`.events` (event
location), :mod:`.dense_output` (Hermite interpolation and samples) and
:mod:`.step_args` (the scene, tolerance and work-array bundles they take),
:mod:`.step_control` (step-size control and method switching); this module holds the
loop, the event landing and the counters.

Counters in ``stats``: table :data:`STATS` (``ST_*``). Status: 0 done, 1 step size underflow,
2 property failure that smaller steps could not cure, 3 chattering (events at one instant).

The compiled entries, one per scene and one per scene with the W-step, and
:func:`recipsim.solve.scene_entries.integrate`, which picks them, are in
:mod:`.scene_entries`.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numba import njit

from recipsim.model import scene_functions as scene_functions  # the pointer calls' overloads
from recipsim.model.scenes import (
    event_action_for,
    event_values_for,
    rhs_for,
)
from recipsim.model.scenes import scene_rhs as scene_rhs  # re-exported (every scene)
from recipsim.physics.layout_table import Layout
from recipsim.physics.thermo.property_slots import SIGNAL_CHECK
from recipsim.solve.dense_output import hermite, record_samples
from recipsim.solve.dopri5 import dopri5_step, stiffness_estimate
from recipsim.solve.events import any_crossing, locate_first_event
from recipsim.solve.step_args import SceneArgs, Tolerance, new_workspace
from recipsim.solve.step_control import (  # METHOD_*: also the integrator's public names
    METHOD_AUTO,
    METHOD_AUTO_IN_W,
    METHOD_ROSW,
    STIFF_LIMIT,
    count_stiff_step,
    next_step,
    rejected_step,
    switch_method,
)
from recipsim.solve.step_control import (
    METHOD_DOPRI5 as METHOD_DOPRI5,  # re-exported
)
from recipsim.solve.w_gate import EXPLICIT, refresh_jacobian_in, w_step_in

STATS = Layout("integrator statistics")
ST_STATUS = STATS.add("status", "code", "how the run ended (DONE, STEP_UNDERFLOW, ...)")
ST_NFEV = STATS.add("rhs_evaluations", "count", "right-hand-side evaluations")
ST_NACCEPT = STATS.add("steps", "count", "accepted steps")
ST_NREJECT = STATS.add("rejected_steps", "count", "rejected steps")
ST_NEVENTS = STATS.add("events", "count", "located events")
ST_T = STATS.add("time", "s", "time reached")
ST_H = STATS.add("step", "s", "last step size")
ST_NSAMPLES = STATS.add("samples", "count", "output samples written")
ST_NSTIFF = STATS.add("stiff_steps", "count", "accepted Rosenbrock-W steps")
ST_NJAC = STATS.add("jacobians", "count", "finite-difference Jacobians")
ST_IN_W = STATS.add("ended_in_w_step", "-", "1 if the run ended taking Rosenbrock-W steps, else 0")
N_STATS = STATS.size

DONE = 0
STEP_UNDERFLOW = 1
PROPERTY_FAILURE = 2
CHATTERING = 3
#: an explicit entry's stop where the W-step takes over (never the status of :func:`integrate`)
NEEDS_W_STEP = 4
#: the user pressed Ctrl-C (the caller raises KeyboardInterrupt)
INTERRUPTED = 5

#: accepted steps between two questions to the property callback whether the user
#: pressed Ctrl-C: the compiled loop never returns to Python otherwise, so a solve of
#: millions of steps would not see it
SIGNAL_CHECK_STEPS = 2048

#: accepted steps in a row at one instant (events) before the run stops as chattering
MAX_EVENTS_AT_ONE_INSTANT = 50


@njit(cache=True, inline="always")
def _step(w_entry, use_w, code, t, h, y, ynew, scene, tol, work):
    """One DOPRI5 or Rosenbrock-W step: ``(status, error_norm, evaluations)``."""
    if use_w:
        st, err = w_step_in(w_entry, code, t, h, y, ynew, scene, tol, work)
        return st, err, 4
    st, err = dopri5_step(code, t, h, y, ynew, scene, tol, work)
    return st, err, 6


@njit(cache=True, inline="always")
def _apply_event(code, landed, t_event, k_event, y, scene, work):
    """Put ``y`` at the event at ``t_event`` [s] and apply action ``k_event``: ``y``
    becomes the re-step's end ``work.ynew`` if it ``landed``, else the accepted step's
    Hermite interpolant at the event (``work.yint``). Returns whether the event ends
    the integration."""
    end = work.ynew if landed else work.yint
    for i in range(y.shape[0]):
        y[i] = end[i]
    mode, par, ipar, props, pbuf = scene
    rhs_for(code, t_event, y, mode, par, ipar, props, pbuf, work.ftmp, work.aux)
    return event_action_for(code, k_event, y, mode, par, ipar, work.aux)


@njit(cache=True, inline="always")
def _advance(t, h, last, t1, y, ynew, k1, k7, g_old, g_new) -> float:
    """Accept the step without event: ``y`` and the first stage ``k1`` move to its end
    (``ynew``, ``k7``), the event values too; returns the new time [s]."""
    for i in range(y.shape[0]):
        y[i] = ynew[i]
        k1[i] = k7[i]
    for k in range(g_old.shape[0]):
        g_old[k] = g_new[k]
    return t1 if last else t + h


@njit(cache=True)
def _write_stats(stats, result, t, h, i_sample, counts, use_w) -> None:
    """Fill ``stats`` (see ``ST_*``) from the run's status, last time and step [s], the
    number of samples recorded, ``counts`` = (nfev, accepted, rejected, events,
    W-steps, Jacobians) and whether it ended taking W-steps."""
    stats[ST_STATUS] = result
    stats[ST_NFEV] = counts[0]
    stats[ST_NACCEPT] = counts[1]
    stats[ST_NREJECT] = counts[2]
    stats[ST_NEVENTS] = counts[3]
    stats[ST_T] = t
    stats[ST_H] = h
    stats[ST_NSAMPLES] = i_sample
    stats[ST_NSTIFF] = counts[4]
    stats[ST_NJAC] = counts[5]
    stats[ST_IN_W] = 1.0 if use_w else 0.0


def scene_entry(name: str, w_entry: int) -> Any:
    """The compiled entry ``name`` with the W-step flag ``w_entry``: the loop below,
    compiled with the flag as a compile-time constant (numba takes a closure's variables
    as constants; each entry is cached in a file of its own, named after it). A closure
    rather than one loop inlined into each entry: numba's inlining copies the loop's IR
    block by block with its whole scope, which every entry's compilation would pay for.

    The scene comes as the entry's first argument: its functions, compiled on their own
    and called through pointers (:func:`recipsim.model.scene_functions.scene_functions`),
    so one entry serves every scene; or a scene's code as a compile-time constant (a
    caller compiled with it, as ``benchmarks/separate_compilation.py`` does to measure
    the scene inlined into the loop).

    Parameters
    ----------
    name : str
        The entry's name (``integrate_scene``, ``integrate_scene_w``: :mod:`.scene_entries`).
    w_entry : int
        :data:`.w_gate.WITH_W_STEP` for an entry that takes Rosenbrock-W steps,
        :data:`.w_gate.EXPLICIT` for one that runs DOPRI5 only: there
        :data:`METHOD_AUTO` stops with :data:`NEEDS_W_STEP` where it would switch to
        the W-step (``stats`` then holds the time reached and the next step) and
        :data:`METHOD_ROSW` at once.
    """

    @njit(cache=True)
    @_named(name)
    def entry(  # type: ignore[no-untyped-def]
        code,
        t0,
        t1,
        y,
        mode,
        par,
        ipar,
        props,
        pbuf,
        rtol,
        atol,
        scale,
        n_err,
        h_init,
        h_max,
        sample_times,
        samples,
        sample_modes,
        stats,
        method,
    ):
        """Integrate the entry's scene from ``t0`` to ``t1`` in place.

        Parameters
        ----------
        code : SceneFunctions or int
            The scene: its functions
            (:class:`recipsim.model.scene_functions.SceneFunctions`), or its code as a
            compile-time constant (``SCENE_*`` of :mod:`recipsim.model.scenes`).
        t0, t1 : float
            Start and end time [s].
        y : ndarray
            State at ``t0``; overwritten with the state at ``t1`` (or at failure).
        mode : int64 ndarray
            Discrete modes of the scene, updated by events.
        par, ipar : ndarray
            Float and integer parameters of the scene.
        props : first-class function ``(T, rho) -> int32``
            Property callback that fills ``pbuf``.
        rtol, atol : float
            Relative tolerance and absolute tolerance on scaled states.
        scale : ndarray
            Typical magnitude of each state (absolute tolerance is ``atol * scale``).
        n_err : int
            Number of leading states under error control.
        h_init, h_max : float
            First trial step and largest step [s].
        sample_times : ndarray
            Increasing times in [t0, t1) at which to record the state.
        samples, sample_modes : ndarray
            Output, one row per sample time.
        stats : ndarray
            Output counters (see ``ST_*``).
        method : int
            :data:`METHOD_DOPRI5`, :data:`METHOD_AUTO` (switch to the Rosenbrock-W step
            on stiff stretches), :data:`METHOD_AUTO_IN_W` (the same, starting with the
            W-step: the continuation after :data:`NEEDS_W_STEP`) or :data:`METHOD_ROSW`
            (Rosenbrock-W throughout).
        """
        scene = SceneArgs(mode, par, ipar, props, pbuf)
        tol = Tolerance(rtol, atol, scale, n_err)
        work = new_workspace(y.shape[0], n_err)
        # the arrays the loop touches on every step, taken out of the bundle once
        k1 = work.stages[0]
        k6 = work.stages[5]
        k7 = work.stages[6]
        ynew = work.ynew
        ytmp = work.ytmp
        yint = work.yint
        aux = work.aux
        g_old = work.g_old
        g_new = work.g_new
        # counts: evaluations, accepted, rejected, events, W-steps, Jacobians
        counts = np.zeros(6, dtype=np.int64)
        n_samples = sample_times.shape[0]
        i_sample = 0
        while i_sample < n_samples and sample_times[i_sample] < t0:
            i_sample += 1

        t = t0
        h = min(h_init, h_max)
        h_min = 1e-14 * max(1.0, abs(t1))
        status = rhs_for(code, t, y, mode, par, ipar, props, pbuf, k1, aux)
        counts[0] += 1
        if status != 0:
            stats[ST_STATUS] = PROPERTY_FAILURE
            stats[ST_T] = t
            return
        event_values_for(code, y, mode, par, ipar, aux, g_old)
        events_here = 0
        t_last_event = -1e300
        result = DONE
        property_failed = False  # the last trial step failed in the property call
        use_w = method == METHOD_ROSW or method == METHOD_AUTO_IN_W
        if method == METHOD_AUTO_IN_W:
            method = METHOD_AUTO
        n_stiff = 0  # DOPRI5 steps that looked stiff
        n_nonstiff = 0  # DOPRI5 steps that did not (W: steps DOPRI5 could have taken)
        jac_age = -1  # accepted steps since the Jacobian was built (-1: none for this y)
        just_rejected = False
        jac_life = 1  # accepted steps a Jacobian is kept
        rho_jac = 0.0
        # An event located in a step is landed on by re-taking the step from its start to
        # the event (the states and quadratures then see a smooth right-hand side, no
        # interpolation across the kink), through the one step call below: its code is
        # compiled once (a second call site would compile the step again).
        landing = False
        h_accepted = h  # the accepted step [s] while its event is landed on
        k_event = -1  # the event located in the accepted step, and its time [s]
        t_event = t0
        last = False  # the step ends at t1
        while t < t1:
            if not landing:
                if use_w and w_entry == EXPLICIT:
                    result = NEEDS_W_STEP  # the entry with the W-step goes on from t
                    break
                if h < h_min:
                    result = PROPERTY_FAILURE if property_failed else STEP_UNDERFLOW
                    break
                last = False
                if t + h >= t1:
                    h = t1 - t
                    last = True
                if use_w and (jac_age < 0 or jac_age >= jac_life):
                    stj, nj, jac_life, rho_jac = refresh_jacobian_in(
                        w_entry, code, t, y, scene, tol, work
                    )
                    counts[0] += nj
                    counts[5] += 1
                    jac_age = 0
                    if stj != 0:
                        result = PROPERTY_FAILURE
                        break
            if landing and h <= 0.0:
                st, err, ne = 1, 0.0, 0  # the event at the step's start: no re-step
            else:
                st, err, ne = _step(w_entry, use_w, code, t, h, y, ynew, scene, tol, work)
            counts[0] += ne
            if landing:
                # the re-step's end, or the interpolant if it failed
                landing = False
                h = h_accepted
                terminal = _apply_event(code, st == 0, t_event, k_event, y, scene, work)
                counts[0] += 1
                counts[3] += 1
                jac_age = -1  # new mode or impact: the Jacobian is rebuilt if needed
                if t_event - t_last_event < 1e-12 * max(1.0, abs(t_event)):
                    events_here += 1
                    if events_here > MAX_EVENTS_AT_ONE_INSTANT:
                        result = CHATTERING
                        t = t_event
                        break
                else:
                    events_here = 0
                t_last_event = t_event
                t = t_event
                st = rhs_for(code, t, y, mode, par, ipar, props, pbuf, k1, aux)
                counts[0] += 1
                if st != 0:
                    result = PROPERTY_FAILURE
                    break
                # a new mode's events fire only on a fresh crossing from <= 0 to > 0
                event_values_for(code, y, mode, par, ipar, aux, g_old)
                if t >= t1 or terminal:
                    break
                continue
            property_failed = st > 0
            if st != 0 or not (err <= 1.0):  # also catches NaN
                counts[2] += 1
                h = rejected_step(h, st, err, use_w)
                if use_w and jac_age > 0 and just_rejected:
                    jac_age = -1  # rejected again at a smaller step: the Jacobian is stale
                just_rejected = True
                continue
            if method == METHOD_AUTO and not use_w:
                stiff_step = stiffness_estimate(h, y, ynew, ytmp, k6, k7, tol) > STIFF_LIMIT
                n_stiff, n_nonstiff = count_stiff_step(stiff_step, n_stiff, n_nonstiff)

            event_values_for(code, ynew, mode, par, ipar, aux, g_new)
            k_event = -1
            t_event = t + h
            if any_crossing(g_old, g_new):
                k_event, t_event, ne = locate_first_event(code, t, h, y, ynew, scene, work)
                counts[0] += ne
            t_end = t + h if k_event < 0 else t_event
            i_sample = record_samples(
                t, h, y, k1, ynew, k7, t_end, t1, mode, sample_times, i_sample, samples,
                sample_modes, yint,
            )  # fmt: skip
            counts[1] += 1
            if counts[1] % SIGNAL_CHECK_STEPS == 0 and props(SIGNAL_CHECK, 0.0) != 0:
                result = INTERRUPTED
                break
            if use_w:
                counts[4] += 1
                jac_age += 1
            if k_event < 0:
                t = _advance(t, h, last, t1, y, ynew, k1, k7, g_old, g_new)
            else:
                # the fallback first (the re-step overwrites the stages), then the re-step
                hermite(t, h, y, k1, ynew, k7, t_event, yint)
                landing = True
                h_accepted = h
                h = t_event - t
                continue
            h_done = h
            h = next_step(h, err, use_w, h_max)
            if just_rejected and use_w:
                # no growth right after a rejected W-step (it would be rejected again)
                h = min(h, h_done)
            just_rejected = False
            use_w, n_stiff, n_nonstiff, to_w = switch_method(
                method, use_w, h, rho_jac, n_stiff, n_nonstiff
            )
            if to_w:
                jac_age = -1

        _write_stats(stats, result, t, h, i_sample, counts, use_w)

    return entry


def _named(name: str) -> Any:
    """A decorator that names a function ``name`` (numba's cache names its file so)."""

    def rename(function: Any) -> Any:
        function.__name__ = function.__qualname__ = name
        return function

    return rename
