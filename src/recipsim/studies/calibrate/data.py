"""Measured points for a calibration: a CSV file, one row per operating point.

Columns (the header names the unit, as the reports do):

- ``standard``: a rating standard, set as ``operating_point.standard``;
- ``<name> [<unit>]`` for an input: ``operating_point.<name>`` (or the dotted key itself
  when ``name`` contains a dot; ``suction_gas_temperature``, the standards' word, is
  ``suction_temperature``), the cell's number with the header's unit, validated by the
  case loader like any override;
- the targets (``--targets``; default ``cooling_capacity [W]`` and ``COP [-]`` where the
  file has them): summary quantities with the same name and unit; an empty cell means
  "not measured at this point".

Every value keeps its printed resolution: a catalogue rounds its figures (capacity to
1 W, COP to 0.01), and that rounding is a measurement uncertainty the fit propagates
(``resolution``: half a unit in the last printed digit).
"""

from __future__ import annotations

import csv
import difflib
import io
import math
import re
from collections.abc import Sequence
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

from recipsim.case.files import read_input_text
from recipsim.errors import CaseError

#: The package whose folder holds the shipped catalogues (``src/recipsim/data/catalogue``).
CATALOGUE_PACKAGE = "recipsim.data.catalogue"

#: Largest data file read [bytes]: a catalogue's table is a few kilobytes.
MAX_DATA_BYTES = 1_000_000
#: Most measured points fitted at once (each is simulated at every trial of the fit).
MAX_POINTS = 500

#: Targets fitted when the command names none (those the file has).
DEFAULT_TARGETS = ("cooling_capacity [W]", "COP [-]")
#: Column names of catalogues and standards for the case's operating-point keys.
ALIASES = {"suction_gas_temperature": "suction_temperature"}
_LABELLED = ("evaporating_temperature", "condensing_temperature", "discharge_pressure")
_HEADER = re.compile(r"^\s*([A-Za-z_][\w.]*)\s*\[([^\]]*)\]\s*$")


@dataclass(frozen=True)
class MeasuredPoint:
    """One row of the data file.

    Attributes
    ----------
    row : int
        1-based row number in the file (the header is row 0).
    label : str
        Short description for tables (the input values).
    overrides : dict of str to Any
        Dotted case key to value (a string with a unit, or a plain string).
    targets : dict of str to float
        Summary column to measured value.
    resolution : dict of str to float
        Summary column to half a unit in the last printed digit of the measured value.
    """

    row: int
    label: str
    overrides: dict[str, Any] = field(default_factory=dict)
    targets: dict[str, float] = field(default_factory=dict)
    resolution: dict[str, float] = field(default_factory=dict)


def printed_resolution(text: str) -> float:
    """Half a unit in the last printed digit of a number as written (``"1.02"`` ->
    0.005, ``"36"`` -> 0.5, ``"1.5e3"`` -> 50)."""
    mantissa, _, exponent = text.strip().lower().partition("e")
    decimals = len(mantissa.partition(".")[2])
    return 0.5 * 10.0 ** (-decimals + (int(exponent) if exponent else 0))


def _input_key(column: str, file: str) -> tuple[str, str]:
    """Case key and unit of an input column, ``("operating_point.x", "degC")``."""
    match = _HEADER.match(column)
    if match is None:
        raise CaseError(file, column, "an input column is named '<key> [<unit>]' (or 'standard')")
    name, unit = match.groups()
    key = name if "." in name else f"operating_point.{ALIASES.get(name, name)}"
    return key, unit.strip()


def _input_value(text: str, unit: str, file: str, where: str) -> Any:
    try:
        number = float(text)
    except ValueError:
        raise CaseError(file, where, f"{text!r} is not a number") from None
    if unit in ("", "-"):
        return number
    return f"{text.strip()} {unit}"


def shipped_catalogues() -> dict[str, Path]:
    """The shipped catalogues, file name to path (``danfoss_tles5.7kk.3_r600a.csv``)."""
    entries = resources.files(CATALOGUE_PACKAGE).iterdir()  # a namespace package's folder
    return {e.name: Path(str(e)) for e in sorted(entries, key=str) if e.name.endswith(".csv")}


