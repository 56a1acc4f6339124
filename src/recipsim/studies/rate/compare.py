"""The rating against what a maker publishes: catalogue points and coefficient files.

A catalogue (the layout of :mod:`recipsim.studies.calibrate.data`: ``standard``, the
operating point's temperatures with units, the published quantities) is run point by
point, in the rating's sweep, each at its own standard; the model and the fitted
polynomial are then compared with each published value. The polynomial is evaluated only
at points rated at the rating's own standard and inside its range of validity (its value
is empty elsewhere, and the ``note`` says why): never extrapolated.

A maker's coefficient file (:mod:`.coefficients`) is evaluated at every good grid point
inside its range of validity and compared with the model there.
"""

from __future__ import annotations

import io
import math
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from recipsim.case.files import read_input_text
from recipsim.errors import CaseError
from recipsim.studies.calibrate.data import (
    MAX_DATA_BYTES,
    MeasuredPoint,
    find_data_file,
    read_points,
)
from recipsim.studies.rate.coefficients import PUBLISHED_UNITS, Polynomial, unit_factor
from recipsim.studies.rate.grid import RatingGrid
from recipsim.studies.rate.polynomial import from_kelvin
from recipsim.studies.sweep.worker import OK
from recipsim.units import to_si

#: Catalogue columns compared, and the rated quantity each one is.
CATALOGUE_TARGETS = {
    "cooling_capacity [W]": "cooling_capacity",
    "COP [-]": "COP",
    "motor_electrical_power [W]": "power_input",
    "motor_current [A]": "current",
    "discharge_mass_flow [kg/s]": "mass_flow",
}
#: The polynomial agrees with the catalogue as the model does within this [-].
CATALOGUE_TOLERANCE = 0.005


def read_catalogue(path: str | Path) -> list[MeasuredPoint]:
    """The points of a catalogue file, with the columns of :data:`CATALOGUE_TARGETS` it
    has as targets.

    Raises
    ------
    CaseError
        Naming the file and what is wrong (no comparable column, a bad cell).
    """
    path = find_data_file(path)  # a file, or a shipped catalogue by its file name
    text = read_input_text(path, "catalogue", MAX_DATA_BYTES)
    header = [str(c).strip() for c in pd.read_csv(io.StringIO(text), nrows=0).columns]
    targets = [c for c in CATALOGUE_TARGETS if c in header]
    if not targets:
        raise CaseError(str(path), "", f"no column to compare: one of {list(CATALOGUE_TARGETS)}")
    points, _ = read_points(path, targets)
    return points


def _kelvin(point: MeasuredPoint, key: str) -> float:
    value = point.overrides.get(f"operating_point.{key}")
    return math.nan if value is None else to_si(value, "K", "catalogue", key)


def _polynomial_value(
    target: str, polynomials: dict[str, Polynomial], t_evap: float, t_cond: float
) -> float:
    """The fitted polynomial's value of a catalogue column in SI (nan if not fitted)."""
    quantity = CATALOGUE_TARGETS[target]
    if quantity == "COP":
        if "cooling_capacity" not in polynomials or "power_input" not in polynomials:
            return math.nan
        capacity = _polynomial_value("cooling_capacity [W]", polynomials, t_evap, t_cond)
        power = polynomials["power_input"].si(np.array([t_evap]), np.array([t_cond]))[0]
        return float(capacity / power)
    if quantity not in polynomials:
        return math.nan
    return float(polynomials[quantity].si(np.array([t_evap]), np.array([t_cond]))[0])


