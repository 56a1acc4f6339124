"""The tabulated pressure curve of ``options.pressure = "tabulated"``: a CSV beside the
case with the columns ``crank_angle [deg]`` (from top dead centre) and
``cylinder_pressure [Pa]``, read and validated into a
:class:`~recipsim.physics.mechanics.tabulated.PressureCurve`.
"""

from __future__ import annotations

import csv
import io
import math
from pathlib import Path

import numpy as np

from recipsim.case.files import MAX_CSV_BYTES, read_input_text
from recipsim.errors import CaseError
from recipsim.physics.mechanics.tabulated import (
    ANGLE_COLUMN,
    PRESSURE_COLUMN,
    PressureCurve,
    tabulated_pressure_curve_from_arrays,
)


def read_pressure_curve(path: str | Path, case_file: str = "") -> PressureCurve:
    """Read and validate a tabulated pressure CSV (see the module docstring).

    Parameters
    ----------
    path : str or pathlib.Path
    case_file : str
        The case file naming ``path`` (for the message if ``path`` cannot be read).

    Returns
    -------
    PressureCurve

    Raises
    ------
    CaseError
        Missing, non-regular, oversized or non-UTF-8 file, missing column,
        non-numbers, non-monotonic angles, a span of a revolution or more,
        non-positive pressures. Messages name rows and columns, never the content of
        a file that is not a valid table.
    """
    file = str(path)
    text = read_input_text(
        Path(path), "pressure curve", MAX_CSV_BYTES, case_file, "pressure_curve.file"
    )
    try:
        rows = list(csv.reader(io.StringIO(text, newline="")))
    except csv.Error as exc:
        raise CaseError(file, "", f"not a valid CSV table ({exc})") from None
    if not rows:
        raise CaseError(file, "", f"empty; needs columns {ANGLE_COLUMN!r}, {PRESSURE_COLUMN!r}")
    header = [h.strip() for h in rows[0]]
    for col in (ANGLE_COLUMN, PRESSURE_COLUMN):
        if col not in header:
            raise CaseError(
                file,
                col,
                f"missing column in the first line ({len(header)} columns there); needs "
                f"{ANGLE_COLUMN!r} and {PRESSURE_COLUMN!r}",
            )
    ia, ip = header.index(ANGLE_COLUMN), header.index(PRESSURE_COLUMN)
    angles, pressures = [], []
    for n, row in enumerate(rows[1:], start=1):
        if not row or all(not c.strip() for c in row):
            continue
        values = []
        for col, i in ((ANGLE_COLUMN, ia), (PRESSURE_COLUMN, ip)):
            try:
                value = float(row[i])
            except (IndexError, ValueError):
                raise CaseError(file, f"{col}, row {n}", "not a number") from None
            if not math.isfinite(value):
                raise CaseError(file, f"{col}, row {n}", "not a finite number")
            values.append(value)
        angles.append(values[0])
        pressures.append(values[1])
    return tabulated_pressure_curve_from_arrays(np.array(angles), np.array(pressures), file)
