"""The summary read from the cycle table's columns as arrays (what a sweep point keeps,
:func:`recipsim.results.tables.summary_row`) equals the summary read from the cycle
table's DataFrame, value for value, and the DataFrame holds exactly those columns."""

from __future__ import annotations

import math

import numpy as np
import pytest

from recipsim.case.load import load_case
from recipsim.results.columns import Column
from recipsim.results.outcome import classify
from recipsim.results.run import simulate_case, simulate_row
from recipsim.results.tables import cycle_columns, cycle_table, summary, summary_row

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
    frame = cycle_table(run.solution)
    columns = cycle_columns(run.solution)
    assert list(frame.columns) == list(columns)
    for key, values in columns.items():
        assert frame[key].dtype == values.dtype
        assert np.array_equal(frame[key].to_numpy(), values, equal_nan=True)
    row, cycle = summary_row(run.solution)
    by_table = summary(run.solution, frame)
    by_table["status"], by_table["status_message"] = classify(run.solution, frame, by_table)
    row["status"], row["status_message"] = classify(run.solution, cycle, row)
    assert list(row) == list(by_table)
    differ = [k for k in row if k != "wall_time [s]" and not _same(row[k], by_table[k])]
    assert not differ
    again = simulate_row(case)
    assert list(again) == list(run.row)


def test_a_column_skips_nan_as_pandas_does() -> None:
    assert Column(np.array([np.nan, 2.0, -1.0])).min() == -1.0
    assert Column(np.array([np.nan, 2.0, -1.0])).max() == 2.0
    assert math.isnan(Column(np.array([np.nan, np.nan])).max())
    assert Column(np.array([3, 1], dtype=np.int64)).min() == 1
