"""Linearly implicit step for the stiff stretches of a revolution: the Rosenbrock-W
method ROS34PW2 (Rang & Angermann 2005) with a finite-difference Jacobian.

Why: while the discharge valve is open near top dead centre the clearance gas sees the
port's flow conductance; the cylinder-state Jacobian then has eigenvalues up to a few
1e6 1/s and DOPRI5's stability region, not its accuracy, bounds the step (0.015-0.04
deg). ROS34PW2 is L-stable, so its step follows the accuracy of the valve and gas
motion instead.

The method (4 stages, order 3, embedded order 2, stiffly accurate) is a W-method: it
keeps its order with *any* matrix in place of the Jacobian. That allows

- a Jacobian with respect to the error-controlled states only (forward differences,
  one right-hand side per state of nonzero scale): the quadratures and zero-scale
  states do not feed back, so their columns are zero and the iteration matrix is
  block lower triangular: only its block on the states of nonzero scale is factorised
  (28 x 28 on the coupled lubricated scene, whose 46 states include 18 quadratures:
  a fifth of the full matrix's factorisation, which was half of the solve's time
  outside the right-hand side), the others' rows are solved for explicitly. The
  quadratures' rows are kept: their stages then see the same linearisation as the gas
  states they integrate (without them the cycle's mass and energy balances close 100x
  worse);
- no time derivative of the right-hand side (the autonomised system's approximate
  Jacobian has a zero time column);
- reusing a Jacobian over several steps (refreshed after a rejection).

Transformed form (Hairer & Wanner, Solving ODEs II, IV.7, with ``u_i = h sum_j
gamma_ij k_j``)::

    (I / (h gamma) - J) u_i = f(t + alpha_i h, y + sum_j a_ij u_j) + sum_j c_ij u_j / h
    y_new = y + sum_i m_i u_i,   error = sum_i (m_i - mhat_i) u_i

Cost per step: 3 new stages and ``f(t + h, y_new)`` (the next step's first stage, and
the Hermite dense output and event functions at the step's end, as for DOPRI5).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from recipsim.model.scenes import rhs_for

# ---- ROS34PW2: alpha (stage abscissae), Gamma (lower triangular, gamma on the diagonal),
# ---- b (order 3) and bhat (order 2)
GAMMA = 0.435866521508459
_ALPHA = np.array(
    [
        [0.0, 0.0, 0.0, 0.0],
        [0.87173304301691801, 0.0, 0.0, 0.0],
        [0.84457060015369423, -0.11299064236484185, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
    ]
)
_GAMMA = np.array(
    [
        [GAMMA, 0.0, 0.0, 0.0],
        [-0.87173304301691801, GAMMA, 0.0, 0.0],
        [-0.90338057013044082, 0.054180672388095326, GAMMA, 0.0],
        [0.24212380706095346, -1.2232505839045147, 0.54526025533510214, GAMMA],
    ]
)
_B = np.array([0.24212380706095346, -1.2232505839045147, 1.5452602553351020, GAMMA])
_BHAT = np.array([0.37810903145819369, -0.096042292212423178, 0.5, 0.2179332607542295])


def transformed_tableau() -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``(a, c, m, e, alpha_sum)`` of the transformed form (see the module docstring)."""
    gi = np.linalg.inv(_GAMMA)
    a = _ALPHA @ gi
    c = np.diag(1.0 / np.diag(_GAMMA)) - gi
    m = _B @ gi
    mhat = _BHAT @ gi
    return a, c, m, m - mhat, _ALPHA.sum(axis=1)


_a, _c, _m, _e, _alpha_sum = transformed_tableau()
_A21 = float(_a[1, 0])
_A31, _A32 = float(_a[2, 0]), float(_a[2, 1])
_A41, _A42, _A43 = float(_a[3, 0]), float(_a[3, 1]), float(_a[3, 2])
_C21 = float(_c[1, 0])
_C31, _C32 = float(_c[2, 0]), float(_c[2, 1])
_C41, _C42, _C43 = float(_c[3, 0]), float(_c[3, 1]), float(_c[3, 2])
_M1, _M2, _M3, _M4 = (float(v) for v in _m)
_E1, _E2, _E3, _E4 = (float(v) for v in _e)
_AL2, _AL3, _AL4 = float(_alpha_sum[1]), float(_alpha_sum[2]), float(_alpha_sum[3])
del _a, _c, _m, _e, _alpha_sum

#: Order of the embedded error estimate plus one (step-size exponent -1/ERR_ORDER).
ERR_ORDER = 3.0
#: Relative size of the finite-difference perturbation.
_FD_REL = 1e-7


