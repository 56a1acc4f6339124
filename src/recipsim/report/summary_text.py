"""The summary of a run for a person: its key numbers in the units a compressor engineer
reads (W, bar, C, kg/h, rpm), as a table for the console (``recipsim run``), as Markdown
for ``summary.md`` and a notebook (:meth:`recipsim.Result._repr_markdown_`).

``summary.csv`` keeps every quantity in SI with its unit in the column name; this is a
reading of the same row, formatted for people (rounded for display only).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from recipsim.physics.motor_models import LOSSLESS
from recipsim.physics.thermo.pressure_sources import PRESSURE_SOURCES, PressureSource
from recipsim.results.loss_breakdown import COP_COST_COLUMNS, LOSS_COLUMNS

#: Kelvin at 0 C [K].
_ZERO_CELSIUS = 273.15
#: How many of the largest losses the summary names.
LARGEST_LOSSES = 3


def _value(row: Mapping[str, Any], column: str) -> float:
    """``row[column]`` as a float, NaN where it is missing or not a number."""
    try:
        value = float(row.get(column, math.nan))
    except (TypeError, ValueError):
        return math.nan
    return value


def _pressure_source(row: Mapping[str, Any]) -> PressureSource | None:
    name = str(row.get("pressure"))
    return PRESSURE_SOURCES[name] if name in PRESSURE_SOURCES else None


def _solves_gas(row: Mapping[str, Any]) -> bool:
    """Whether the row's pressure source solved the cylinder's gas."""
    source = _pressure_source(row)
    return source is not None and source.solves_gas


def pressure_label(row: Mapping[str, Any]) -> str:
    """How a title names the row's pressure source ("cylinder model", ...)."""
    source = _pressure_source(row)
    return source.label if source is not None else str(row.get("pressure"))


def _fmt(value: float, decimals: int) -> str:
    return "-" if not math.isfinite(value) else f"{value:.{decimals}f}"


def _celsius(row: Mapping[str, Any], column: str) -> str:
    return _fmt(_value(row, column) - _ZERO_CELSIUS, 1)


def _bar(row: Mapping[str, Any], column: str) -> str:
    pressure = _value(row, column) / 1e5
    return _fmt(pressure, 3 if abs(pressure) < 10.0 else 2)


def _watts(value: float) -> str:
    return _fmt(value, 1 if abs(value) < 1000.0 else 0)


def key_figures(row: Mapping[str, Any]) -> list[tuple[str, str, str]]:
    """The summary's rows as (quantity, value, unit), formatted for reading.

    Parameters
    ----------
    row : mapping
        A summary row (``summary.csv``'s columns, SI).

    Returns
    -------
    list of (str, str, str)
        The operating point, the performance (where the gas is simulated: capacity,
        electrical power where a motor model is on, shaft power, both COPs, the
        efficiencies, the mass flow, the discharge temperature), the largest losses of
        the loss chain and the convergence; ``-`` where a value does not apply.
    """
    rows = [
        ("refrigerant", str(row.get("refrigerant", "")), ""),
        ("evaporating temperature", _celsius(row, "evaporating_temperature [K]"), "C"),
        ("condensing temperature", _celsius(row, "condensing_temperature [K]"), "C"),
        ("suction pressure", _bar(row, "suction_pressure [Pa]"), "bar"),
        ("suction temperature", _celsius(row, "suction_temperature [K]"), "C"),
        ("discharge pressure", _bar(row, "discharge_pressure [Pa]"), "bar"),
        ("speed", _fmt(_value(row, "mean_crank_speed [rpm]"), 0), "rpm"),
    ]
    shaft = _value(row, "shaft_power [W]")
    capacity = _value(row, "cooling_capacity [W]")
    gas = _solves_gas(row)
    if gas:
        rows += [
            ("discharge temperature", _celsius(row, "discharge_temperature [K]"), "C"),
            ("mass flow", _fmt(_value(row, "discharge_mass_flow [kg/s]") * 3600.0, 3), "kg/h"),
            ("cooling capacity", _watts(capacity), "W"),
        ]
    rows += _powers(row, shaft, capacity)
    if gas:
        rows += [
            ("isentropic efficiency", _fmt(_value(row, "isentropic_efficiency [-]"), 3), "-"),
            ("volumetric efficiency", _fmt(_value(row, "volumetric_efficiency [-]"), 3), "-"),
        ]
    rows += largest_losses(row)
    return rows + [_convergence(row)]