def find_data_file(path: str | Path) -> Path:
    """The data file ``path`` names: the file itself where it exists, else, for a bare
    file name (with or without ``.csv``), the shipped catalogue of that name.

    Raises
    ------
    CaseError
        Neither: one line naming the shipped catalogues (and the closest name).
    """
    given = Path(path)
    if given.exists() or given.name != str(path):
        return given
    shipped = shipped_catalogues()
    for name in (given.name, f"{given.name}.csv"):
        if name in shipped:
            return shipped[name]
    close = difflib.get_close_matches(given.name, list(shipped), n=1)
    hint = f"; did you mean {close[0]!r}?" if close else ""
    raise CaseError(
        str(path),
        "",
        f"no such calibration data file (not a file here, nor a shipped catalogue: "
        f"{', '.join(shipped)}){hint}",
    )


def read_points(
    path: str | Path, targets: Sequence[str] | None = None, ignore: Sequence[str] = ()
) -> tuple[list[MeasuredPoint], tuple[str, ...]]:
    """Read a data file.

    Parameters
    ----------
    path : str or Path
        CSV file (header row, one operating point per row), or the file name of a
        shipped catalogue (:func:`find_data_file`).
    targets : sequence of str, optional
        Target columns (summary names with units). Default: :data:`DEFAULT_TARGETS`
        present in the file.
    ignore : sequence of str
        Columns that are neither inputs nor targets.

    Returns
    -------
    points : list of MeasuredPoint
    targets : tuple of str
        The target columns used.

    Raises
    ------
    CaseError
        Naming the file, the column (or row and column) and what is expected.
    """
    path = find_data_file(path)
    file = str(path)
    text = read_input_text(path, "calibration data", MAX_DATA_BYTES)
    try:
        rows = list(csv.reader(io.StringIO(text.removeprefix("\ufeff"), newline="")))
    except csv.Error as exc:  # a field over csv's size limit, a stray NUL
        raise CaseError(file, "", f"not a readable CSV file ({exc})") from None
    if len(rows) < 2:
        raise CaseError(file, "", "expected a header row and at least one data row")
    if len(rows) - 1 > MAX_POINTS:
        raise CaseError(file, "", f"{len(rows) - 1} rows; at most {MAX_POINTS} measured points")
    header = [h.strip() for h in rows[0]]
    repeated = sorted({h for h in header if header.count(h) > 1})
    if repeated:
        raise CaseError(file, repeated[0], "the column appears more than once; keep one")
    missing = [t for t in (targets or ()) if t not in header]
    if missing:
        raise CaseError(file, missing[0], f"no such column; the file has {header}")
    chosen = tuple(targets) if targets else tuple(t for t in DEFAULT_TARGETS if t in header)
    if not chosen:
        raise CaseError(file, "", f"no target column: name them with --targets ({header})")
    inputs = {
        c: (("operating_point.standard", "") if c == "standard" else _input_key(c, file))
        for c in header
        if c not in chosen and c not in ignore
    }
    points = []
    for number, cells in enumerate(rows[1:], start=1):
        if not any(cell.strip() for cell in cells):
            continue
        if len(cells) != len(header):
            raise CaseError(file, f"row {number}", f"{len(cells)} cells for {len(header)} columns")
        values = dict(zip(header, (c.strip() for c in cells), strict=True))
        point = MeasuredPoint(number, _label(values, inputs))
        for column, (key, unit) in inputs.items():
            if values[column]:
                where = f"row {number}, {column}"
                text = values[column]
                point.overrides[key] = (
                    text if column == "standard" else _input_value(text, unit, file, where)
                )
        for column in chosen:
            if values[column]:
                measured = float(_input_value(values[column], "", file, f"row {number}, {column}"))
                if not math.isfinite(measured) or measured == 0.0:
                    raise CaseError(file, f"row {number}, {column}", "expected a non-zero number")
                point.targets[column] = measured
                point.resolution[column] = printed_resolution(values[column])
        points.append(point)
    return points, chosen


def _label(values: dict[str, str], inputs: dict[str, tuple[str, str]]) -> str:
    parts = []
    for column, (_, unit) in inputs.items():
        if values[column] and (column == "standard" or column.startswith(_LABELLED)):
            parts.append(values[column] if column == "standard" else f"{values[column]}{unit}")
    return " ".join(parts)
