"""The rating's tables: the points in the standard's units, the fits and their residuals.

Quantities (SI inside, the makers' units in the tables: :data:`.coefficients.PUBLISHED_UNITS`):

- ``cooling_capacity``: the summary's ``cooling_capacity [W]`` (the standard's suction gas
  and liquid);
- ``power_input``: ``motor_electrical_power [W]`` where the case has a motor model
  (``options.motor`` other than ``lossless``), else ``shaft_power [W]``: the table and
  ``coefficients.csv`` say which;
- ``current``: ``motor_current [A]``, only with a motor model (otherwise left out, and
  ``coefficients.csv`` says why);
- ``mass_flow``: ``discharge_mass_flow [kg/s]`` (the flow the capacity is computed with).

S and D of each good point are the dew-point temperatures at its suction and discharge
pressures (for a pure refrigerant the grid's evaporating and condensing temperatures; for
a blend the discharge dew point lies above the condensing (bubble) temperature by the
glide).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from recipsim.case.case import Case
from recipsim.case.rating import STANDARDS, RatingStandard
from recipsim.case.refrigerant import case_fluid
from recipsim.physics.motor_models import MOTOR_MODELS
from recipsim.physics.thermo.property_backends import HEOS
from recipsim.studies.rate.coefficients import (
    PUBLISHED_UNITS,
    Polynomial,
    coefficient_row,
    unit_factor,
)
from recipsim.studies.rate.grid import RatingGrid
from recipsim.studies.rate.polynomial import PolynomialFit, RatingError, fit, from_kelvin
from recipsim.studies.sweep.worker import OK

#: Fits within this relative error at every grid point reproduce their grid [-].
GRID_TOLERANCE = 0.01
#: Decimals of the range of validity (in the standard's unit): a round-off of the dew point
#: solve (1e-12) never puts a grid point outside its own polynomial's range.
BOUND_DECIMALS = 6


@dataclass(frozen=True)
class Sources:
    """Which summary column each quantity comes from (None: left out, with why)."""

    columns: dict[str, str | None]
    notes: dict[str, str]


def quantity_sources(case: Case) -> Sources:
    """The summary columns of the rated quantities for ``case``'s options."""
    motor = case.options.motor
    if not MOTOR_MODELS[motor].circuit:
        power, current = "shaft_power [W]", None
        notes = {
            "power_input": "shaft power: the case has no motor model (options.motor = lossless)",
            "current": "not fitted: the case has no motor model (options.motor = lossless), "
            "so no current",
        }
    else:
        power, current = "motor_electrical_power [W]", "motor_current [A]"
        notes = {
            "power_input": f"electrical power of the motor model (options.motor = {motor})",
            "current": f"line current of the motor model (options.motor = {motor})",
        }
    columns = {
        "cooling_capacity": "cooling_capacity [W]",
        "power_input": power,
        "current": current,
        "mass_flow": "discharge_mass_flow [kg/s]",
    }
    notes["cooling_capacity"] = "cooling capacity at the standard's suction gas and liquid"
    notes["mass_flow"] = "refrigerant mass flow delivered"
    return Sources(columns, notes)


def conditions_text(standard: RatingStandard) -> str:
    """The standard's suction gas, liquid and ambient in words (degC)."""

    def c(kelvin: float) -> str:
        return f"{kelvin - 273.15:.1f} C"

    gas = (
        f"suction gas {c(standard.suction_temperature)}"
        if standard.suction_temperature is not None
        else f"superheat {standard.superheat:.1f} K"
    )
    if standard.liquid_temperature is not None:
        liquid = f"liquid {c(standard.liquid_temperature)}"
    elif standard.subcooling:
        liquid = f"subcooling {standard.subcooling:.1f} K"
    else:
        liquid = "liquid at the bubble point (no subcooling)"
    return f"{gas}, {liquid}, ambient {c(standard.ambient_temperature)}"


def dew_points(case: Case, table: pd.DataFrame) -> tuple[np.ndarray, np.ndarray]:
    """Suction and discharge dew-point temperatures [K] of the rows (nan where unsolved)."""
    fluid = case_fluid(case.refrigerant, HEOS.name)
    out = []
    for column in ("suction_pressure [Pa]", "discharge_pressure [Pa]"):
        pressures = pd.to_numeric(table.get(column, pd.Series(np.nan, index=table.index)))
        values = [
            fluid.saturation_temperature(float(p), 1.0)
            if math.isfinite(p) and p < case.refrigerant.critical_pressure
            else math.nan
            for p in pressures
        ]
        out.append(np.array(values, dtype=float))
    return out[0], out[1]


