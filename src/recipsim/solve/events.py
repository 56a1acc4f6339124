"""Event location of the compiled integrator: the earliest crossing of a scene's event
function from <= 0 to > 0 inside an accepted step, by the Illinois method on the step's
cubic Hermite interpolant (the state at trial times is interpolated, the event function
evaluated on it after the right-hand side has refreshed the scene's outputs)."""

from __future__ import annotations

from numba import njit

from recipsim.model.scenes import N_EVENTS, event_values_for, rhs_for
from recipsim.solve.dense_output import hermite

#: Illinois iterations per event at most (the bracket shrinks below 1e-13 s long before)
MAX_ILLINOIS_ITERATIONS = 80


@njit(cache=True, inline="always")
def any_crossing(g_old, g_new) -> bool:
    """Whether an event function goes from <= 0 (``g_old``) to > 0 (``g_new``) over a
    step; :func:`locate_first_event` is needed only then."""
    for k in range(g_old.shape[0]):
        if g_old[k] <= 0.0 and g_new[k] > 0.0:
            return True
    return False


@njit(cache=True)
def locate_first_event(code, t, h, y, ynew, scene, work):
    """The earliest event crossing in the accepted step of ``h`` [s] from (t [s], y) to
    ``ynew`` of scene ``code`` (a compile-time constant, see
    :func:`recipsim.model.scenes.rhs_for`).

    ``work.g_old`` and ``work.g_new`` hold the event values at both ends of the step,
    ``work.stages[0]`` and ``work.stages[6]`` the derivatives there; ``work.yint``,
    ``work.ftmp``, ``work.g_int`` and ``work.aux`` are overwritten.

    Returns
    -------
    k_event : int
        Index of the event that fires first, -1 if none crosses.
    t_event : float
        Time of the crossing [s] (the bracket's upper end: the event function is > 0
        there); ``t + h`` if none crosses.
    evaluations : int
        Right-hand side evaluations spent.
    """
    mode, par, ipar, props, pbuf = scene
    ftmp = work.ftmp
    aux = work.aux
    g_old = work.g_old
    g_new = work.g_new
    g_int = work.g_int
    yint = work.yint
    k1 = work.stages[0]
    k7 = work.stages[6]
    nfev = 0
    k_event = -1
    t_event = t + h
    for k in range(N_EVENTS):
        if g_old[k] <= 0.0 and g_new[k] > 0.0:
            ta, tb = t, t + h
            ga, gb = g_old[k], g_new[k]
            side = 0
            for _ in range(MAX_ILLINOIS_ITERATIONS):
                tm = (ta * gb - tb * ga) / (gb - ga)
                if not (ta < tm < tb):
                    tm = 0.5 * (ta + tb)
                hermite(t, h, y, k1, ynew, k7, tm, yint)
                st2 = rhs_for(code, tm, yint, mode, par, ipar, props, pbuf, ftmp, aux)
                nfev += 1
                if st2 != 0:
                    tm = 0.5 * (ta + tb)
                    hermite(t, h, y, k1, ynew, k7, tm, yint)
                    st2 = rhs_for(code, tm, yint, mode, par, ipar, props, pbuf, ftmp, aux)
                    nfev += 1
                event_values_for(code, yint, mode, par, ipar, aux, g_int)
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
    return k_event, t_event, nfev
