"""The argument bundles of the compiled integrator's step functions.

A step of :mod:`recipsim.solve.integrator` needs the scene (modes, parameters, the
property callback and its buffer), the error control (tolerances and state scales) and
a set of work arrays. Each travels as one named tuple, so a step function takes a
handful of arguments and the integrator allocates its work arrays once per call:

- :class:`SceneArgs`: what :func:`recipsim.model.scenes.scene_rhs` needs besides the
  time, the state, the output and the auxiliary outputs;
- :class:`Tolerance`: the error norm's relative and absolute tolerances, the typical
  magnitude of each state (absolute tolerance ``atol * scale``) and the number of
  leading states under error control;
- :class:`Workspace`: the stages, trial states, event values and the Rosenbrock-W
  matrices, allocated by :func:`new_workspace`.

Taking an array out of a bundle costs a reference-count increment and decrement, so a
function that evaluates the right-hand side unpacks the bundle once at its top and hands
the arrays themselves to :func:`recipsim.model.scenes.scene_rhs` (a wrapper
``rhs(t, y, scene, out, aux)`` would pay that cost at every evaluation), and the
functions the integrator calls on every step are inlined into its loop
(``inline="always"``).
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np
from numba import njit

from recipsim.model.scenes import N_AUX, N_EVENTS


class SceneArgs(NamedTuple):
    """The scene a step evaluates: discrete modes (int64, updated by events), float and
    integer parameters, the property callback ``(T [K], rho [kg/m^3]) -> int32`` and the
    buffer it fills."""

    mode: np.ndarray
    par: np.ndarray
    ipar: np.ndarray
    props: Any
    pbuf: np.ndarray


class Tolerance(NamedTuple):
    """Error control: relative tolerance ``rtol`` [-], absolute tolerance ``atol`` on
    scaled states [-], typical magnitude ``scale`` of each state [state units] (zero:
    not controlled) and the number ``n_err`` of leading states under control."""

    rtol: float
    atol: float
    scale: np.ndarray
    n_err: int


class Workspace(NamedTuple):
    """Work arrays of one integration of ``n`` states (``n_err`` under error control).

    ``stages`` (7, n): Dormand-Prince stages, f(t, y) first and f(t + h, y_new) last
    (the Rosenbrock-W step uses rows 1-5 as its own); ``ytmp``, ``ynew``, ``yint``,
    ``ftmp`` (n): trial state, step's end (also of the re-step to an event),
    interpolated state, scratch derivative; ``aux`` (``N_AUX``): the scene's outputs;
    ``g_old``, ``g_new``, ``g_int`` (``N_EVENTS``): event values at the step's start,
    end and at a trial time; ``jac`` (n, n_err), ``lu`` (n_err, n_err), ``piv``
    (n_err): the Rosenbrock-W Jacobian, its iteration matrix's factors and pivots;
    ``active`` (n_err) and ``usub`` (n_err): the indices of the states the iteration
    matrix is factorised over (under control, nonzero scale) and a right-hand side
    gathered on them.
    """

    stages: np.ndarray
    ytmp: np.ndarray
    ynew: np.ndarray
    yint: np.ndarray
    ftmp: np.ndarray
    aux: np.ndarray
    g_old: np.ndarray
    g_new: np.ndarray
    g_int: np.ndarray
    jac: np.ndarray
    lu: np.ndarray
    piv: np.ndarray
    active: np.ndarray
    usub: np.ndarray


@njit(cache=True)
def new_workspace(n, n_err):
    """Allocate the :class:`Workspace` of ``n`` states with ``n_err`` under error control."""
    return Workspace(
        np.empty((7, n)),
        np.empty(n),
        np.empty(n),
        np.empty(n),
        np.empty(n),
        np.zeros(N_AUX),
        np.empty(N_EVENTS),
        np.empty(N_EVENTS),
        np.empty(N_EVENTS),
        np.zeros((n, n_err)),
        np.empty((n_err, n_err)),
        np.empty(n_err, dtype=np.int64),
        np.zeros(n_err, dtype=np.int64),
        np.empty(n_err),
    )
