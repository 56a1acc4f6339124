"""The scene's outputs (the ``aux`` layout of :mod:`recipsim.model.scenes`) at the
samples of a revolution, through the scene's own compiled right-hand side like the
integrator (:mod:`recipsim.model.scene_functions`: one compiled function for every
scene, a case compiles only its own scene's functions)."""

from __future__ import annotations

import numpy as np
from numba import njit

from recipsim.model.scene_functions import scene_functions
from recipsim.model.scenes import N_AUX, rhs_for
from recipsim.physics.thermo.cylinder import I_SCENE


@njit(cache=True)
def _evaluate(scene, times, samples, sample_modes, par, ipar, props, pbuf, out):
    n = samples.shape[1]
    dydt = np.empty(n)
    aux = np.zeros(N_AUX)  # the scene's whole block, whatever columns ``out`` keeps
    for k in range(times.shape[0]):
        mode = sample_modes[k]
        rhs_for(scene, times[k], samples[k], mode, par, ipar, props, pbuf, dydt, aux)
        for j in range(out.shape[1]):
            out[k, j] = aux[j]


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
    scene = scene_functions(int(ipar[I_SCENE]))
    _evaluate(scene, times, samples, sample_modes, par, ipar, props, pbuf, out)
