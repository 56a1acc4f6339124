"""``recipsim bench``: error arithmetic, the ladder's sanity on the reference case,
unavailable options as rows, and the CSV contract of a quick run.

No timing is asserted: the wall times depend on the machine and its load.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from helpers import REFERENCE
from recipsim.case.load import load_case
from recipsim.cli.main import main
from recipsim.studies.bench.errors import MAX_ERROR, PRESSURE_ERROR, error_columns
from recipsim.studies.bench.ladder import Rung, build_ladder, reference_overrides
from recipsim.studies.bench.measure import OK, UNAVAILABLE, run_rung
from recipsim.studies.bench.report import RUN_COLUMNS, SETTING_COLUMNS, outcome_row

BEARINGS = ("primary", "secondary", "eccentric", "pin", "piston_top", "piston_skirt")


def _triangle(theta_deg: np.ndarray) -> np.ndarray:
    """A periodic pressure trace that is linear between multiples of 2 deg [Pa]."""
    return 1.0e6 + 1.0e3 * np.abs(np.mod(theta_deg, 360.0) - 180.0)


def test_errors_of_hand_made_summaries():
    """Relative errors, the pressure-trace RMS on another angle grid, and their maximum."""
    reference = {
        "discharge_mass_flow [kg/s]": 2.0e-3,
        "indicated_power [W]": 100.0,
        "COP [-]": math.nan,  # the reference lacks it: not compared
        "bearing_rms_primary [N]": 10.0,
        "bearing_max_primary [N]": 20.0,
    }
    values = {
        "discharge_mass_flow [kg/s]": 2.002e-3,  # +1e-3
        "indicated_power [W]": 99.0,  # -1e-2
        "COP [-]": 2.0,
        "bearing_rms_primary [N]": 10.0,  # exact
        # bearing_max_primary missing: infinite error
    }
    ref_angles = np.arange(720) * 0.5
    ref_trace = (ref_angles, _triangle(ref_angles))
    # the rung's trace: every 2 deg, shuffled, 500 Pa high: linear interpolation is exact,
    # so the RMS error is 500 Pa over the peak of 1.18e6 Pa
    angles = np.random.default_rng(1).permutation(np.arange(180) * 2.0)
    trace = (angles, _triangle(angles) + 500.0)
    err = error_columns(values, reference, trace, ref_trace)
    assert err["error_discharge_mass_flow [-]"] == pytest.approx(1e-3, rel=1e-9)
    assert err["error_indicated_power [-]"] == pytest.approx(1e-2, rel=1e-9)
    assert math.isnan(err["error_COP [-]"])
    assert err["error_bearing_rms_primary [-]"] == 0.0
    assert err["error_bearing_max_primary [-]"] == math.inf
    assert err[PRESSURE_ERROR] == pytest.approx(500.0 / 1.18e6, rel=1e-12)
    assert err[MAX_ERROR] == math.inf
    values["bearing_max_primary [N]"] = 19.0  # -5e-2: now the largest
    assert error_columns(values, reference, trace, ref_trace)[MAX_ERROR] == pytest.approx(5e-2)


@pytest.fixture(scope="module")
def reference_run():
    base = load_case(REFERENCE)
    ref = run_rung(REFERENCE, [], Rung("reference", overrides=reference_overrides()), base, 1)
    assert ref.status == OK
    return base, ref


def test_errors_fall_as_rtol_tightens(reference_run):
    """On the reference case, at cycle tolerance c = 1e-5: the max error falls from
    rtol 1e-4 to 1e-6 to 1e-8 until it reaches the floor the periodic iteration leaves.
    The floor: revolutions stop when the cycle residual is below c, which leaves errors
    of the order of c; 10 c is allowed."""
    base, ref = reference_run
    cycle = 1e-5
    floor = 10.0 * cycle
    errors = []
    for rtol in (1e-4, 1e-6, 1e-8):
        overrides = (
            "options.properties=heos",  # the reference's backend: integration error only
            # 2 deg steps: at rtol 1e-4 and the case's 5 deg the revolution-to-revolution
            # noise (2e-4) stays above this cycle tolerance
            "solver.max_step=2deg",
            f"solver.rtol={rtol:g}",
            f"solver.cycle_tolerance={cycle:g}",
        )
        rung = Rung(f"rtol={rtol:g}", overrides=overrides)
        out = run_rung(REFERENCE, [], rung, base, 1)
        assert out.status == OK, out.message
        errors.append(outcome_row(out, ref.quantities, ref.trace)[MAX_ERROR])
    assert errors[0] > floor  # rtol 1e-4 is far from the floor (about 7e-3)
    for loose, tight in zip(errors, errors[1:], strict=False):
        assert tight < loose or tight <= floor, errors
    assert errors[-1] <= floor, errors


def test_rejected_option_is_a_row_not_an_error(reference_run):
    """An override the case loader rejects gives an ``unavailable`` row with its message."""
    base, ref = reference_run
    rung = Rung("made-up backend", overrides=("options.properties=no_such_backend",))
    out = run_rung(REFERENCE, [], rung, base, 1)
    assert out.status == UNAVAILABLE
    assert "options.properties" in out.message and "no_such_backend" in out.message
    row = outcome_row(out, ref.quantities, ref.trace)
    assert row["status"] == UNAVAILABLE and row["properties"] == "no_such_backend"
    assert math.isnan(row[MAX_ERROR]) and math.isnan(row["median_wall_time [s]"])


def test_quick_bench_writes_every_column(tmp_path):
    """``recipsim bench --quick`` on the cylinder case: one row per rung, every column."""
    out = tmp_path / "bench"
    assert main(["bench", str(REFERENCE), "--quick", "--repeats", "1", "--out", str(out)]) == 0
    out = out / "reference_r134a_lbp_ideal"  # --out is the parent of <case>/
    frame = pd.read_csv(out / "work_precision.csv")
    quantities = ["discharge_mass_flow", "indicated_power", "COP"] + [
        f"bearing_{kind}_{b}" for b in BEARINGS for kind in ("rms", "max")
    ]
    expected = (
        list(SETTING_COLUMNS)
        + list(RUN_COLUMNS)
        + [f"error_{q} [-]" for q in quantities]
        + [PRESSURE_ERROR, MAX_ERROR]
    )
    assert set(expected) <= set(frame.columns), set(expected) - set(frame.columns)
    rungs = build_ladder(load_case(REFERENCE), quick=True)
    assert list(frame["rung"]) == [r.name for r in rungs]
    assert set(frame["status"]) <= {"ok", "unconverged", "unavailable", "failed"}
    done = frame[frame["status"] == "ok"]
    assert (done["baseline"]).any() and (~done["baseline"]).any()
    # every number is there (steps: solve_ivp does not report them)
    numbers = [c for c in expected[len(SETTING_COLUMNS) :] if c != "steps [-]"]
    assert np.isfinite(done[numbers].to_numpy(dtype=float)).all()
    assert (out / "work_precision.png").stat().st_size > 0
    assert (out / "bench.json").stat().st_size > 0


def test_rung_selection_by_regular_expression(tmp_path):
    """``--rungs`` keeps the matching rungs (searched), refuses a pattern that matches none
    (naming the rungs) or is not a regular expression, before anything is integrated."""
    from recipsim.errors import RecipsimError
    from recipsim.studies.bench.ladder import select_rungs

    ladder = build_ladder(load_case(REFERENCE), quick=True)
    assert select_rungs(ladder, None) == ladder
    stiff = select_rungs(ladder, "dopri5_stiff")
    assert [r.name for r in stiff] == [r.name for r in ladder if "dopri5_stiff" in r.name]
    assert stiff and len(stiff) < len(ladder)
    with pytest.raises(RecipsimError, match="matches no rung.*dopri5 rtol"):
        select_rungs(ladder, "no-such-rung")
    with pytest.raises(RecipsimError, match="not a regular expression"):
        select_rungs(ladder, "(")
    # the CLI refuses before the reference runs: no directory is written
    assert main(["bench", str(REFERENCE), "--quick", "--rungs", "(", "--out", str(tmp_path)]) == 1
    assert not any(tmp_path.iterdir())
