"""A cycle table without pandas: the columns of :func:`recipsim.results.tables.cycle_table`
as numpy arrays, for the summary of a point whose table is not kept (a sweep point) and
for the figures and tables of a report process (which does not import pandas).

The summary reads a cycle table through :class:`CycleLike`: ``cycle[name].to_numpy()``,
``.min()`` and ``.max()`` (pandas' meaning: NaN skipped, NaN when every value is),
``name in cycle`` and ``cycle.columns``; a ``pandas.DataFrame`` and :class:`Columns` both
provide it, with the same values, so the summary is the same number for number. Building
the DataFrame and looking its columns up cost about as much as everything else the
summary does (1-2 ms a point).
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any, Protocol

import numpy as np


class ColumnLike(Protocol):
    """One column of a cycle table."""

    def to_numpy(self, dtype: Any = None) -> Any: ...

    def min(self) -> Any: ...

    def max(self) -> Any: ...


class CycleLike(Protocol):
    """What the summary reads of a cycle table."""

    def __getitem__(self, name: Any) -> Any: ...

    def __contains__(self, name: Any) -> bool: ...

    @property
    def columns(self) -> Any: ...


class Column:
    """A column: its values and pandas' ``min``/``max`` (NaN skipped)."""

    __slots__ = ("values",)

    def __init__(self, values: np.ndarray) -> None:
        self.values = values

    def to_numpy(self, dtype: Any = None) -> np.ndarray:
        """The values (not a copy, unless ``dtype`` asks for another type)."""
        return self.values if dtype is None else np.asarray(self.values, dtype=dtype)

    def _finite_part(self) -> np.ndarray:
        v = self.values
        return v[~np.isnan(v)] if v.dtype.kind == "f" else v

    def min(self) -> Any:
        """Smallest value, NaN skipped (NaN if none is left)."""
        v = self._finite_part()
        return v.min() if v.size else math.nan

    def max(self) -> Any:
        """Largest value, NaN skipped (NaN if none is left)."""
        v = self._finite_part()
        return v.max() if v.size else math.nan


class Columns:
    """Named columns of equal length (insertion order kept), read like a DataFrame."""

    __slots__ = ("_data",)

    def __init__(self, data: dict[str, np.ndarray]) -> None:
        self._data = data

    def __getitem__(self, name: str) -> Column:
        return Column(self._data[name])

    def __contains__(self, name: object) -> bool:
        return name in self._data

    @property
    def columns(self) -> Iterable[str]:
        """The column names, in order."""
        return list(self._data)


def as_columns(cycle: Any) -> Any:
    """The cycle table as a :class:`CycleLike`: ``cycle`` itself (a DataFrame or
    :class:`Columns`), or :class:`Columns` of it (a dict of numpy arrays), without
    pandas."""
    return Columns(cycle) if isinstance(cycle, dict) else cycle


def as_table(cycle: Any) -> Any:
    """The cycle table as a pandas DataFrame: ``cycle`` itself, or built from its columns
    (a dict of numpy arrays: pandas is imported only then, where the table is needed)."""
    if isinstance(cycle, dict):
        import pandas as pd

        return pd.DataFrame(cycle)
    return cycle
