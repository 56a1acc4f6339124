"""The summary read from only the columns it needs (what a sweep point keeps,
:func:`recipsim.results.tables.summary_row`) equals the summary read from the whole
cycle table, value for value, and the report's DataFrame holds exactly those columns."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from recipsim.case.load import load_case
from recipsim.pipeline import simulate_case, simulate_row
from recipsim.results.outcome import classify
from recipsim.results.sampled import nan_max, nan_min
from recipsim.results.tables import cycle_columns, summary, summary_row

_SHORT = {"solver.min_revolutions": 2, "solver.max_revolutions": 2}


def _same(a: object, b: object) -> bool:
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return type(a) is type(b) and a == b


@pytest.mark.parametrize(
    ("name", "overrides"),
    [
        ("reference_r134a_lbp", {}),  # rigid crank, constant speed
        ("reference_r134a_lbp_lubricated", _SHORT),  # oil films
        ("reference_r134a_lbp_coupled", _SHORT),  # flexible crank train, free speed
    ],
)
def test_the_summary_from_columns_equals_the_one_from_the_table(name, overrides) -> None:
    case = load_case(name).with_(overrides)
    run = simulate_case(case)
    assert run.solution is not None
    frame = run.cycle
    columns = cycle_columns(run.solution)
    assert list(frame.columns) == list(columns)
    for key, values in columns.items():
        assert frame[key].dtype == values.dtype
        assert np.array_equal(frame[key].to_numpy(), values, equal_nan=True)
    row, cycle = summary_row(run.solution)
    by_table = summary(run.solution, columns)
    by_table["status"], by_table["status_message"] = classify(run.solution, columns, by_table)
    row["status"], row["status_message"] = classify(run.solution, cycle, row)
    assert list(row) == list(by_table)
    differ = [k for k in row if k != "wall_time [s]" and not _same(row[k], by_table[k])]
    assert not differ
    # the summary's columns (a sweep point's) are the table's, the same arrays, fewer
    cheap = cycle_columns(run.solution, full=False)
    assert set(cheap) < set(columns) and "time [s]" not in cheap
    for key, values in cheap.items():
        assert np.array_equal(values, columns[key], equal_nan=True), key


@pytest.mark.parametrize(
    ("name", "overrides"),
    [
        ("reference_r134a_lbp", {}),  # rigid crank (the sweep maps' scene)
        ("reference_r134a_lbp_coupled", _SHORT),  # flexible crank train, free speed
        ("reference_r134a_lbp_lubricated", _SHORT),  # oil films
    ],
)
def test_a_sweep_points_row_is_the_runs_summary_row(name, overrides) -> None:
    """``simulate_row`` (a sweep point: the summary from the columns it reads) and
    ``simulate_case`` (``recipsim run``: from the whole table) give the same row, value for
    value, so the cheap path cannot drift from the report's."""
    case = load_case(name).with_(overrides)
    full = simulate_case(case).row
    point = simulate_row(case)
    assert list(point) == list(full)
    differ = [k for k in full if k != "wall_time [s]" and not _same(point[k], full[k])]
    assert not differ, {k: (point[k], full[k]) for k in differ}


@pytest.mark.parametrize(
    "values",
    [[np.nan, 2.0, -1.0], [np.nan, np.nan], [3, 1], [0.5], [-0.0, 0.0, np.inf]],
)
def test_extremes_skip_nan_as_pandas_does(values) -> None:
    array = np.array(values)
    for ours, theirs in ((nan_min, pd.Series(array).min()), (nan_max, pd.Series(array).max())):
        got = ours(array)
        assert (math.isnan(got) and math.isnan(theirs)) or got == theirs
