"""The scene's outputs (the ``aux`` layout of :mod:`recipsim.model.scenes`) at the
samples of a revolution, compiled per scene like the integrator (one entry per scene
passes its code as a compile-time constant, so a case compiles only its own scene).

On the rigid crank, :func:`rigid_cycle_samples` also does in the same compiled call
what the cycle table does next: the samples sorted by crank angle, each output as a
row, and the pinned mechanism's reactions at them (a sweep point's summary spends a
third of its time in those numpy steps otherwise).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from recipsim.model.scenes import (
    A_MECH,
    OUTPUTS,
    SCENE_COUPLED,
    SCENE_CYLINDER,
    SCENE_MECHANISM,
    rhs_for,
)
from recipsim.physics.mechanics.pinned import pinned_reactions_array
from recipsim.physics.thermo.cylinder import A_PRESSURE, I_SCENE

#: The scene output holding the crank angle [rad] (not wrapped to one revolution).
CRANK_ANGLE = OUTPUTS.entry("crank_angle").index
assert CRANK_ANGLE < A_MECH  # the cylinder's block
#: A wrapped crank angle this close below 2 pi is the TDC sample (0) [rad].
_TDC_ROUND_OFF = 1e-9


# inlined into each scene's entry (one library to compile instead of two)
@njit(cache=True, inline="always")
def _evaluate(code, times, samples, sample_modes, par, ipar, props, pbuf, out):
    n = samples.shape[1]
    dydt = np.empty(n)
    aux = np.empty(out.shape[1])
    for k in range(times.shape[0]):
        mode = sample_modes[k]
        rhs_for(code, times[k], samples[k], mode, par, ipar, props, pbuf, dydt, aux)
        for j in range(aux.shape[0]):
            out[k, j] = aux[j]


@njit(cache=True)
def _cylinder_outputs(times, samples, sample_modes, par, ipar, props, pbuf, out):
    _evaluate(SCENE_CYLINDER, times, samples, sample_modes, par, ipar, props, pbuf, out)


@njit(cache=True)
def _mechanism_outputs(times, samples, sample_modes, par, ipar, props, pbuf, out):
    _evaluate(SCENE_MECHANISM, times, samples, sample_modes, par, ipar, props, pbuf, out)


@njit(cache=True)
def _coupled_outputs(times, samples, sample_modes, par, ipar, props, pbuf, out):
    _evaluate(SCENE_COUPLED, times, samples, sample_modes, par, ipar, props, pbuf, out)


_BY_SCENE = (_cylinder_outputs, _mechanism_outputs, _coupled_outputs)


def evaluate_samples(
    times: np.ndarray,
    samples: np.ndarray,
    sample_modes: np.ndarray,
    par: np.ndarray,
    ipar: np.ndarray,
    props: object,
    pbuf: np.ndarray,
    out: np.ndarray,
) -> None:
    """Fill ``out[k]`` with the outputs of the scene in ``ipar[I_SCENE]`` at sample ``k``
    (times [s], states and modes), evaluating its right-hand side there."""
    _BY_SCENE[int(ipar[I_SCENE])](times, samples, sample_modes, par, ipar, props, pbuf, out)


@njit(cache=True)
def _rigid_cycle(
    times, samples, sample_modes, par, ipar, props, pbuf, omega, mech_par, angles, rows, modes, load
):
    n = times.shape[0]
    aux = np.empty((n, A_MECH))
    _evaluate(SCENE_CYLINDER, times, samples, sample_modes, par, ipar, props, pbuf, aux)
    two_pi = 2.0 * math.pi
    theta = np.empty(n)
    for k in range(n):
        wrapped = np.remainder(aux[k, CRANK_ANGLE], two_pi)
        theta[k] = 0.0 if wrapped > two_pi - _TDC_ROUND_OFF else wrapped
    order = np.argsort(theta, kind="mergesort")  # stable: equal angles keep time order
    for k in range(n):
        src = order[k]
        angles[k] = theta[src]
        for j in range(rows.shape[0]):
            rows[j, k] = aux[src, j]
        for j in range(modes.shape[0]):
            modes[j, k] = sample_modes[src, j]
    pinned_reactions_array(angles, omega, rows[A_PRESSURE], mech_par, load)


def rigid_cycle_samples(
    times: np.ndarray,
    samples: np.ndarray,
    sample_modes: np.ndarray,
    par: np.ndarray,
    ipar: np.ndarray,
    props: object,
    pbuf: np.ndarray,
    omega: float,
    mech_par: np.ndarray,
    width: int,
    n_reactions: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The rigid crank's outputs at the samples (:func:`evaluate_samples`), sorted by
    crank angle, with the pinned mechanism's reactions there, in one compiled call.

    Parameters
    ----------
    times, samples, sample_modes, par, ipar, props, pbuf
        As in :func:`evaluate_samples` (the scene must be the cylinder's).
    omega : float
        Crank speed [rad/s].
    mech_par : ndarray
        The pinned mechanism's parameters
        (:func:`recipsim.model.build.case_mechanism_parameters`).
    width : int
        How many of the scene's first outputs to keep (at most ``A_MECH``).
    n_reactions : int
        Outputs of the pinned reactions (``recipsim.physics.mechanics.pinned.N_PIN_OUT``).

    Returns
    -------
    angles : ndarray
        Crank angle of each sample in [0, 2 pi), ascending [rad], shape (n,).
    rows : ndarray
        Output ``j`` at those angles in row ``j``, shape (width, n).
    modes : ndarray
        The valve modes at those angles, one row per valve, shape (2, n).
    reactions : ndarray
        The pinned reactions at those angles and the cylinder pressure, shape
        (n, n_reactions).
    """
    if int(ipar[I_SCENE]) != SCENE_CYLINDER or not A_PRESSURE < width <= A_MECH:
        raise ValueError("rigid_cycle_samples: the cylinder's scene, the pressure kept")
    n = times.shape[0]
    angles = np.empty(n)
    rows = np.empty((width, n))
    modes = np.empty((sample_modes.shape[1], n), dtype=sample_modes.dtype)
    reactions = np.zeros((n, n_reactions))
    _rigid_cycle(
        times,
        samples,
        sample_modes,
        par,
        ipar,
        props,
        pbuf,
        omega,
        mech_par,
        angles,
        rows,
        modes,
        reactions,
    )
    return angles, rows, modes, reactions
