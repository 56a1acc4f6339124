"""Coefficient files: the ten coefficients of each rated quantity, written and read back.

A coefficient file is a CSV table, one row per quantity (the layout ``recipsim rate``
writes as ``coefficients.csv`` and reads as a maker's file with ``--coefficients``):

- ``quantity``: ``cooling_capacity``, ``power_input``, ``current`` or ``mass_flow``;
- ``unit``: the unit of X (``W``, ``kW``, ``Btu/h``, ``A``, ``kg/h``, ``lb/h``, ...);
- ``standard``: the rating standard the coefficients hold at (optional when read);
- ``temperature_unit``: the unit of S and D, ``degC`` or ``degF``;
- ``C1`` .. ``C10``: the coefficients in the standards' order
  (:mod:`recipsim.studies.rate.polynomial`);
- optional: ``S_min``, ``S_max``, ``D_min``, ``D_max`` (the range of validity, in
  ``temperature_unit``; the polynomial is not evaluated outside it), ``points`` (the good
  points fitted), ``source`` (the model's column each quantity comes from) and ``note``.

A row whose coefficients are empty says why a quantity was not fitted (its ``note``) and
is skipped when read.
"""

from __future__ import annotations

import io
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from recipsim.case.files import read_input_text
from recipsim.errors import CaseError
from recipsim.studies.rate.polynomial import COEFFICIENTS, evaluate, from_kelvin
from recipsim.units import to_si

#: Rated quantities and their SI unit.
SI_UNITS = {
    "cooling_capacity": "W",
    "power_input": "W",
    "current": "A",
    "mass_flow": "kg/s",
}
#: Units the makers publish each quantity in, by the temperature unit of the standard.
PUBLISHED_UNITS = {
    "degC": {"cooling_capacity": "W", "power_input": "W", "current": "A", "mass_flow": "kg/h"},
    "degF": {"cooling_capacity": "Btu/h", "power_input": "W", "current": "A", "mass_flow": "lb/h"},
}
#: Validity columns of a coefficient file (in its temperature unit).
RANGE_COLUMNS = ("S_min", "S_max", "D_min", "D_max")
_TEMPERATURE_ALIASES = {
    **dict.fromkeys(("degc", "c", "°c", "celsius"), "degC"),
    **dict.fromkeys(("degf", "f", "°f", "fahrenheit"), "degF"),
}
#: Largest coefficient file read [bytes].
MAX_BYTES = 1_000_000


def unit_factor(unit: str, quantity: str, file: str = "", key: str = "unit") -> float:
    """SI value of one ``unit`` of ``quantity`` (``"Btu/h"`` of capacity: 0.2931 W)."""
    return to_si(f"1 {unit}", SI_UNITS[quantity], file, key)


@dataclass(frozen=True)
class Polynomial:
    """One quantity's published polynomial.

    Attributes
    ----------
    quantity, unit, temperature_unit : str
        What it gives, in which unit, of S and D in which unit.
    coefficients : numpy.ndarray
        C1 .. C10.
    bounds : tuple of float
        ``S_min, S_max, D_min, D_max`` in ``temperature_unit`` (nan: unbounded).
    standard : str
        The standard named in the file ("" if none).
    """

    quantity: str
    unit: str
    temperature_unit: str
    coefficients: np.ndarray
    bounds: tuple[float, float, float, float]
    standard: str = ""

    def inside(self, s: np.ndarray, d: np.ndarray) -> np.ndarray:
        """Whether each (S, D) lies in the range of validity."""
        s_lo, s_hi, d_lo, d_hi = (b if math.isfinite(b) else np.nan for b in self.bounds)
        ok = np.ones(np.shape(s), dtype=bool)
        for value, lo, hi in ((s, s_lo, s_hi), (d, d_lo, d_hi)):
            if not np.isnan(lo):
                ok &= value >= lo - 1e-9
            if not np.isnan(hi):
                ok &= value <= hi + 1e-9
        return ok

    def si(self, evaporating: np.ndarray, condensing: np.ndarray) -> np.ndarray:
        """The quantity in SI at dew points ``evaporating``, ``condensing`` [K]; nan outside
        the range of validity (never extrapolated)."""
        s = np.atleast_1d(from_kelvin(evaporating, self.temperature_unit))
        d = np.atleast_1d(from_kelvin(condensing, self.temperature_unit))
        value = evaluate(self.coefficients, s, d) * unit_factor(self.unit, self.quantity)
        return np.where(self.inside(s, d), value, np.nan)


