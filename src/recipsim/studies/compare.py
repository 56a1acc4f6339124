"""The comparison of two summary rows: ``comparison.csv`` and ``cases.csv``.

``comparison.csv`` has one row per numeric summary quantity (units in the name, as in
``summary.csv``) and the columns ``quantity``, ``group``, ``<case A>``, ``<case B>``,
``difference`` (B - A, in the quantity's unit) and ``relative_difference [-]``
((B - A) / |A|; NaN when A is 0 or either value is NaN). A quantity that only one case
has, or that is NaN in one case (the gas metrics of a tabulated-pressure run), is kept
with NaN. Rows are ordered by group: operating point, gas, energy, mechanism, bearing
(per bearing: RMS, peak, orbit radius), any quantity not known here ("other"), solver.

The text columns of the summary rows (refrigerant, options) and the boolean
``converged [-]`` go to ``cases.csv``, one row per case (:func:`case_records`).

This module knows the summary's column names but nothing of how they are computed.
"""

from __future__ import annotations

import math
import numbers
import re
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pandas as pd

#: Group names in the order the rows appear.
GROUPS: tuple[str, ...] = (
    "operating_point",
    "gas",
    "energy",
    "mechanism",
    "bearing",
    "other",
    "solver",
)

#: Known quantities per group, in row order (``bearing`` is matched by pattern).
_KNOWN: dict[str, tuple[str, ...]] = {
    "operating_point": (
        "evaporating_temperature [K]",
        "condensing_temperature [K]",
        "suction_pressure [Pa]",
        "suction_temperature [K]",
        "discharge_pressure [Pa]",
        "liquid_temperature [K]",
        "pressure_ratio [-]",
        "shaft_speed [rpm]",
        "swept_volume [m3]",
        "clearance_volume [m3]",
        "ambient_temperature [K]",
    ),
    "gas": (
        "discharge_mass_flow [kg/s]",
        "suction_mass_flow [kg/s]",
        "leakage_mass_flow [kg/s]",
        "suction_backflow_mass_flow [kg/s]",
        "discharge_backflow_mass_flow [kg/s]",
        "volumetric_efficiency [-]",
        "discharge_temperature [K]",
        "peak_cylinder_pressure [Pa]",
        "minimum_cylinder_pressure [Pa]",
        "discharge_overpressure [-]",
        "suction_underpressure [-]",
        "suction_valve_opening_angle [deg]",
        "suction_valve_closing_angle [deg]",
        "discharge_valve_opening_angle [deg]",
        "discharge_valve_closing_angle [deg]",
    ),
    "energy": (
        "cooling_capacity [W]",
        "indicated_power [W]",
        "shaft_power [W]",
        "isentropic_power [W]",
        "bearing_dissipation_power [W]",
        "motor_input_power [W]",
        "motor_rotor_loss_power [W]",
        "friction_power [W]",
        "motor_electrical_power [W]",
        "motor_loss_power [W]",
        "motor_efficiency [-]",
        "motor_power_factor [-]",
        "heat_to_wall [W]",
        "COP [-]",
        "indicated_COP [-]",
        "isentropic_efficiency [-]",
        "indicated_isentropic_efficiency [-]",
    ),
    "mechanism": (
        "mean_shaft_torque [N m]",
        "peak_shaft_torque [N m]",
        "minimum_shaft_torque [N m]",
        "mean_crank_speed [rpm]",
        "crank_speed_ripple [-]",
        "motor_slip [-]",
    ),
    "solver": (
        "mass_balance_residual [-]",
        "energy_balance_residual [-]",
        "revolutions [-]",
        "cycle_residual [-]",
        "rhs_evaluations [-]",
        "steps [-]",
        "rejected_steps [-]",
        "events [-]",
        "wall_time [s]",
    ),
}
_GROUP_OF = {q: g for g, names in _KNOWN.items() for q in names}
#: Group of a quantity not listed above, by its unit.
_GROUP_OF_UNIT = {"[kg/s]": "gas", "[W]": "energy", "[N m]": "mechanism", "[rpm]": "mechanism"}
#: Per-bearing quantities in row order within one bearing.
_BEARING_KINDS = ("bearing_rms", "bearing_max", "orbit_radius_max")
_BEARING_RE = re.compile(r"^(bearing_rms|bearing_max|orbit_radius_max)_(\w+) \[")

#: Fixed columns of the comparison table (a case may not be labelled with these).
FIXED_COLUMNS = ("quantity", "group", "difference", "relative_difference [-]")


def quantity_group(quantity: str) -> str:
    """Group of a summary quantity (one of :data:`GROUPS`).

    Parameters
    ----------
    quantity : str
        Summary column name with its unit, e.g. ``"bearing_rms_primary [N]"``.

    Returns
    -------
    str
        Its known group; ``"bearing"`` for ``bearing_rms_*``, ``bearing_max_*`` and
        ``orbit_radius_max_*``; for another quantity the group of its unit (``[kg/s]``
        gas, ``[W]`` energy, ``[N m]`` and ``[rpm]`` mechanism), otherwise ``"other"``.
    """
    if quantity in _GROUP_OF:
        return _GROUP_OF[quantity]
    if _BEARING_RE.match(quantity):
        return "bearing"
    return _GROUP_OF_UNIT.get(quantity[quantity.rfind(" ") + 1 :], "other")


