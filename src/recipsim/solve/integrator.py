"""Compiled adaptive Dormand-Prince 5(4) integrator with events and discrete modes.

One call integrates a scene from ``t0`` to ``t1`` without returning to Python:

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
:data:`STIFF_AFTER` steps without :data:`NONSTIFF_RESET` non-stiff steps in between,
the integrator continues with the L-stable Rosenbrock-W step of
:mod:`recipsim.solve.stiff` (finite-difference Jacobian of the error-controlled
states, kept for as many accepted steps as amortise its cost, see
:data:`JAC_STAGES_PER_STEP`, and refreshed after a rejection), with
the same error norm, events, impacts, re-step to the event and Hermite dense output.
It returns to DOPRI5 once the step the W-method takes would be inside DOPRI5's
stability region (``h * rho(J) <`` :data:`BACK_TO_DOPRI5`, ``rho`` bounded by the
scaled infinity norm of the Jacobian) on :data:`NONSTIFF_AFTER` consecutive steps.
At tight tolerances DOPRI5's steps stay inside its stability region, the test never
fires and the integration is pure DOPRI5. :data:`METHOD_DOPRI5` never switches,
:data:`METHOD_ROSW` uses the W-method throughout (tests).

Status codes returned in ``stats[ST_STATUS]``: 0 done, 1 step size underflow,
2 property failure that smaller steps could not cure, 3 too many events at one
instant (chattering).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from recipsim.model.scenes import N_AUX, N_EVENTS, scene_event_action, scene_event_values, scene_rhs
from recipsim.solve.stiff import ERR_ORDER, jacobian_fd, spectral_bound, w_step

ST_STATUS = 0
ST_NFEV = 1
ST_NACCEPT = 2
ST_NREJECT = 3
ST_NEVENTS = 4
ST_T = 5
ST_H = 6
ST_NSAMPLES = 7
ST_NSTIFF = 8  # accepted Rosenbrock-W steps
ST_NJAC = 9  # finite-difference Jacobians
N_STATS = 10

#: ``method`` of :func:`integrate`
METHOD_DOPRI5 = 0
METHOD_AUTO = 1
METHOD_ROSW = 2
#: stiffness switching (see the module docstring)
STIFF_LIMIT = 3.25
STIFF_AFTER = 5
NONSTIFF_RESET = 6
BACK_TO_DOPRI5 = 2.0
NONSTIFF_AFTER = 3
#: A Jacobian of ``n_j`` finite-difference evaluations is kept for
#: ``max(1, n_j // JAC_STAGES_PER_STEP)`` accepted W-steps (each costs 4 evaluations), so
#: building it costs at most about two steps' worth: every step for the 4-6 gas states
#: of a rigid crank, every 3-4 steps for the 30-odd states of a crank train on oil
#: films (1.6x fewer evaluations there; the W-method keeps its order with a stale matrix).
JAC_STAGES_PER_STEP = 8

DONE = 0
STEP_UNDERFLOW = 1
PROPERTY_FAILURE = 2
CHATTERING = 3

# Dormand-Prince 5(4) tableau
_C2, _C3, _C4, _C5 = 0.2, 0.3, 0.8, 8.0 / 9.0
_A21 = 0.2
_A31, _A32 = 3.0 / 40.0, 9.0 / 40.0
_A41, _A42, _A43 = 44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0
_A51, _A52, _A53, _A54 = 19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0
_A61, _A62, _A63, _A64, _A65 = (
    9017.0 / 3168.0,
    -355.0 / 33.0,
    46732.0 / 5247.0,
    49.0 / 176.0,
    -5103.0 / 18656.0,
)
_B1, _B3, _B4, _B5, _B6 = 35.0 / 384.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0
_E1, _E3, _E4, _E5, _E6, _E7 = (
    71.0 / 57600.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
)


@njit(cache=True)
def _dp_step(
    t, h, y, mode, par, ipar, props, pbuf, rtol, atol, scale, n_err, stages, ytmp, ynew, aux
):
    """One Dormand-Prince step from (t, y); ``stages[0]`` holds f(t, y) on entry.

    Returns ``(status, error_norm)``; on success ``ynew`` and ``stages[6] = f(t + h, ynew)``.
    """
    n = y.shape[0]
    k1, k2, k3, k4, k5, k6, k7 = (
        stages[0],
        stages[1],
        stages[2],
        stages[3],
        stages[4],
        stages[5],
        stages[6],
    )
    for i in range(n):
        ytmp[i] = y[i] + h * _A21 * k1[i]
    st = scene_rhs(t + _C2 * h, ytmp, mode, par, ipar, props, pbuf, k2, aux)
    if st != 0:
        return st, math.inf
    for i in range(n):
        ytmp[i] = y[i] + h * (_A31 * k1[i] + _A32 * k2[i])
    st = scene_rhs(t + _C3 * h, ytmp, mode, par, ipar, props, pbuf, k3, aux)
    if st != 0:
        return st, math.inf
    for i in range(n):
        ytmp[i] = y[i] + h * (_A41 * k1[i] + _A42 * k2[i] + _A43 * k3[i])
    st = scene_rhs(t + _C4 * h, ytmp, mode, par, ipar, props, pbuf, k4, aux)
    if st != 0:
        return st, math.inf
    for i in range(n):
        ytmp[i] = y[i] + h * (_A51 * k1[i] + _A52 * k2[i] + _A53 * k3[i] + _A54 * k4[i])
    st = scene_rhs(t + _C5 * h, ytmp, mode, par, ipar, props, pbuf, k5, aux)
    if st != 0:
        return st, math.inf
    for i in range(n):
        ytmp[i] = y[i] + h * (
            _A61 * k1[i] + _A62 * k2[i] + _A63 * k3[i] + _A64 * k4[i] + _A65 * k5[i]
        )
    st = scene_rhs(t + h, ytmp, mode, par, ipar, props, pbuf, k6, aux)
    if st != 0:
        return st, math.inf
    for i in range(n):
        ynew[i] = y[i] + h * (_B1 * k1[i] + _B3 * k3[i] + _B4 * k4[i] + _B5 * k5[i] + _B6 * k6[i])
    st = scene_rhs(t + h, ynew, mode, par, ipar, props, pbuf, k7, aux)
    if st != 0:
        return st, math.inf
    err = 0.0
    m = 0
    for i in range(n_err):
        if scale[i] == 0.0:  # a quadrature inside the controlled range
            continue
        e = h * (_E1 * k1[i] + _E3 * k3[i] + _E4 * k4[i] + _E5 * k5[i] + _E6 * k6[i] + _E7 * k7[i])
        sc = atol * scale[i] + rtol * max(abs(y[i]), abs(ynew[i]))
        err += (e / sc) ** 2
        m += 1
    return 0, math.sqrt(err / max(m, 1))


@njit(cache=True)
def _hermite(t0, h, y0, f0, y1, f1, tau, out) -> None:
    """Cubic Hermite interpolation between (t0, y0, f0) and (t0 + h, y1, f1)."""
    s = (tau - t0) / h
    h00 = (1.0 + 2.0 * s) * (1.0 - s) ** 2
    h10 = s * (1.0 - s) ** 2
    h01 = s * s * (3.0 - 2.0 * s)
    h11 = s * s * (s - 1.0)
    for i in range(y0.shape[0]):
        out[i] = h00 * y0[i] + h * h10 * f0[i] + h01 * y1[i] + h * h11 * f1[i]


@njit(cache=True)
def _step(
    use_w,
    t,
    h,
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
    jac,
    lu,
    piv,
    stages,
    ytmp,
    ynew,
    aux,
):
    """One DOPRI5 or Rosenbrock-W step: ``(status, error_norm, evaluations)``."""
    if use_w:
        st, err = w_step(
            t,
            h,
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
            jac,
            lu,
            piv,
            stages,
            ytmp,
            ynew,
            aux,
        )
        return st, err, 4
    st, err = _dp_step(
        t, h, y, mode, par, ipar, props, pbuf, rtol, atol, scale, n_err, stages, ytmp, ynew, aux
    )
    return st, err, 6


@njit(cache=True)
def _stiffness(h, y, ynew, ytmp, k6, k7, rtol, atol, scale, n_err) -> float:
    """Hairer's estimate of ``h |lambda|`` from DOPRI5's last two stages (both at t + h)."""
    num = 0.0
    den = 0.0
    for i in range(n_err):
        if scale[i] == 0.0:
            continue
        sc = atol * scale[i] + rtol * max(abs(y[i]), abs(ynew[i]))
        num += ((k7[i] - k6[i]) / sc) ** 2
        den += ((ynew[i] - ytmp[i]) / sc) ** 2
    if den <= 0.0:
        return 0.0
    return h * math.sqrt(num / den)


@njit(cache=True)
def integrate(
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
    method=METHOD_DOPRI5,
):
    """Integrate a scene from ``t0`` to ``t1`` in place.

    Parameters
    ----------
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
        on stiff stretches) or :data:`METHOD_ROSW` (Rosenbrock-W throughout).
    """
    n = y.shape[0]
    stages = np.empty((7, n))  # Dormand-Prince stages: f(t, y) first, f(t + h, y_new) last
    k1 = stages[0]
    k6 = stages[5]
    k7 = stages[6]
    ytmp = np.empty(n)
    ynew = np.empty(n)
    yint = np.empty(n)
    ystep = np.empty(n)
    ftmp = np.empty(n)
    aux = np.zeros(N_AUX)
    g_old = np.empty(N_EVENTS)
    g_new = np.empty(N_EVENTS)
    g_int = np.empty(N_EVENTS)
    jac = np.zeros((n, n_err))
    lu = np.empty((n_err, n_err))
    piv = np.empty(n_err, dtype=np.int64)
    nfev = 0
    n_acc = 0
    n_rej = 0
    n_ev = 0
    n_w = 0
    n_jac = 0
    n_samples = sample_times.shape[0]
    i_sample = 0
    while i_sample < n_samples and sample_times[i_sample] < t0:
        i_sample += 1

    t = t0
    h = min(h_init, h_max)
    h_min = 1e-14 * max(1.0, abs(t1))
    status = scene_rhs(t, y, mode, par, ipar, props, pbuf, k1, aux)
    nfev += 1
    if status != 0:
        stats[ST_STATUS] = PROPERTY_FAILURE
        stats[ST_T] = t
        return
    scene_event_values(y, mode, par, ipar, aux, g_old)
    events_here = 0
    t_last_event = -1e300
    result = DONE
    property_failed = False  # the last trial step failed in the property call
    use_w = method == METHOD_ROSW
    n_stiff = 0  # DOPRI5 steps that looked stiff
    n_nonstiff = 0  # DOPRI5 steps that did not (W: steps DOPRI5 could have taken)
    jac_age = -1  # accepted steps since the Jacobian was built (-1: none for this y)
    jac_life = 1  # accepted steps a Jacobian is kept
    rho_jac = 0.0
    while t < t1:
        if h < h_min:
            result = PROPERTY_FAILURE if property_failed else STEP_UNDERFLOW
            break
        last = False
        if t + h >= t1:
            h = t1 - t
            last = True
        if use_w and (jac_age < 0 or jac_age >= jac_life):
            stj, nj = jacobian_fd(
                t, y, k1, mode, par, ipar, props, pbuf, scale, n_err, jac, ytmp, ftmp, aux
            )
            nfev += nj
            n_jac += 1
            jac_age = 0
            jac_life = max(1, nj // JAC_STAGES_PER_STEP)
            rho_jac = spectral_bound(jac, scale, n_err)
            if stj != 0:
                result = PROPERTY_FAILURE
                break
        st, err, ne = _step(
            use_w,
            t,
            h,
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
            jac,
            lu,
            piv,
            stages,
            ytmp,
            ynew,
            aux,
        )
        nfev += ne
        property_failed = st > 0
        if st != 0:
            n_rej += 1
            h *= 0.25
            if use_w and jac_age > 0:
                jac_age = -1
            continue
        if not (err <= 1.0):  # also catches NaN
            n_rej += 1
            if err != err:
                h *= 0.25
            elif use_w:
                h *= max(0.2, 0.9 * err ** (-1.0 / ERR_ORDER))
            else:
                h *= max(0.2, 0.9 * err**-0.2)
            if use_w and jac_age > 0:
                jac_age = -1  # a stale Jacobian may be why: refresh it
            continue

        # stiffness test on the accepted DOPRI5 step (k6, ytmp: its sixth stage)
        if method == METHOD_AUTO and not use_w:
            if _stiffness(h, y, ynew, ytmp, k6, k7, rtol, atol, scale, n_err) > STIFF_LIMIT:
                n_stiff += 1
                n_nonstiff = 0
            else:
                n_nonstiff += 1
                if n_nonstiff >= NONSTIFF_RESET:
                    n_stiff = 0

        # accepted: look for events on [t, t + h]
        scene_event_values(ynew, mode, par, ipar, aux, g_new)
        k_event = -1
        t_event = t + h
        for k in range(N_EVENTS):
            if g_old[k] <= 0.0 and g_new[k] > 0.0:
                # Illinois on the interpolant
                ta, tb = t, t + h
                ga, gb = g_old[k], g_new[k]
                side = 0
                for _ in range(80):
                    tm = (ta * gb - tb * ga) / (gb - ga)
                    if not (ta < tm < tb):
                        tm = 0.5 * (ta + tb)
                    _hermite(t, h, y, k1, ynew, k7, tm, yint)
                    st2 = scene_rhs(tm, yint, mode, par, ipar, props, pbuf, ftmp, aux)
                    nfev += 1
                    if st2 != 0:
                        tm = 0.5 * (ta + tb)
                        _hermite(t, h, y, k1, ynew, k7, tm, yint)
                        st2 = scene_rhs(tm, yint, mode, par, ipar, props, pbuf, ftmp, aux)
                        nfev += 1
                    scene_event_values(yint, mode, par, ipar, aux, g_int)
                    gm = g_int[k]
                    if gm > 0.0:
                        tb, gb = tm, gm
                        if side == -1:
                            ga *= 0.5
                        side = -1
                    else:
                        ta, ga = tm, gm
                        if side == 1:
                            gb *= 0.5
                        side = 1
                    if tb - ta <= 1e-13 * max(1.0, abs(tb)) + 1e-15:
                        break
                if tb < t_event or k_event < 0:
                    t_event = tb
                    k_event = k

        t_end = t + h if k_event < 0 else t_event
        # samples on (t, t_end]
        while i_sample < n_samples and sample_times[i_sample] <= t_end:
            if sample_times[i_sample] >= t1:
                break
            _hermite(t, h, y, k1, ynew, k7, sample_times[i_sample], yint)
            for i in range(n):
                samples[i_sample, i] = yint[i]
            for i in range(mode.shape[0]):
                sample_modes[i_sample, i] = mode[i]
            i_sample += 1
        n_acc += 1
        if use_w:
            n_w += 1
            jac_age += 1
        if k_event < 0:
            t = t + h
            for i in range(n):
                y[i] = ynew[i]
                k1[i] = k7[i]
            for k in range(N_EVENTS):
                g_old[k] = g_new[k]
            if last:
                t = t1
        else:
            # re-take the step exactly to the event: the states and quadratures then see a
            # smooth right-hand side (no interpolation across the kink at the event)
            h_event = t_event - t
            _hermite(t, h, y, k1, ynew, k7, t_event, yint)  # fallback if the re-step fails
            if h_event > 0.0:
                st, err, ne = _step(
                    use_w,
                    t,
                    h_event,
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
                    jac,
                    lu,
                    piv,
                    stages,
                    ytmp,
                    ystep,
                    aux,
                )
                nfev += ne
                if st == 0:
                    for i in range(n):
                        yint[i] = ystep[i]
            for i in range(n):
                y[i] = yint[i]
            scene_rhs(t_event, y, mode, par, ipar, props, pbuf, ftmp, aux)
            terminal = scene_event_action(k_event, y, mode, par, ipar, aux)
            n_ev += 1
            jac_age = -1  # new mode or impact: the Jacobian is rebuilt if needed
            if t_event - t_last_event < 1e-12 * max(1.0, abs(t_event)):
                events_here += 1
                if events_here > 50:
                    result = CHATTERING
                    t = t_event
                    break
            else:
                events_here = 0
            t_last_event = t_event
            t = t_event
            st = scene_rhs(t, y, mode, par, ipar, props, pbuf, k1, aux)
            nfev += 2
            if st != 0:
                result = PROPERTY_FAILURE
                break
            # a new mode's events fire only on a fresh crossing from <= 0 to > 0
            scene_event_values(y, mode, par, ipar, aux, g_old)
            if t >= t1 or terminal:
                break
            continue
        if use_w:
            if err > 0.0:
                fac = min(5.0, max(0.2, 0.9 * err ** (-1.0 / ERR_ORDER)))
            else:
                fac = 5.0
            h = min(h * fac, h_max)
            if method == METHOD_AUTO:
                # back to DOPRI5 once it could take the step the W-method takes
                if h * rho_jac < BACK_TO_DOPRI5:
                    n_nonstiff += 1
                    if n_nonstiff >= NONSTIFF_AFTER:
                        use_w = False
                        n_stiff = 0
                        n_nonstiff = 0
                else:
                    n_nonstiff = 0
            continue
        if err > 0.0:
            fac = min(5.0, max(0.2, 0.9 * err**-0.2))
        else:
            fac = 5.0
        h = min(h * fac, h_max)
        if method == METHOD_AUTO and n_stiff >= STIFF_AFTER:
            use_w = True
            jac_age = -1
            n_stiff = 0
            n_nonstiff = 0

    stats[ST_STATUS] = result
    stats[ST_NFEV] = nfev
    stats[ST_NACCEPT] = n_acc
    stats[ST_NREJECT] = n_rej
    stats[ST_NEVENTS] = n_ev
    stats[ST_T] = t
    stats[ST_H] = h
    stats[ST_NSAMPLES] = i_sample
    stats[ST_NSTIFF] = n_w
    stats[ST_NJAC] = n_jac
