"""The bundle benchmark compares equal work: the array and the NamedTuple kernels
return the same sum (each compiled in its own interpreter), and its timings are
positive numbers."""

from __future__ import annotations

import pytest

from recipsim.studies.bench.bundles import measure_variant


@pytest.mark.slow
def test_both_variants_compute_the_same_sum() -> None:
    array = measure_variant(8, "array")
    bundle = measure_variant(8, "namedtuple")
    assert array["value"] == pytest.approx(bundle["value"], rel=1e-15)
    for result in (array, bundle):
        assert result["compile"] > 0.0 and result["loop"] > 0.0 and result["call"] > 0.0