def catalogue_table(
    points: list[MeasuredPoint],
    rows: pd.DataFrame,
    grid: RatingGrid,
    polynomials: dict[str, Polynomial],
) -> pd.DataFrame:
    """One row per catalogue point and published quantity: the catalogue's value, the
    model's and the polynomial's (SI, the unit in ``unit``), their relative errors and
    the polynomial's error less the model's."""
    out: list[dict[str, Any]] = []
    for point, (_, row) in zip(points, rows.iterrows(), strict=True):
        standard = str(point.overrides.get("operating_point.standard", "none"))
        t_evap, t_cond = (
            _kelvin(point, "evaporating_temperature"),
            _kelvin(point, "condensing_temperature"),
        )
        same = standard == grid.standard
        for target, published in _published(point).items():
            model = float(row[target]) if row["status"] == OK and target in row else math.nan
            poly = _polynomial_value(target, polynomials, t_evap, t_cond) if same else math.nan
            if not same:
                note = f"rated at {standard}: the {grid.standard} polynomial does not apply"
            elif math.isnan(poly):
                note = "outside the polynomial's range (not extrapolated), or not fitted"
            else:
                note = ""
            if target not in point.targets:
                note = "; ".join(n for n in ("published as capacity / COP", note) if n)
            error_model = (model - published) / published
            error_poly = (poly - published) / published
            out.append(
                {
                    "row": point.row,
                    "point": point.label,
                    "standard": standard,
                    "evaporating_temperature [K]": t_evap,
                    "condensing_temperature [K]": t_cond,
                    "status": row["status"],
                    "quantity": target.rsplit(" [", 1)[0],
                    "unit": target.rsplit(" [", 1)[1].rstrip("]"),
                    "catalogue": published,
                    "model": model,
                    "polynomial": poly,
                    "error_model [-]": error_model,
                    "error_polynomial [-]": error_poly,
                    "polynomial_minus_model [-]": error_poly - error_model,
                    "note": note,
                }
            )
    return pd.DataFrame(out)


def catalogue_note(table: pd.DataFrame) -> str:
    """One line: whether the polynomial's error against the catalogue is within
    :data:`CATALOGUE_TOLERANCE` of the model's at every point it applies to."""
    compared = table[table["polynomial_minus_model [-]"].notna()]
    if not len(compared):
        return "catalogue: no point at the rating's standard inside the polynomial's range"
    worst = compared.loc[compared["polynomial_minus_model [-]"].abs().idxmax()]
    gap = float(worst["polynomial_minus_model [-]"])
    verdict = "within" if abs(gap) <= CATALOGUE_TOLERANCE else "NOT within"
    return (
        f"catalogue: the polynomial's error is {verdict} {CATALOGUE_TOLERANCE:.1%} of the "
        f"model's at the {len(compared)} comparisons inside its range (largest "
        f"{gap:+.2%}: row {worst['row']}, {worst['quantity']})"
    )


def _published(point: MeasuredPoint) -> dict[str, float]:
    """The point's published values, with the power input derived as capacity / COP
    where the catalogue gives those two and not the power."""
    values = dict(point.targets)
    capacity, cop = values.get("cooling_capacity [W]"), values.get("COP [-]")
    if capacity and cop and "motor_electrical_power [W]" not in values:
        values["motor_electrical_power [W]"] = capacity / cop
    return values


def maker_table(
    makers: dict[str, Polynomial], grid: RatingGrid, si: dict[str, np.ndarray]
) -> pd.DataFrame:
    """The maker's polynomials against the model at every good grid point: one row per
    point and quantity, values in the rating's published units, ``difference [-]`` the
    model's relative to the maker's (empty outside the maker's range of validity)."""
    unit = grid.temperature_unit
    published = PUBLISHED_UNITS[unit]
    good = np.isfinite(si["S"]) & np.isfinite(si["D"])
    out = []
    for quantity, polynomial in makers.items():
        if quantity not in si:
            continue
        factor = unit_factor(published[quantity], quantity)
        maker = polynomial.si(si["S"][good], si["D"][good]) / factor
        model = si[quantity][good] / factor
        for s, d, m, k in zip(si["S"][good], si["D"][good], model, maker, strict=True):
            out.append(
                {
                    f"suction_dew_temperature [{unit}]": float(from_kelvin(s, unit)),
                    f"discharge_dew_temperature [{unit}]": float(from_kelvin(d, unit)),
                    "quantity": quantity,
                    "unit": published[quantity],
                    "model": m,
                    "maker": k,
                    "difference [-]": (m - k) / k,
                    "note": "" if math.isfinite(k) else "outside the maker's range of validity",
                }
            )
    return pd.DataFrame(out)
