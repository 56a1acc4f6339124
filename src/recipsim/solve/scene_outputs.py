"""The scene's outputs (the ``aux`` layout of :mod:`recipsim.model.scenes`) at the
samples of a revolution, compiled per scene like the integrator (one entry per scene
passes its code as a compile-time constant, so a case compiles only its own scene)."""

from __future__ import annotations

import numpy as np
from numba import njit

from recipsim.model.scenes import SCENE_COUPLED, SCENE_CYLINDER, SCENE_MECHANISM, rhs_for
from recipsim.physics.thermo.cylinder import I_SCENE


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