def ratings_table(
    case: Case, grid: RatingGrid, rows: pd.DataFrame, sources: Sources
) -> tuple[pd.DataFrame, dict[str, np.ndarray]]:
    """One row per grid point in the standard's units, and the quantities in SI.

    Returns
    -------
    table : pandas.DataFrame
        ``point``, ``status``, ``message``, the nominal evaporating and condensing and the
        dew-point temperatures S and D (the standard's unit), the quantities in the
        makers' units and ``COP [-]``.
    si : dict of str to numpy.ndarray
        ``S``, ``D`` [K] and each quantity in SI, nan where a point failed.
    """
    unit = grid.temperature_unit
    published = PUBLISHED_UNITS[unit]
    nominal = np.array(grid.points(), dtype=float)
    s_k, d_k = dew_points(case, rows)
    ok = (rows["status"] == OK).to_numpy()
    si: dict[str, np.ndarray] = {"S": np.where(ok, s_k, np.nan), "D": np.where(ok, d_k, np.nan)}
    table = pd.DataFrame(
        {
            "point": np.arange(len(rows)),
            "status": rows["status"].to_numpy(),
            "message": rows["message"].fillna("").to_numpy(),
            f"evaporating_temperature [{unit}]": nominal[:, 0],
            f"condensing_temperature [{unit}]": nominal[:, 1],
            f"suction_dew_temperature [{unit}]": from_kelvin(si["S"], unit),
            f"discharge_dew_temperature [{unit}]": from_kelvin(si["D"], unit),
        }
    )
    for quantity, column in sources.columns.items():
        if column is None:
            continue
        if column not in rows:
            raise RatingError(
                f"{case.name}: the summary has no {column!r}; a rating needs a case with a "
                "cylinder (options.pressure = 'cylinder')"
            )
        values = pd.to_numeric(rows[column]).to_numpy(dtype=float)
        si[quantity] = np.where(ok, values, np.nan)
        factor = unit_factor(published[quantity], quantity)
        table[f"{quantity} [{published[quantity]}]"] = si[quantity] / factor
    table["COP [-]"] = si["cooling_capacity"] / si["power_input"]
    return table, si


def fit_quantities(
    grid: RatingGrid, si: dict[str, np.ndarray], sources: Sources
) -> dict[str, PolynomialFit | str]:
    """Each quantity's fit over its good points, or why it was not fitted.

    Raises
    ------
    RatingError
        Fewer than ten good points for capacity or power input (the rating's point).
    """
    unit = grid.temperature_unit
    published = PUBLISHED_UNITS[unit]
    out: dict[str, PolynomialFit | str] = {}
    for quantity in sources.columns:
        if quantity not in si:
            out[quantity] = sources.notes[quantity]
            continue
        good = np.isfinite(si[quantity]) & np.isfinite(si["S"]) & np.isfinite(si["D"])
        values = si[quantity][good] / unit_factor(published[quantity], quantity)
        try:
            out[quantity] = fit(
                from_kelvin(si["S"][good], unit), from_kelvin(si["D"][good], unit), values, quantity
            )
        except RatingError:
            if quantity in ("cooling_capacity", "power_input"):
                raise
            out[quantity] = f"not fitted: {int(good.sum())} good points, ten needed"
    return out


