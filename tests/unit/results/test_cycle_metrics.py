"""Valve timing from a cycle table: the opening and closing crank angles are the ends
of the longest run of flowing samples round the circle."""

from __future__ import annotations

import math

import numpy as np
import pytest

from recipsim.results.cycle_metrics import _open_interval


def _longest_run_by_walking(angles: np.ndarray, flowing: np.ndarray) -> tuple[float, float]:
    """The longest circular run of True, first of the longest, walked sample by sample
    from a closed sample."""
    n = len(flowing)
    start = next(i for i in range(n) if not flowing[i])
    best_len, best = 0, (0, 0)
    i = 0
    while i < n:
        k = (start + i) % n
        if flowing[k]:
            j = i
            while j < n and flowing[(start + j) % n]:
                j += 1
            if j - i > best_len:
                best_len, best = j - i, ((start + i) % n, (start + j - 1) % n)
            i = j
        else:
            i += 1
    return float(angles[best[0]]), float(angles[best[1]])


def test_a_run_across_top_dead_centre_opens_before_and_closes_after_it() -> None:
    angles = np.arange(12) * 30.0
    flowing = np.zeros(12, dtype=bool)
    flowing[[10, 11, 0, 1]] = True  # 300 deg through 0 to 30 deg
    flowing[5] = True  # a shorter blip
    assert _open_interval(angles, flowing) == (300.0, 30.0)


def test_never_and_always_flowing() -> None:
    angles = np.arange(8) * 45.0
    assert all(math.isnan(a) for a in _open_interval(angles, np.zeros(8, dtype=bool)))
    assert _open_interval(angles, np.ones(8, dtype=bool)) == (0.0, 360.0)


@pytest.mark.parametrize("seed", range(20))
def test_the_longest_run_is_the_one_found_by_walking_the_circle(seed: int) -> None:
    rng = np.random.default_rng(seed)
    n = int(rng.integers(3, 60))
    flowing = rng.random(n) < rng.uniform(0.2, 0.9)
    if flowing.all() or not flowing.any():
        flowing[int(rng.integers(n))] = not flowing[0]
    angles = np.sort(rng.uniform(0.0, 360.0, n))
    assert _open_interval(angles, flowing) == _longest_run_by_walking(angles, flowing)