def coefficient_row(
    quantity: str,
    unit: str,
    standard: str,
    temperature_unit: str,
    coefficients: np.ndarray | None,
    extra: dict[str, Any],
) -> dict[str, Any]:
    """One row of ``coefficients.csv`` (``coefficients`` None: a quantity not fitted)."""
    row: dict[str, Any] = {
        "quantity": quantity,
        "unit": unit,
        "standard": standard,
        "temperature_unit": temperature_unit,
    }
    values = [math.nan] * len(COEFFICIENTS) if coefficients is None else list(coefficients)
    row.update(zip(COEFFICIENTS, (float(v) for v in values), strict=True))
    row.update(extra)
    return row


def read_coefficients(path: str | Path) -> dict[str, Polynomial]:
    """Read a coefficient file (the module's layout); the polynomials by quantity.

    Raises
    ------
    CaseError
        Naming the file, the row or column and what is expected.
    """
    file = str(path)
    text = read_input_text(Path(path), "coefficient", MAX_BYTES)
    try:
        table = pd.read_csv(io.StringIO(text.removeprefix("\ufeff")), skipinitialspace=True)
    except (pd.errors.ParserError, pd.errors.EmptyDataError, ValueError) as exc:
        raise CaseError(file, "", f"not a readable CSV file ({exc})") from None
    table.columns = [str(c).strip() for c in table.columns]
    missing = [c for c in ("quantity", "unit", "temperature_unit", *COEFFICIENTS) if c not in table]
    if missing:
        raise CaseError(file, missing[0], f"missing column; a coefficient file has {_LAYOUT}")
    polynomials: dict[str, Polynomial] = {}
    for number, row in enumerate(table.to_dict("records"), start=1):
        polynomial = _polynomial(row, file, f"row {number}")
        if polynomial is None:
            continue
        if polynomial.quantity in polynomials:
            raise CaseError(file, f"row {number}", f"{polynomial.quantity} is given twice")
        polynomials[polynomial.quantity] = polynomial
    if not polynomials:
        raise CaseError(file, "", "no row with ten coefficients")
    return polynomials


_LAYOUT = "quantity, unit, temperature_unit, C1 .. C10 (optional: standard, S_min .. D_max)"


def _polynomial(row: dict[str, Any], file: str, where: str) -> Polynomial | None:
    """A row as a :class:`Polynomial`; None for a row without coefficients."""
    quantity = str(row["quantity"]).strip()
    if quantity not in SI_UNITS:
        raise CaseError(file, f"{where}, quantity", f"{quantity!r}: one of {', '.join(SI_UNITS)}")
    values = [_number(row[c], file, f"{where}, {c}") for c in COEFFICIENTS]
    if all(math.isnan(v) for v in values):
        return None
    if any(math.isnan(v) for v in values):
        raise CaseError(file, where, "give all ten coefficients C1 .. C10, or none")
    unit = str(row["unit"]).strip()
    unit_factor(unit, quantity, file, f"{where}, unit")  # a unit of the right dimension
    t_unit = _TEMPERATURE_ALIASES.get(str(row["temperature_unit"]).strip().lower())
    if t_unit is None:
        raise CaseError(
            file, f"{where}, temperature_unit", f"{row['temperature_unit']!r}: degC or degF"
        )
    bounds = tuple(_number(row.get(c, math.nan), file, f"{where}, {c}") for c in RANGE_COLUMNS)
    standard = row.get("standard", "")
    return Polynomial(
        quantity,
        unit,
        t_unit,
        np.array(values),
        (bounds[0], bounds[1], bounds[2], bounds[3]),
        "" if pd.isna(standard) else str(standard).strip(),
    )


def _number(value: Any, file: str, where: str) -> float:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return math.nan
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise CaseError(file, where, f"{value!r} is not a number") from None
    if math.isinf(number):
        raise CaseError(file, where, "expected a finite number")
    return number
