"""A report's tables written as CSV without pandas: the same bytes as pandas' ``to_csv``.

A ``recipsim run`` writes its tables in a forked report process that would otherwise
import pandas for that alone (0.3 s of CPU on the 2-core machine, beside the solve).
The text of each cell is the one pandas writes (``DataFrame(columns).to_csv(path,
index=False)``, pandas 2): a float column through numpy's shortest repr (for float64
Python's repr, the same text at half the cost), missing values (NaN, None) empty,
integers and booleans as ``str`` gives them, the rest as Python's ``csv`` module quotes
them (minimal quoting, ``"\\n"`` line ends), which is what pandas' writer calls too.
``tests/unit/report/test_csv_tables.py`` compares the bytes with pandas' for the tables
of every scene, the sweep's table, records with different keys and the edge values.
"""

from __future__ import annotations

import csv
import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np


def _cell(value: Any) -> Any:
    """A value of an object column as pandas writes it: a missing one empty."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return ""
    return value


def _column_cells(values: Any) -> list[Any]:
    """A column's cells as pandas formats them (``na_rep`` empty)."""
    array = np.asarray(values)
    if array.dtype == np.float64:
        # Python's repr is numpy's shortest repr of a float64, text for text, at half
        # the cost of ``astype(str)`` (tests/unit/report/test_csv_tables.py)
        cells: list[Any] = list(map(repr, array.tolist()))
        for i in np.flatnonzero(np.isnan(array)).tolist():
            cells[i] = ""
        return cells
    if array.dtype.kind == "f":
        text = array.astype(str)
        text[np.isnan(array)] = ""
        return text.tolist()  # type: ignore[no-any-return]
    if array.dtype.kind in "iub":
        return array.astype(str).tolist()  # type: ignore[no-any-return]
    return [_cell(v) for v in array.tolist()]


def write_columns_csv(path: str | Path, columns: Mapping[str, Any]) -> None:
    """Write ``columns`` (name -> values, all of one length) as a CSV table with a header
    row, as ``pandas.DataFrame(columns).to_csv(path, index=False)`` does.

    Parameters
    ----------
    path : str or Path
        The file (overwritten).
    columns : mapping of str to array-like
        The table's columns in order: numpy arrays, or sequences of Python values (one
        value each: a row such as a summary).
    """
    cells = [_column_cells(values) for values in columns.values()]
    with open(path, "w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(list(columns))
        writer.writerows(zip(*cells, strict=True))


def record_column(cells: Sequence[Any]) -> Any:
    """One column of records (Python values, None where a record lacks it) as pandas
    holds it after ``DataFrame.from_records``: an int64 or float64 array where every value
    is a number (float64, NaN where one is missing), a bool array where every value is a
    bool, else the list itself (an object column).

    Parameters
    ----------
    cells : sequence
        The column's values, one per record.
    """
    kinds = set(map(type, cells))  # the few types present, not each value, are tested
    missing = type(None) in kinds
    kinds.discard(type(None))
    if not kinds:
        return list(cells)
    if all(issubclass(k, int | float) and not issubclass(k, bool) for k in kinds):
        return np.array(cells, float) if missing else np.array(cells)  # None -> NaN
    if not missing and all(issubclass(k, bool) for k in kinds):
        return np.array(cells, bool)
    return list(cells)


def write_records_csv(path: str | Path, records: Sequence[Mapping[str, Any]]) -> None:
    """Write ``records`` (column name -> value, one mapping per row) as a CSV table, as
    ``pandas.DataFrame.from_records(records).to_csv(path, index=False)`` does: every
    name in the order it first appears, a cell empty where a record lacks it."""
    names: dict[str, None] = {}
    for record in records:
        names.update(dict.fromkeys(record))
    columns = {name: record_column([record.get(name) for record in records]) for name in names}
    write_columns_csv(path, columns)


def write_row_csv(path: str | Path, row: Mapping[str, Any]) -> None:
    """Write one row (a summary: column name -> value) as a one-row CSV table, as
    ``pandas.DataFrame([row]).to_csv(path, index=False)`` does."""
    write_records_csv(path, [row])