@njit(cache=True)
def jacobian_fd(code, t, y, f0, scene, tol, work):
    """Forward-difference Jacobian ``work.jac[i, j]`` of every derivative ``i`` with
    respect to the first ``tol.n_err`` states ``j`` (columns of zero scale, quadratures,
    stay zero).

    ``code`` is the scene's code, a compile-time constant
    (:func:`recipsim.model.scenes.rhs_for`); ``f0`` is f(t [s], y); ``scene`` a
    :class:`recipsim.solve.step_args.SceneArgs`,
    ``tol`` a :class:`~recipsim.solve.step_args.Tolerance`, ``work`` a
    :class:`~recipsim.solve.step_args.Workspace` (``ytmp``, ``ftmp`` and ``aux`` are
    overwritten). Returns ``(status, evaluations)``; status != 0 if a perturbed state
    left the property model in both directions.
    """
    mode, par, ipar, props, pbuf = scene
    jac = work.jac
    ytmp = work.ytmp
    ftmp = work.ftmp
    aux = work.aux
    scale = tol.scale
    n = y.shape[0]
    for i in range(n):
        ytmp[i] = y[i]
    nfev = 0
    for j in range(tol.n_err):
        if scale[j] == 0.0 or f0[j] == 0.0:
            # a quadrature, or a state its mode holds fixed (a seated reed): its
            # increments u_j stay zero, so its column never acts
            for i in range(n):
                jac[i, j] = 0.0
            continue
        d = _FD_REL * max(abs(y[j]), scale[j])
        ytmp[j] = y[j] + d
        st = rhs_for(code, t, ytmp, mode, par, ipar, props, pbuf, ftmp, aux)
        nfev += 1
        if st != 0:
            d = -d
            ytmp[j] = y[j] + d
            st = rhs_for(code, t, ytmp, mode, par, ipar, props, pbuf, ftmp, aux)
            nfev += 1
            if st != 0:
                ytmp[j] = y[j]
                return st, nfev
        d = ytmp[j] - y[j]  # the increment actually represented
        for i in range(n):
            jac[i, j] = (ftmp[i] - f0[i]) / d
        ytmp[j] = y[j]
    return 0, nfev


@njit(cache=True)
def spectral_bound(jac, scale, n_err) -> float:
    """Bound on the spectral radius of the Jacobian [1/s]: the infinity norm of
    ``D^-1 J D`` with ``D`` the states' scales (zero-scale states left out)."""
    rho = 0.0
    for i in range(n_err):
        if scale[i] == 0.0:
            continue
        row = 0.0
        for j in range(n_err):
            if scale[j] != 0.0:
                row += abs(jac[i, j]) * scale[j]
        rho = max(rho, row / scale[i])
    return rho


@njit(cache=True)
def _lu_factor(a, piv, n) -> bool:
    """In-place LU factorisation with partial pivoting of ``a[:n, :n]``; False if singular."""
    for k in range(n):
        p = k
        big = abs(a[k, k])
        for i in range(k + 1, n):
            if abs(a[i, k]) > big:
                big = abs(a[i, k])
                p = i
        piv[k] = p
        if big == 0.0 or big != big:
            return False
        if p != k:
            for j in range(n):
                tmp = a[k, j]
                a[k, j] = a[p, j]
                a[p, j] = tmp
        inv = 1.0 / a[k, k]
        for i in range(k + 1, n):
            a[i, k] *= inv
            lik = a[i, k]
            if lik != 0.0:
                for j in range(k + 1, n):
                    a[i, j] -= lik * a[k, j]
    return True


@njit(cache=True)
def _lu_solve(a, piv, b, n) -> None:
    """Solve ``A x = b`` in place in ``b[:n]`` from :func:`_lu_factor`'s output."""
    for k in range(n):
        p = piv[k]
        if p != k:
            tmp = b[k]
            b[k] = b[p]
            b[p] = tmp
    for i in range(n):
        s = b[i]
        for j in range(i):
            s -= a[i, j] * b[j]
        b[i] = s
    for i in range(n - 1, -1, -1):
        s = b[i]
        for j in range(i + 1, n):
            s -= a[i, j] * b[j]
        b[i] = s / a[i, i]


@njit(cache=True)
def _active_states(scale, n_err, active) -> int:
    """Write the indices of the states under control with nonzero scale into ``active``
    (increasing); returns their number."""
    m = 0
    for i in range(n_err):
        if scale[i] != 0.0:
            active[m] = i
            m += 1
    return m


