"""The Dormand-Prince 5(4) step and Hairer's stiffness test on it.

:func:`dopri5_step` takes one explicit step with the first-same-as-last property:
``stages[0]`` holds f(t, y) on entry and ``stages[6] = f(t + h, y_new)`` on exit, which
the integrator reuses as the next step's first stage, for the Hermite dense output and
for the event functions at the step's end. :func:`stiffness_estimate` estimates
``h |lambda|`` from the last two stages (Hairer & Wanner, Solving ODEs I, II.10).
"""

from __future__ import annotations

import math

from numba import njit

from recipsim.model.scenes import rhs_for

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


@njit(cache=True, inline="always")
def dopri5_step(code, t, h, y, ynew, scene, tol, work):
    """One Dormand-Prince step of ``h`` [s] from (t [s], y).

    Parameters
    ----------
    code : int
        The scene's code, a compile-time constant (:func:`recipsim.model.scenes.rhs_for`).
    t, h : float
        Start time and step [s].
    y : ndarray
        State at ``t``; ``work.stages[0]`` holds f(t, y) on entry.
    ynew : ndarray
        Output: the state at ``t + h``.
    scene : SceneArgs
        The scene (:mod:`recipsim.solve.step_args`).
    tol : Tolerance
        Error control.
    work : Workspace
        Work arrays; on success ``work.stages[6] = f(t + h, ynew)`` and ``work.ytmp``
        holds the sixth stage's state (used by :func:`stiffness_estimate`).

    Returns
    -------
    status : int
        0 on success, else the property status of the failing stage.
    error_norm : float
        Root-mean-square of the scaled local error estimate [-] (inf on failure).
    """
    n = y.shape[0]
    # unpacked once per step: the right-hand side then takes the arrays themselves
    mode, par, ipar, props, pbuf = scene
    stages = work.stages
    ytmp = work.ytmp
    aux = work.aux
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
    st = rhs_for(code, t + _C2 * h, ytmp, mode, par, ipar, props, pbuf, k2, aux)
    if st != 0:
        return st, math.inf
    for i in range(n):
        ytmp[i] = y[i] + h * (_A31 * k1[i] + _A32 * k2[i])
    st = rhs_for(code, t + _C3 * h, ytmp, mode, par, ipar, props, pbuf, k3, aux)
    if st != 0:
        return st, math.inf
    for i in range(n):
        ytmp[i] = y[i] + h * (_A41 * k1[i] + _A42 * k2[i] + _A43 * k3[i])
    st = rhs_for(code, t + _C4 * h, ytmp, mode, par, ipar, props, pbuf, k4, aux)
    if st != 0:
        return st, math.inf
    for i in range(n):
        ytmp[i] = y[i] + h * (_A51 * k1[i] + _A52 * k2[i] + _A53 * k3[i] + _A54 * k4[i])
    st = rhs_for(code, t + _C5 * h, ytmp, mode, par, ipar, props, pbuf, k5, aux)
    if st != 0:
        return st, math.inf
    for i in range(n):
        ytmp[i] = y[i] + h * (
            _A61 * k1[i] + _A62 * k2[i] + _A63 * k3[i] + _A64 * k4[i] + _A65 * k5[i]
        )
    st = rhs_for(code, t + h, ytmp, mode, par, ipar, props, pbuf, k6, aux)
    if st != 0:
        return st, math.inf
    for i in range(n):
        ynew[i] = y[i] + h * (_B1 * k1[i] + _B3 * k3[i] + _B4 * k4[i] + _B5 * k5[i] + _B6 * k6[i])
    st = rhs_for(code, t + h, ynew, mode, par, ipar, props, pbuf, k7, aux)
    if st != 0:
        return st, math.inf
    scale = tol.scale
    err = 0.0
    m = 0
    for i in range(tol.n_err):
        if scale[i] == 0.0:  # a quadrature inside the controlled range
            continue
        e = h * (_E1 * k1[i] + _E3 * k3[i] + _E4 * k4[i] + _E5 * k5[i] + _E6 * k6[i] + _E7 * k7[i])
        sc = tol.atol * scale[i] + tol.rtol * max(abs(y[i]), abs(ynew[i]))
        err += (e / sc) ** 2
        m += 1
    return 0, math.sqrt(err / max(m, 1))


@njit(cache=True, inline="always")
def stiffness_estimate(h, y, ynew, ytmp, k6, k7, tol) -> float:
    """Hairer's estimate of ``h |lambda|`` [-] after an accepted :func:`dopri5_step` of
    ``h`` [s] from ``y`` to ``ynew``, from its last two stages (both at t + h: the sixth
    ``k6`` at ``ytmp``, the seventh ``k7`` at ``ynew``). Above 3.25 the step is bounded
    by DOPRI5's stability, not its accuracy."""
    scale = tol.scale
    num = 0.0
    den = 0.0
    for i in range(tol.n_err):
        if scale[i] == 0.0:
            continue
        sc = tol.atol * scale[i] + tol.rtol * max(abs(y[i]), abs(ynew[i]))
        num += ((k7[i] - k6[i]) / sc) ** 2
        den += ((ynew[i] - ytmp[i]) / sc) ** 2
    if den <= 0.0:
        return 0.0
    return h * math.sqrt(num / den)
