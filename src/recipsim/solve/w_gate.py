"""The Rosenbrock-W step's calls in the integrator loop, compiled only into the entries
that take W-steps.

Each scene has two compiled entries (:mod:`recipsim.solve.scene_entries`): an explicit one,
which runs DOPRI5 and, for ``solver.method = "dopri5_stiff"``, watches Hairer's
stiffness test, and one with the W-step (:mod:`recipsim.solve.stiff`), which the explicit
entry hands the integration over to once the test fires. The functions here take the
entry's ``w_entry`` flag, a compile-time constant (numba's ``Literal[int]``, as the
scene code of :func:`recipsim.model.scenes.rhs_for`): with :data:`WITH_W_STEP` they are
the W-step and its Jacobian's refresh; with :data:`EXPLICIT` they compile to a constant
that the loop never uses (the explicit entry never sets ``use_w``), so an entry that
runs DOPRI5 compiles none of the W-method: the finite-difference Jacobian, the LU
factorisation and the four stages.
"""

from __future__ import annotations

import math
from typing import Any

from numba import types
from numba.core.errors import TypingError
from numba.extending import overload

from recipsim.solve.step_control import JAC_STAGES_PER_STEP
from recipsim.solve.stiff import jacobian_fd, spectral_bound, w_step

#: ``w_entry`` of an entry that runs DOPRI5 only
EXPLICIT = 0
#: ``w_entry`` of an entry that takes W-steps
WITH_W_STEP = 1


def _takes_w_steps(w_entry: Any) -> bool:
    """Whether the literal flag ``w_entry`` (a numba type) is :data:`WITH_W_STEP` (a
    typing error for a flag not known at compile time)."""
    if not isinstance(w_entry, types.IntegerLiteral):
        raise TypingError("the W-step flag of an integrator entry must be a compile-time constant")
    return bool(w_entry.literal_value == WITH_W_STEP)


# The plain-Python bodies run only without the JIT (``NUMBA_DISABLE_JIT=1``); compiled
# code gets the overloads below.
def w_step_in(w_entry, code, t, h, y, ynew, scene, tol, work):  # type: ignore[no-untyped-def]
    """:func:`recipsim.solve.stiff.w_step` in an entry with the W-step:
    ``(status, error_norm)``."""
    return w_step(code, t, h, y, ynew, scene, tol, work)


def refresh_jacobian_in(w_entry, code, t, y, scene, tol, work):  # type: ignore[no-untyped-def]
    """Build the W-method's Jacobian at (t [s], y) in an entry with the W-step:
    ``(status, evaluations, accepted steps to keep it, bound on its spectral radius
    [1/s])``."""
    stj, nj = jacobian_fd(code, t, y, work.stages[0], scene, tol, work)
    jac_life = max(1, nj // JAC_STAGES_PER_STEP)
    return stj, nj, jac_life, spectral_bound(work.jac, tol.scale, tol.n_err)


@overload(w_step_in)
def _w_step_in(w_entry, code, t, h, y, ynew, scene, tol, work):  # type: ignore[no-untyped-def]
    if _takes_w_steps(w_entry):
        return lambda w_entry, code, t, h, y, ynew, scene, tol, work: w_step(
            code, t, h, y, ynew, scene, tol, work
        )
    # never called: the explicit entry's ``use_w`` stays False
    return lambda w_entry, code, t, h, y, ynew, scene, tol, work: (-1, math.inf)


@overload(refresh_jacobian_in)
def _refresh_jacobian_in(w_entry, code, t, y, scene, tol, work):  # type: ignore[no-untyped-def]
    if _takes_w_steps(w_entry):
        return refresh_jacobian_in
    # never called: the explicit entry's ``use_w`` stays False
    return lambda w_entry, code, t, y, scene, tol, work: (-1, 0, 1, 0.0)