def is_numeric(value: Any) -> bool:
    """Whether a summary value is a number (booleans and text are not)."""
    return isinstance(value, numbers.Real) and not isinstance(value, bool | np.bool_)


def numeric_quantities(rows: Sequence[Mapping[str, Any]]) -> list[str]:
    """Numeric quantities of the rows (numeric in any row), in comparison order.

    Within a group the known order is kept; unknown quantities follow in their order
    of first appearance; bearing quantities are grouped per bearing (bearings in
    order of first appearance), RMS, peak, orbit radius.
    """
    seen: list[str] = []
    for row in rows:
        seen += [k for k, v in row.items() if is_numeric(v) and k not in seen]
    bearings: list[str] = []
    for q in seen:
        m = _BEARING_RE.match(q)
        if m and m.group(2) not in bearings:
            bearings.append(m.group(2))

    def key(q: str) -> tuple[int, int, int]:
        group = quantity_group(q)
        g = GROUPS.index(group)
        if group == "bearing":
            m = _BEARING_RE.match(q)
            assert m is not None
            return g, bearings.index(m.group(2)), _BEARING_KINDS.index(m.group(1))
        known = _KNOWN.get(group, ())
        return g, known.index(q) if q in known else len(known), seen.index(q)

    return sorted(seen, key=key)


def relative_difference(a: Any, b: Any) -> np.ndarray:
    """(b - a) / |a|, NaN where a is 0 or either is NaN.

    Parameters
    ----------
    a, b : array_like
        Values of case A and case B (same unit).

    Returns
    -------
    numpy.ndarray
        Relative difference [-].
    """
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    ok = np.isfinite(a) & np.isfinite(b) & (a != 0.0)
    out = np.full(np.broadcast(a, b).shape, np.nan)
    np.divide(b - a, np.abs(a), out=out, where=ok)
    return out


def case_labels(name_a: str, name_b: str) -> tuple[str, str]:
    """Column labels of two cases: their names, suffixed ``_a``/``_b`` when equal.

    A name equal to a fixed column of the table (``quantity``, ``group``, ...) is
    suffixed too, so every column name is unique.
    """
    label_a, label_b = name_a, name_b
    if name_a == name_b:
        label_a, label_b = f"{name_a}_a", f"{name_b}_b"
    if label_a in FIXED_COLUMNS:
        label_a += "_a"
    if label_b in FIXED_COLUMNS:
        label_b += "_b"
    return label_a, label_b


def _value(row: Mapping[str, Any], quantity: str) -> float:
    value = row.get(quantity, math.nan)
    return float(value) if is_numeric(value) else math.nan


def comparison_table(
    row_a: Mapping[str, Any], row_b: Mapping[str, Any], label_a: str, label_b: str
) -> pd.DataFrame:
    """The comparison of two summary rows (the contents of ``comparison.csv``): columns
    ``quantity``, ``group``, ``label_a``, ``label_b``, ``difference`` (B - A, in the
    quantity's unit) and ``relative_difference [-]``; one row per numeric quantity of
    either row, in the order of :func:`numeric_quantities`.

    Parameters
    ----------
    row_a, row_b : mapping
        Summary rows (:func:`recipsim.results.tables.summary`), units in the keys.
    label_a, label_b : str
        Column names of the two cases (:func:`case_labels`); must differ from each
        other and from :data:`FIXED_COLUMNS`.
    """
    if label_a == label_b or {label_a, label_b} & set(FIXED_COLUMNS):
        raise ValueError(f"case labels must be distinct table columns: {label_a!r}, {label_b!r}")
    quantities = numeric_quantities([row_a, row_b])
    a = np.array([_value(row_a, q) for q in quantities], dtype=float)
    b = np.array([_value(row_b, q) for q in quantities], dtype=float)
    return pd.DataFrame(
        {
            "quantity": quantities,
            "group": [quantity_group(q) for q in quantities],
            label_a: a,
            label_b: b,
            "difference": b - a,
            "relative_difference [-]": relative_difference(a, b),
        }
    )


def case_records(
    rows: Sequence[Mapping[str, Any]],
    labels: Sequence[str],
    extra: Sequence[Mapping[str, Any]] | None = None,
) -> list[dict[str, Any]]:
    """The non-numeric summary columns per case (the rows of ``cases.csv``), one record
    per case.

    Parameters
    ----------
    rows : sequence of mapping
        Summary rows.
    labels : sequence of str
        Label of each case (its column in ``comparison.csv``).
    extra : sequence of mapping, optional
        Further columns per case (e.g. ``file``, ``overrides``, ``report``), placed
        after ``label``.

    Returns
    -------
    list of dict
        Per case: ``label``, the extra columns, then every text or boolean summary column
        (``case``, ``refrigerant``, ``pressure``, ``mechanics``, ..., ``converged [-]``).
    """
    records = []
    for k, (row, label) in enumerate(zip(rows, labels, strict=True)):
        record: dict[str, Any] = {"label": label}
        if extra is not None:
            record.update(extra[k])
        record.update({c: v for c, v in row.items() if not is_numeric(v)})
        records.append(record)
    return records