@njit(cache=True)
def _solve_stage(lu, piv, jac, active, m, usub, hg, u) -> None:
    """``u <- W^-1 u`` with ``W = I / (h gamma) - J``, ``J`` zero in every column but
    those of the ``m`` states ``active`` (block lower triangular: the active block from
    its LU factors, then the other rows explicitly, ``u_i = h gamma (b_i + J_ia u_a)``)."""
    for a in range(m):
        usub[a] = u[active[a]]
    _lu_solve(lu, piv, usub, m)
    k = 0
    for i in range(u.shape[0]):
        if k < m and active[k] == i:
            u[i] = usub[k]
            k += 1
            continue
        s = u[i]
        for b in range(m):
            s += jac[i, active[b]] * usub[b]
        u[i] = hg * s


@njit(cache=True)
def w_step(code, t, h, y, ynew, scene, tol, work):
    """One ROS34PW2 step of ``h`` [s] from (t [s], y) with the Jacobian ``work.jac``;
    ``work.stages[0]`` holds f(t, y) on entry.

    ``code`` is the scene's code (a compile-time constant); ``scene``, ``tol`` and
    ``work`` are the bundles of :mod:`recipsim.solve.step_args`;
    uses ``work.stages[1:6]``, ``work.lu``, ``work.piv``, ``work.active`` and
    ``work.usub`` as work space. Returns
    ``(status, error_norm)``; on success ``ynew`` holds the state at ``t + h`` and
    ``work.stages[6] = f(t + h, ynew)`` (status -1: singular iteration matrix).
    """
    mode, par, ipar, props, pbuf = scene
    stages = work.stages
    jac = work.jac
    lu = work.lu
    piv = work.piv
    ytmp = work.ytmp
    aux = work.aux
    n_err = tol.n_err
    scale = tol.scale
    n = y.shape[0]
    k1 = stages[0]
    u1 = stages[1]
    u2 = stages[2]
    u3 = stages[3]
    u4 = stages[4]
    fs = stages[5]
    k7 = stages[6]
    active = work.active
    usub = work.usub
    hg = h * GAMMA
    inv = 1.0 / hg
    m_act = _active_states(scale, n_err, active)
    for a in range(m_act):
        ia = active[a]
        for b in range(m_act):
            lu[a, b] = -jac[ia, active[b]]
        lu[a, a] += inv
    if not _lu_factor(lu, piv, m_act):
        return -1, math.inf
    ih = 1.0 / h
    # stage 1
    for i in range(n):
        u1[i] = k1[i]
    _solve_stage(lu, piv, jac, active, m_act, usub, hg, u1)
    # stage 2
    for i in range(n):
        ytmp[i] = y[i] + _A21 * u1[i]
    st = rhs_for(code, t + _AL2 * h, ytmp, mode, par, ipar, props, pbuf, fs, aux)
    if st != 0:
        return st, math.inf
    for i in range(n):
        u2[i] = fs[i] + ih * (_C21 * u1[i])
    _solve_stage(lu, piv, jac, active, m_act, usub, hg, u2)
    # stage 3
    for i in range(n):
        ytmp[i] = y[i] + _A31 * u1[i] + _A32 * u2[i]
    st = rhs_for(code, t + _AL3 * h, ytmp, mode, par, ipar, props, pbuf, fs, aux)
    if st != 0:
        return st, math.inf
    for i in range(n):
        u3[i] = fs[i] + ih * (_C31 * u1[i] + _C32 * u2[i])
    _solve_stage(lu, piv, jac, active, m_act, usub, hg, u3)
    # stage 4
    for i in range(n):
        ytmp[i] = y[i] + _A41 * u1[i] + _A42 * u2[i] + _A43 * u3[i]
    st = rhs_for(code, t + _AL4 * h, ytmp, mode, par, ipar, props, pbuf, fs, aux)
    if st != 0:
        return st, math.inf
    for i in range(n):
        u4[i] = fs[i] + ih * (_C41 * u1[i] + _C42 * u2[i] + _C43 * u3[i])
    _solve_stage(lu, piv, jac, active, m_act, usub, hg, u4)
    for i in range(n):
        ynew[i] = y[i] + _M1 * u1[i] + _M2 * u2[i] + _M3 * u3[i] + _M4 * u4[i]
    st = rhs_for(code, t + h, ynew, mode, par, ipar, props, pbuf, k7, aux)
    if st != 0:
        return st, math.inf
    err = 0.0
    m = 0
    for i in range(n_err):
        if scale[i] == 0.0:
            continue
        e = _E1 * u1[i] + _E2 * u2[i] + _E3 * u3[i] + _E4 * u4[i]
        sc = tol.atol * scale[i] + tol.rtol * max(abs(y[i]), abs(ynew[i]))
        err += (e / sc) ** 2
        m += 1
    return 0, math.sqrt(err / max(m, 1))
