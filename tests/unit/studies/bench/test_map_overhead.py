"""``bench-system``'s map overhead by stage: each stage timed where the sweep calls it,
the nested ones taken out of their outer stage, the shares adding up to the ratio."""

from __future__ import annotations

import pytest

from recipsim.errors import RecipsimError
from recipsim.studies.bench import map_overhead
from recipsim.studies.bench.map_overhead import (
    POINT_STAGES,
    STAGE_FUNCTIONS,
    format_overhead_stages,
    overhead_stages,
    stage_seconds_here,
)

SWEEP = """name = "tiny"
base = "reference_r134a_lbp"
[axes]
operating_point.shaft_speed = ["3000 rpm", "3500 rpm", "4000 rpm"]
"""


def test_every_stage_of_a_sweep_is_timed_and_the_functions_are_put_back(tmp_path):
    import recipsim.studies.sweep.store as store
    import recipsim.studies.sweep.worker as worker

    originals = (worker.point_case, store.PointStore.save)
    sweep = tmp_path / "tiny.toml"
    sweep.write_text(SWEEP)
    measured = stage_seconds_here(str(sweep), 1)
    assert (worker.point_case, store.PointStore.save) == originals
    assert measured["points"] == 3
    (run,) = measured["runs"]
    stages = run["stages"]
    assert set(stages) == set(STAGE_FUNCTIONS)
    # every stage ran; the solve call holds the solve's own timer, and the summary the
    # sampled outputs, both taken out
    assert all(stages[s] > 0.0 for s in STAGE_FUNCTIONS if s != "solve_call")
    assert stages["solve_call"] > -1e-4
    assert run["solve_sum [s]"] > stages["sampled_outputs"] > 0.0
    assert run["wall [s]"] > run["solve_sum [s]"] + sum(stages.values())

    result = overhead_stages(measured)
    shares = result["share_of_solves [-]"]
    assert sum(shares.values()) == pytest.approx(result["overhead_ratio [-]"], rel=1e-9)
    assert set(result["per_point [ms]"]) == {"solve", *POINT_STAGES}
    assert result["per_point [ms]"]["solve"] == pytest.approx(run["solve_sum [s]"] / 3 * 1e3)
    text = "\n".join(format_overhead_stages(result))
    assert "overhead by stage (1 worker, after start-up, 3 points)" in text
    assert "per sweep [ms]: plan" in text


def test_a_stage_whose_function_has_moved_fails_naming_it(tmp_path, monkeypatch):
    import recipsim.studies.sweep.worker as worker

    original = worker.point_case
    moved = {**STAGE_FUNCTIONS, "gone": ("recipsim.studies.sweep.engine", "_no_such_stage")}
    monkeypatch.setattr(map_overhead, "STAGE_FUNCTIONS", moved)
    sweep = tmp_path / "tiny.toml"
    sweep.write_text(SWEEP)
    with pytest.raises(RecipsimError, match="engine._no_such_stage is gone"):
        stage_seconds_here(str(sweep), 1)
    assert worker.point_case is original
