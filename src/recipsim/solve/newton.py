"""Newton-Broyden on a fixed-point map ``z -> G(z)`` with a finite-difference Jacobian:
the solver of shooting (:mod:`.shooting`, :mod:`.subharmonic`) and of the paper's
undamped study. Generic: it knows nothing of revolutions (the map may fail with one of
``failures`` and tell, through ``same_branch``, when a difference step changed a discrete
branch such as a valve mode).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from recipsim.errors import SolverError

#: Singular values of the scaled ``dG/dz - I`` below this fraction of the largest are
#: treated as neutral directions (no step along them).
_SVD_CUTOFF = 1e-9
#: Largest Newton step, scaled infinity norm (1 = the state's residual reference).
_MAX_STEP = 4.0
#: Step halvings when the residual grows.
_BACKTRACK = 2


def _newton_step(a: np.ndarray, f: np.ndarray) -> np.ndarray:
    """Least-norm solution of ``a dz = -f`` by truncated SVD, limited to ``_MAX_STEP``."""
    u, sv, vt = np.linalg.svd(a)
    keep = sv > _SVD_CUTOFF * sv[0]
    dz = -(vt[keep].T @ ((u[:, keep].T @ f) / sv[keep]))
    big = float(np.max(np.abs(dz)))
    if big > _MAX_STEP:
        dz *= _MAX_STEP / big
    return dz


@dataclass
class NewtonResult:
    """Outcome of :func:`newton_fixed_point`.

    Attributes
    ----------
    z, g : numpy.ndarray
        Last iterate and its image ``G(z)``.
    payload : object
        What the map returned with ``g`` for ``z`` (e.g. the revolution).
    converged : bool
        ``accept`` held at ``z``.
    stalled : bool
        Not converged although the budget was not spent: no step reduced the residual
        even with a fresh Jacobian.
    evaluations : int
        Map evaluations, Jacobian columns included.
    iterations : int
        Newton trial steps (each one map evaluation).
    jacobians, jacobian_evaluations : int
        Jacobians built by finite differences and the evaluations they cost.
    jacobian : numpy.ndarray or None
        Last scaled ``dG/dz - I`` (finite differences and Broyden updates), for reuse.
    """

    z: np.ndarray
    g: np.ndarray
    payload: Any
    converged: bool
    stalled: bool = False
    evaluations: int = 0
    iterations: int = 0
    jacobians: int = 0
    jacobian_evaluations: int = 0
    jacobian: np.ndarray | None = None


def newton_fixed_point(
    fun: Callable[[np.ndarray], tuple[np.ndarray, Any]],
    z: np.ndarray,
    first: tuple[np.ndarray, Any],
    ref: np.ndarray,
    fd_step: np.ndarray,
    accept: Callable[[np.ndarray, np.ndarray, Any], bool],
    max_evaluations: int,
    *,
    jacobian: np.ndarray | None = None,
    same_branch: Callable[[Any, Any], bool] | None = None,
    failures: tuple[type[BaseException], ...] = (SolverError,),
) -> NewtonResult:
    """Solve ``G(z) = z`` by Newton-Broyden with a finite-difference Jacobian.

    Works in scaled variables ``z / ref``. The Jacobian of ``G`` is built by forward
    differences (one evaluation per unknown, step ``fd_step * ref``), then updated by
    Broyden's rank-one formula after every accepted step; it is rebuilt only when no
    step reduces the scaled infinity norm of ``F = G(z) - z``. Steps come from a
    truncated SVD of ``dG/dz - I`` (directions with singular values below
    ``_SVD_CUTOFF`` of the largest are not stepped along), at most ``_MAX_STEP`` in the
    scaled infinity norm, halved up to ``_BACKTRACK`` times while the residual grows.

    Parameters
    ----------
    fun : callable
        ``fun(z) -> (G(z), payload)``; may raise one of ``failures`` (a failed
        evaluation: the trial step is halved, a Jacobian column retried smaller).
    z : numpy.ndarray
        Starting point.
    first : (numpy.ndarray, object)
        ``fun(z)``, already evaluated.
    ref : numpy.ndarray
        Scale of each unknown (positive).
    fd_step : numpy.ndarray
        Finite-difference steps relative to ``ref``.
    accept : callable
        ``accept(z, g, payload) -> bool``: convergence test at an evaluated point.
    max_evaluations : int
        Budget of map evaluations.
    jacobian : numpy.ndarray, optional
        Scaled ``dG/dz - I`` to start from (same ``ref``).
    same_branch : callable, optional
        ``same_branch(payload_base, payload_column)``: False when a difference step
        crossed a discontinuity (e.g. other valve modes); the column is retried with
        a step ten times smaller and kept if it still differs.
    failures : tuple of exception types
        Exceptions of ``fun`` that mean a failed evaluation.

    Returns
    -------
    NewtonResult
    """
    g, payload = first
    a, fresh = jacobian, False
    out = NewtonResult(z, g, payload, False, jacobian=a)
    while True:
        out.z, out.g, out.payload, out.jacobian = z, g, payload, a
        if accept(z, g, payload):
            out.converged = True
            return out
        if a is None:
            a = _fresh_jacobian(
                fun, z, g, payload, ref, fd_step, same_branch, failures, out, max_evaluations
            )
            if a is None:
                return out
            fresh = True
        f = (g - z) / ref
        dz = _newton_step(a, f)
        found, spent = _line_search(fun, z, dz, f, ref, failures, out, max_evaluations)
        if spent or (found is None and fresh):
            out.stalled = not spent  # no step helped even with a fresh Jacobian
            return out
        if found is None:
            a = None  # Broyden's Jacobian went stale: rebuild it here
            continue
        z, g, payload, f_new, dz = found
        a, fresh = _broyden(a, dz, f, f_new), False


def _broyden(a: np.ndarray, dz: np.ndarray, f: np.ndarray, f_new: np.ndarray) -> np.ndarray:
    """Broyden's rank-one update of the scaled Jacobian of ``F = G(z) - z``.

    Parameters
    ----------
    a : numpy.ndarray
        Scaled ``dG/dz - I`` before the step.
    dz : numpy.ndarray
        The scaled step taken.
    f, f_new : numpy.ndarray
        Scaled residual before and after the step.

    Returns
    -------
    numpy.ndarray
        The updated matrix.
    """
    return a + np.outer(f_new - f - a @ dz, dz) / float(dz @ dz)


def _fresh_jacobian(
    fun: Callable[[np.ndarray], tuple[np.ndarray, Any]],
    z: np.ndarray,
    g: np.ndarray,
    payload: Any,
    ref: np.ndarray,
    fd_step: np.ndarray,
    same_branch: Callable[[Any, Any], bool] | None,
    failures: tuple[type[BaseException], ...],
    out: NewtonResult,
    max_evaluations: int,
) -> np.ndarray | None:
    """Build the Jacobian at ``z`` if the budget allows one (:func:`_jacobian`).

    Parameters
    ----------
    fun, z, g, payload, ref, fd_step, same_branch, failures
        As in :func:`newton_fixed_point` (``g``, ``payload``: ``fun(z)``).
    out : NewtonResult
        Counts the evaluations; ``stalled`` is set when a column's evaluation fails.
    max_evaluations : int
        Budget of map evaluations.

    Returns
    -------
    numpy.ndarray or None
        Scaled ``dG/dz - I``; None when the budget cannot pay for it or an evaluation
        failed (the solve stops).
    """
    if out.evaluations + z.size + 1 > max_evaluations:
        return None
    try:
        return _jacobian(fun, z, g, payload, ref, fd_step, same_branch, failures, out)
    except failures:
        out.stalled = True
        return None


def _line_search(
    fun: Callable[[np.ndarray], tuple[np.ndarray, Any]],
    z: np.ndarray,
    dz: np.ndarray,
    f: np.ndarray,
    ref: np.ndarray,
    failures: tuple[type[BaseException], ...],
    out: NewtonResult,
    max_evaluations: int,
) -> tuple[tuple[np.ndarray, np.ndarray, Any, np.ndarray, np.ndarray] | None, bool]:
    """Try the Newton step ``dz`` from ``z``, halved up to ``_BACKTRACK`` times while the
    scaled residual does not drop (or the evaluation fails).

    Parameters
    ----------
    fun, ref, failures
        As in :func:`newton_fixed_point`.
    z : numpy.ndarray
        Current iterate.
    dz : numpy.ndarray
        Scaled Newton step.
    f : numpy.ndarray
        Scaled residual ``(G(z) - z) / ref`` at ``z``.
    out : NewtonResult
        Counts evaluations and iterations.
    max_evaluations : int
        Budget of map evaluations.

    Returns
    -------
    found : tuple or None
        ``(z_new, g_new, payload_new, f_new, dz)`` of the first trial whose residual's
        infinity norm is below that of ``f`` (``dz`` the step taken); None if none was.
    spent : bool
        The budget ran out before a trial (the solve stops).
    """
    norm = float(np.max(np.abs(f)))
    for _ in range(_BACKTRACK + 1):
        if out.evaluations >= max_evaluations:
            return None, True
        z_new = z + dz * ref
        out.evaluations += 1
        out.iterations += 1
        try:
            g_new, payload_new = fun(z_new)
        except failures:
            dz = 0.5 * dz
            continue
        f_new = (g_new - z_new) / ref
        if float(np.max(np.abs(f_new))) < norm:
            return (z_new, g_new, payload_new, f_new, dz), False
        dz = 0.5 * dz
    return None, False


def _jacobian(
    fun: Callable[[np.ndarray], tuple[np.ndarray, Any]],
    z: np.ndarray,
    g: np.ndarray,
    payload: Any,
    ref: np.ndarray,
    fd_step: np.ndarray,
    same_branch: Callable[[Any, Any], bool] | None,
    failures: tuple[type[BaseException], ...],
    out: NewtonResult,
) -> np.ndarray:
    """Scaled ``dG/dz - I`` by forward differences, one evaluation per column."""
    n = z.size
    jac = np.empty((n, n))
    for j in range(n):
        step = fd_step[j] * ref[j]
        g_j: np.ndarray | None = None
        for attempt in range(2):
            zp = z.copy()
            zp[j] += step
            out.evaluations += 1
            out.jacobian_evaluations += 1
            try:
                g_try, payload_j = fun(zp)
            except failures:
                if attempt == 1:
                    raise
                step *= 0.1
                continue
            g_j = g_try
            if same_branch is None or same_branch(payload, payload_j) or attempt == 1:
                break
            step *= 0.1
        assert g_j is not None
        jac[:, j] = (g_j - g) / step
    out.jacobians += 1
    return jac / ref[:, None] * ref[None, :] - np.eye(n)
