"""Anderson mixing of the revolution iteration (:mod:`recipsim.solve.acceleration`) on
maps whose fixed point and multipliers are known."""

from __future__ import annotations

import numpy as np
import pytest

from recipsim.solve.acceleration import MAX_GAIN, MEMORY, _anderson


def _linear_map(multipliers: list[float], seed: int) -> tuple[np.ndarray, np.ndarray]:
    """``G(z) = z* + M (z - z*)`` with ``M`` of the given (real) eigenvalues in a random
    orthonormal basis: ``(M, z*)``."""
    rng = np.random.default_rng(seed)
    n = len(multipliers)
    basis, _ = np.linalg.qr(rng.normal(size=(n, n)))
    m = basis @ np.diag(multipliers) @ basis.T
    return m, rng.normal(size=n)


def _iterate(m: np.ndarray, fixed: np.ndarray, steps: int, mix: bool) -> list[float]:
    """Distances from the fixed point of the starts of ``steps`` iterations (mixing with
    the last three iterates, as the solver does, or plain)."""
    z = fixed + np.ones(fixed.size)
    starts: list[np.ndarray] = []
    images: list[np.ndarray] = []
    errors = []
    for _ in range(steps):
        g = fixed + m @ (z - fixed)
        starts, images = [*starts[-MEMORY:], z], [*images[-MEMORY:], g]
        z = _anderson(starts, images) if mix else g
        errors.append(float(np.max(np.abs(z - fixed))))
    return errors


@pytest.mark.parametrize("slow", [0.81, -0.39, 0.95])
def test_one_slow_mode_is_extrapolated_away(slow: float) -> None:
    """A slow mode (the skirt's 0.81, the journals' -0.39, or 0.95) among fast ones
    (|mu| <= 0.1), from a start at distance 1: after six mixed iterations the start is
    within 1e-5 of the fixed point (measured 8e-7, 7e-8, 5e-6), where plain iteration is
    still at about ``|slow|^6`` (0.28, 3.5e-3, 0.74; above 1e-3 in every case)."""
    m, fixed = _linear_map([slow, 0.1, -0.05, 0.02, 0.0, 0.08], seed=1)
    mixed = _iterate(m, fixed, 6, mix=True)
    plain = _iterate(m, fixed, 6, mix=False)
    assert mixed[-1] < 1e-5
    assert plain[-1] > 1e-3


def test_a_pair_of_slow_complex_multipliers_is_extrapolated_away() -> None:
    """A rotating slow mode (multipliers 0.8 e^(+-i 1.2): an orbit that turns each
    revolution) is extrapolated as well: within 1e-5 of the fixed point after ten mixed
    iterations (measured 3e-7), plain iteration still at 0.05."""
    rng = np.random.default_rng(4)
    rot = 0.8 * np.array([[np.cos(1.2), -np.sin(1.2)], [np.sin(1.2), np.cos(1.2)]])
    block = np.zeros((5, 5))
    block[:2, :2] = rot
    block[2:, 2:] = np.diag([0.1, -0.05, 0.0])
    basis, _ = np.linalg.qr(rng.normal(size=(5, 5)))
    m = basis @ block @ basis.T
    fixed = rng.normal(size=5)
    assert _iterate(m, fixed, 10, mix=True)[-1] < 1e-5
    assert _iterate(m, fixed, 10, mix=False)[-1] > 0.01


def test_first_iterate_and_an_oversized_step_give_the_plain_image() -> None:
    """No difference yet: the image itself. Differences that call for a step of more
    than MAX_GAIN plain steps (a multiplier of 0.999, or noise) also give the image."""
    z0, g0 = np.zeros(3), np.array([1.0, 0.0, 0.0])
    assert _anderson([z0], [g0]) is g0
    # the residual shrank by 0.999: the exact extrapolation is 999 plain steps away
    z1 = g0
    g1 = z1 + 0.999 * (g0 - z0)
    start = _anderson([z0, z1], [g0, g1])
    assert np.array_equal(start, g1)
    assert MAX_GAIN < 999.0