def coefficients_table(
    grid: RatingGrid,
    fits: dict[str, PolynomialFit | str],
    si: dict[str, np.ndarray],
    sources: Sources,
) -> pd.DataFrame:
    """``coefficients.csv``: one row per quantity (empty coefficients, and why, for one
    not fitted), with the range of validity (the good points' bounds) and the standard's
    conditions."""
    unit = grid.temperature_unit
    # the dew points of the grid's temperatures come back from CoolProp within 1e-12 K
    s = np.round(from_kelvin(si["S"], unit), BOUND_DECIMALS)
    d = np.round(from_kelvin(si["D"], unit), BOUND_DECIMALS)
    conditions = conditions_text(STANDARDS[grid.standard])
    rows = []
    for quantity, result in fits.items():
        fitted = isinstance(result, PolynomialFit)
        extra = {
            "S_min": float(np.nanmin(s)),
            "S_max": float(np.nanmax(s)),
            "D_min": float(np.nanmin(d)),
            "D_max": float(np.nanmax(d)),
            "points": len(result.fitted) if isinstance(result, PolynomialFit) else 0,
            "source": sources.columns[quantity] or "",
            "conditions": conditions,
            "note": sources.notes[quantity] if fitted else str(result),
        }
        coefficients = result.coefficients if isinstance(result, PolynomialFit) else None
        rows.append(
            coefficient_row(
                quantity, PUBLISHED_UNITS[unit][quantity], grid.standard, unit, coefficients, extra
            )
        )
    return pd.DataFrame(rows)


def residuals_table(grid: RatingGrid, fits: dict[str, PolynomialFit | str]) -> pd.DataFrame:
    """``residuals.csv``: largest and RMS residual of each fit, absolute (the quantity's
    published unit) and relative, and whether every grid point is within 1 %."""
    rows = []
    for quantity, result in fits.items():
        if not isinstance(result, PolynomialFit):
            continue
        rows.append(
            {
                "quantity": quantity,
                "unit": PUBLISHED_UNITS[grid.temperature_unit][quantity],
                "points": len(result.fitted),
                "max_abs": result.max_abs,
                "rms_abs": result.rms_abs,
                "max_rel [-]": result.max_rel,
                "rms_rel [-]": result.rms_rel,
                "within_1_percent": bool(result.max_rel <= GRID_TOLERANCE),
            }
        )
    return pd.DataFrame(rows)


def add_fit_columns(
    table: pd.DataFrame,
    grid: RatingGrid,
    fits: dict[str, PolynomialFit | str],
    si: dict[str, np.ndarray],
) -> None:
    """Add ``<quantity>_polynomial [unit]`` and ``<quantity>_residual [-]`` to ``table``."""
    published = PUBLISHED_UNITS[grid.temperature_unit]
    for quantity, result in fits.items():
        if not isinstance(result, PolynomialFit):
            continue
        good = np.isfinite(si[quantity]) & np.isfinite(si["S"]) & np.isfinite(si["D"])
        fitted = np.full(len(table), np.nan)
        relative = np.full(len(table), np.nan)
        fitted[good] = result.fitted
        relative[good] = result.relative
        table[f"{quantity}_polynomial [{published[quantity]}]"] = fitted
        table[f"{quantity}_residual [-]"] = relative


def fitted_polynomials(grid: RatingGrid, coefficients: pd.DataFrame) -> dict[str, Polynomial]:
    """The fitted rows of ``coefficients.csv`` as :class:`Polynomial` objects."""
    out = {}
    for row in coefficients.to_dict("records"):
        if math.isnan(row["C1"]):
            continue
        out[row["quantity"]] = Polynomial(
            row["quantity"],
            row["unit"],
            grid.temperature_unit,
            np.array([row[f"C{i}"] for i in range(1, 11)], dtype=float),
            (row["S_min"], row["S_max"], row["D_min"], row["D_max"]),
            grid.standard,
        )
    return out


def rating_table(ratings: pd.DataFrame, grid: RatingGrid) -> pd.DataFrame:
    """Each quantity as a maker prints it: one row per (quantity, condensing
    temperature), one column per evaporating temperature (failed points empty)."""
    unit = grid.temperature_unit
    evap, cond = f"evaporating_temperature [{unit}]", f"condensing_temperature [{unit}]"
    blocks = []
    for quantity, published in PUBLISHED_UNITS[unit].items():
        column = f"{quantity} [{published}]"
        if column not in ratings:
            continue
        good = ratings.where(ratings["status"] == "ok")
        pivot = good.assign(**{evap: ratings[evap], cond: ratings[cond]}).pivot(
            index=cond, columns=evap, values=column
        )
        pivot.columns = [f"evaporating {e:g} {unit}" for e in pivot.columns]
        pivot.insert(0, "unit", published)
        pivot.insert(0, "quantity", quantity)
        block = pivot.reset_index()
        blocks.append(block[["quantity", "unit", cond, *pivot.columns[2:]]])
    return pd.concat(blocks, ignore_index=True)
