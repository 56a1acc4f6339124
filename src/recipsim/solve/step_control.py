"""Step-size control and method switching of the compiled integrator
(:mod:`recipsim.solve.integrator`, whose docstring describes the switching): the next
trial step after a rejected or an accepted step, Hairer's stiffness count, and the
switch between DOPRI5 and the Rosenbrock-W step."""

from __future__ import annotations

from numba import njit

from recipsim.solve.stiff import ERR_ORDER

#: ``method`` of :func:`recipsim.solve.scene_entries.integrate`
METHOD_DOPRI5 = 0
METHOD_AUTO = 1
METHOD_ROSW = 2
#: :data:`METHOD_AUTO` starting with the W-step (the hand-over between the integrator's
#: entries, :func:`recipsim.solve.scene_entries.integrate`)
METHOD_AUTO_IN_W = 3
#: stiffness switching (see the module docstring)
STIFF_LIMIT = 3.25
STIFF_AFTER = 5
NONSTIFF_RESET = 6
BACK_TO_DOPRI5 = 2.0
NONSTIFF_AFTER = 3
#: A Jacobian of ``n_j`` finite-difference evaluations is kept for
#: ``max(1, n_j // JAC_STAGES_PER_STEP)`` accepted W-steps (each costs 4 evaluations), so
#: building it costs at most about one step's worth: every step for the 4-6 gas states
#: of a rigid crank, every 6-7 steps for the 28 controlled states of a crank train on
#: oil films (the W-method keeps its order with a stale matrix). Measured on the
#: lubricated reference case, evaluations per revolution: 7.4 k keeping it 3 steps, 6.0 k
#: for 6 steps, 5.7 k for 13 steps; with the skirt film 13 steps made 2.6 times as many
#: rejected steps as 6 and cost more than it saved.
JAC_STAGES_PER_STEP = 4


@njit(cache=True, inline="always")
def rejected_step(h, st, err, use_w) -> float:
    """The next trial step [s] after a rejected one of ``h`` [s] (property failure
    ``st != 0``, error norm ``err`` above 1 or NaN)."""
    if st != 0 or err != err:
        return h * 0.25
    if use_w:
        return h * max(0.2, 0.9 * err ** (-1.0 / ERR_ORDER))
    return h * max(0.2, 0.9 * err**-0.2)


@njit(cache=True, inline="always")
def next_step(h, err, use_w, h_max) -> float:
    """The next step [s] after an accepted one of ``h`` [s] with error norm ``err``."""
    if use_w:
        if err > 0.0:
            fac = min(5.0, max(0.2, 0.9 * err ** (-1.0 / ERR_ORDER)))
        else:
            fac = 5.0
    elif err > 0.0:
        fac = min(5.0, max(0.2, 0.9 * err**-0.2))
    else:
        fac = 5.0
    return min(h * fac, h_max)


@njit(cache=True, inline="always")
def count_stiff_step(stiff_step, n_stiff, n_nonstiff):
    """Count an accepted DOPRI5 step that looked stiff (or not): ``(n_stiff,
    n_nonstiff)``; :data:`NONSTIFF_RESET` non-stiff steps in a row clear the count."""
    if stiff_step:
        return n_stiff + 1, 0
    n_nonstiff += 1
    if n_nonstiff >= NONSTIFF_RESET:
        return 0, n_nonstiff
    return n_stiff, n_nonstiff


@njit(cache=True, inline="always")
def switch_method(method, use_w, h, rho_jac, n_stiff, n_nonstiff):
    """After an accepted step: ``(use_w, n_stiff, n_nonstiff, switched_to_w)`` (see
    the module docstring; ``h`` [s] is the next step, ``rho_jac`` [1/s] the Jacobian's
    spectral bound)."""
    if method != METHOD_AUTO:
        return use_w, n_stiff, n_nonstiff, False
    if use_w:
        # back to DOPRI5 once it could take the step the W-method takes
        if h * rho_jac < BACK_TO_DOPRI5:
            n_nonstiff += 1
            if n_nonstiff >= NONSTIFF_AFTER:
                return False, 0, 0, False
            return True, n_stiff, n_nonstiff, False
        return True, n_stiff, 0, False
    if n_stiff >= STIFF_AFTER:
        return True, 0, 0, True
    return False, n_stiff, n_nonstiff, False
