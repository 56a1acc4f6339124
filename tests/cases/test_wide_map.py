"""A sample of the shipped wide maps (issue 18): every point ends ok, no_delivery,
subharmonic or outside_envelope, with consistent values.

The full maps (``cases/sweeps/wide_map_*.toml``, 4599 points: 2620 inside the envelopes,
all ok, and 1979 refused) are run by hand with ``recipsim sweep`` (2.3 minutes with 2
jobs on the shared 2-core machine); this test takes every 140th point of each (spread over all axes:
35 points, about 15 s on one core with a warm cache) through the sweep worker, as a sweep
runs them.
Checks (issue 18, "What must hold"): no NaN among an ok row's numbers, volumetric
efficiency never negative, mass and energy closures below 1e-3 on every ok row, and a
point beyond an envelope bound refused before integrating.
"""

import math

import pytest

from helpers import CASES
from recipsim.results.tables import GAS_SUMMARY
from recipsim.studies.sweep.plan import plan_sweep
from recipsim.studies.sweep.spec import load_sweep
from recipsim.studies.sweep.worker import PointTask, run_point

MAPS = sorted((CASES / "sweeps").glob("wide_map_*.toml"))
STRIDE = 140
ACCEPTED = {"ok", "no_delivery", "subharmonic", "outside_envelope"}
#: The cycle's results, finite on every ok row (the columns of options a map does not
#: switch on, e.g. the shell's thermal network or oil films, are NaN by definition).
RESULTS = (*GAS_SUMMARY, "indicated_power [W]", "shaft_power [W]", "peak_cylinder_pressure [Pa]")


def _sample() -> list[tuple[str, PointTask]]:
    tasks = []
    for path in MAPS:
        spec = load_sweep(path)
        for point in plan_sweep(spec)[::STRIDE]:
            task = PointTask(point.index, point.point_id, str(spec.base), point.overrides)
            tasks.append((f"{spec.name}-{point.index}", task))
    return tasks


SAMPLE = _sample()


def test_the_wide_maps_cover_every_shipped_refrigerant_with_500_points():
    refrigerants = set()
    total = 0
    for path in MAPS:
        spec = load_sweep(path)
        total += len(plan_sweep(spec))
        refrigerants |= {str(v) for k, values in spec.axes if k == "refrigerant" for v in values}
    assert total >= 500
    assert {"R134a", "R600a", "R290", "R1234yf", "R32", "R410A"} <= refrigerants
    assert any("r744" in p.stem for p in MAPS)


@pytest.mark.parametrize("name,task", SAMPLE, ids=[n for n, _ in SAMPLE])
def test_a_wide_map_point_ends_in_a_named_consistent_outcome(name, task):
    result = run_point(task)
    status, row = result["status"], result["summary"]
    assert status in ACCEPTED, result["message"]
    if status == "outside_envelope":
        assert "outside the envelope" in result["message"] and not row
        return
    assert row["volumetric_efficiency [-]"] >= 0.0
    assert abs(row["mass_balance_residual [-]"]) < 1e-3
    assert abs(row["energy_balance_residual [-]"]) < 1e-3
    if status == "ok":
        nan = [k for k in RESULTS if not math.isfinite(row[k])]
        assert not nan, nan