def _powers(row: Mapping[str, Any], shaft: float, capacity: float) -> list[tuple[str, str, str]]:
    """Electrical power and COP where a motor model is on (``options.motor`` other than
    ``"lossless"``), else said to be the shaft power's; shaft power and its COP."""
    motor = row.get("motor", LOSSLESS.name) != LOSSLESS.name
    electrical = _value(row, "motor_electrical_power [W]")
    gas = _solves_gas(row)
    rows = [
        (
            "electrical power",
            _watts(electrical) if motor else "-",
            "W" if motor else "no motor model (options.motor): shaft power only",
        )
    ]
    rows.append(("shaft power", _watts(shaft), "W"))
    if gas:
        if motor:
            rows.append(("COP, electrical", _fmt(_value(row, "COP [-]"), 2), "-"))
        rows.append(("COP, shaft power", _fmt(capacity / shaft if shaft > 0 else math.nan, 2), "-"))
    return rows


def largest_losses(row: Mapping[str, Any]) -> list[tuple[str, str, str]]:
    """The :data:`LARGEST_LOSSES` terms of the loss chain (``loss_* [W]``,
    :mod:`recipsim.results.loss_breakdown`) that cost the most COP (the capacity a
    suction-side loss takes counted with its power), largest first, with their share of
    the power put in (electrical, else shaft) and their COP cost; none where the scene has
    no gas model."""
    losses = [
        (column, _value(row, column), _value(row, COP_COST_COLUMNS[column]))
        for column in LOSS_COLUMNS
    ]
    losses = [item for item in losses if math.isfinite(item[1]) and item[1] > 0.0]
    losses.sort(key=lambda item: -(item[2] if math.isfinite(item[2]) else item[1]))
    power = _value(row, "motor_electrical_power [W]")
    if not math.isfinite(power) or power <= 0.0:
        power = _value(row, "shaft_power [W]")
    rows = []
    for column, value, cost in losses[:LARGEST_LOSSES]:
        name = column.removeprefix("loss_").split(" [", 1)[0].replace("_", " ")
        notes = [f"{100.0 * value / power:.1f} % of the input"] if power > 0.0 else []
        if math.isfinite(cost):
            notes.append(f"costs {cost:.3f} of COP")
        rows.append(
            (f"loss: {name}", _watts(value), "W" + (f" ({', '.join(notes)})" if notes else ""))
        )
    return rows


def _convergence(row: Mapping[str, Any]) -> tuple[str, str, str]:
    revolutions = row.get("revolutions [-]", "")
    residual = _value(row, "cycle_residual [-]")
    state = "converged" if row.get("converged [-]", True) else "NOT converged"
    detail = f"in {revolutions} revolutions" + (
        f", cycle residual {residual:.1e}" if math.isfinite(residual) else ""
    )
    return ("periodic state", state, detail)


def summary_text(row: Mapping[str, Any]) -> str:
    """The key figures as an aligned plain-text table (the console after ``recipsim run``),
    headed by the case's name and what was run."""
    figures = key_figures(row)
    width = max(len(name) for name, _, _ in figures)
    digits = max(len(value) for _, value, _ in figures)
    lines = [
        f"{name:<{width}}  {value:>{digits}}  {unit}".rstrip() for name, value, unit in figures
    ]
    return "\n".join([_heading(row), *lines])


def summary_markdown(row: Mapping[str, Any], title: bool = True) -> str:
    """The key figures as a Markdown table (``summary.md``), under the case's name as a
    title (``title``; else only the line saying what was run, as a notebook shows it)."""
    lines = [f"# {row.get('case', '')}", ""] if title else []
    lines += [f"**{_heading(row)}**" if not title else _heading(row), ""]
    lines += ["| quantity | value | unit |", "|---|---:|---|"]
    lines += [f"| {name} | {value} | {unit} |" for name, value, unit in key_figures(row)]
    lines += ["", "All quantities, in SI with their units: `summary.csv`."]
    return "\n".join(lines) + "\n"


def _heading(row: Mapping[str, Any]) -> str:
    pressure = pressure_label(row)
    return (
        f"{row.get('case', '')}: {row.get('mechanics', '')} crank, {row.get('drive', '')}, "
        f"{pressure}"
    )
