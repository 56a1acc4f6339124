"""A root of a scalar function inside a sign-changing bracket, by Brent's method.

Used where a run or a case load needs one root and nothing else from
``scipy.optimize``: importing that package costs 0.25-0.4 s (it imports
``scipy.sparse``, ``scipy.spatial``, ``scipy.linalg`` and more), which is a fifth to
a quarter of a warm ``recipsim run`` of a motor-driven case, paid once per process and
so once per sweep worker. The method is Brent's (Brent, *Algorithms for Minimization
without Derivatives*, 1973, ch. 4): inverse quadratic interpolation or the secant
step where it stays well inside the bracket, bisection otherwise, so it converges
superlinearly on a smooth function and never slower than bisection; the same method and
stopping rule as ``scipy.optimize.brentq`` (``|half bracket| < (xtol + rtol |x|) / 2``).
"""

from __future__ import annotations

from collections.abc import Callable


def bracketed_root(
    f: Callable[[float], float],
    low: float,
    high: float,
    xtol: float = 2e-12,
    rtol: float = 4.0 * 2.220446049250313e-16,
    maxiter: int = 200,
) -> float:
    """Root of ``f`` in ``[low, high]``, where ``f(low)`` and ``f(high)`` differ in sign.

    Parameters
    ----------
    f : callable
        The function, float to float.
    low, high : float
        The bracket's ends (either order).
    xtol, rtol : float
        Absolute and relative tolerance on the root: the answer lies within
        ``xtol + rtol |x|`` of a sign change of ``f``.
    maxiter : int
        Most evaluations after the two at the ends.

    Returns
    -------
    float
        The root.

    Raises
    ------
    ValueError
        If ``f`` has the same sign at both ends, or the bracket does not shrink to the
        tolerance within ``maxiter`` steps.
    """
    a, b = float(low), float(high)
    fa, fb = f(a), f(b)
    if fa == 0.0:
        return a
    if fb == 0.0:
        return b
    if (fa > 0.0) == (fb > 0.0):
        raise ValueError(f"f({a}) = {fa} and f({b}) = {fb}: no sign change in the bracket")
    # b: the best estimate; c: the other end of the bracket [b, c]; a: the previous b
    c, fc = a, fa
    step = previous_step = b - a
    for _ in range(maxiter):
        if (fb > 0.0) == (fc > 0.0):  # the sign change is now between a and b
            c, fc = a, fa
            step = previous_step = b - a
        if abs(fc) < abs(fb):  # keep b the end with the smaller residual
            a, b, c = b, c, b
            fa, fb, fc = fb, fc, fb
        tol = 0.5 * (xtol + rtol * abs(b))
        half = 0.5 * (c - b)
        if fb == 0.0 or abs(half) < tol:
            return b
        if abs(previous_step) >= tol and abs(fa) > abs(fb):
            s = fb / fa
            if a == c:  # two points: the secant
                p, q = 2.0 * half * s, 1.0 - s
            else:  # three points: inverse quadratic interpolation
                q, r = fa / fc, fb / fc
                p = s * (2.0 * half * q * (q - r) - (b - a) * (r - 1.0))
                q = (q - 1.0) * (r - 1.0) * (s - 1.0)
            if p > 0.0:
                q = -q
            else:
                p = -p
            # accept the interpolation only well inside the bracket and shrinking fast
            if 2.0 * p < min(3.0 * half * q - abs(tol * q), abs(previous_step * q)):
                previous_step, step = step, p / q
            else:
                step = previous_step = half
        else:
            step = previous_step = half
        a, fa = b, fb
        b += step if abs(step) > tol else (tol if half > 0.0 else -tol)
        fb = f(b)
    raise ValueError(f"no root to tolerance in {maxiter} steps in [{low}, {high}]")
