"""The converged revolution as plain numpy columns, and their NaN-skipping extremes.

The summary of a cycle reads its table as a mapping of report column name (unit in the
name, ``"cylinder_pressure [Pa]"``) to a numpy array of one value per crank-angle sample
(:func:`recipsim.results.cycle.cycle_columns`); the report and the API make a pandas
DataFrame of the same columns.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

#: Report column name to its values at the crank-angle samples.
CycleColumns = Mapping[str, np.ndarray]


def nan_min(values: np.ndarray) -> float:
    """Smallest value, NaN skipped (NaN if every value is NaN), as pandas' ``min``."""
    finite = values[~np.isnan(values)] if values.dtype.kind == "f" else values
    return finite.min() if finite.size else math.nan


def nan_max(values: np.ndarray) -> float:
    """Largest value, NaN skipped (NaN if every value is NaN), as pandas' ``max``."""
    finite = values[~np.isnan(values)] if values.dtype.kind == "f" else values
    return finite.max() if finite.size else math.nan
