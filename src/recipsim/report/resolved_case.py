"""The report's ``case.toml``: the case as run, fully resolved.

No ``extends`` (the chain is merged), no ``rating_point`` (its temperatures are written),
the overrides applied, every declared value (defaults and derived values included:
``liner_length``, ``port_position``, ``atol``, ``shell_pressure``) in SI with its unit
written (``"0.022 m"``), so the file reads the same in any version whose defaults
differ. The refrigerant file and a tabulated pressure curve are copied beside it
(``refrigerants/<name>.toml``, the CSV by its file name), so :func:`recipsim.load_case`
reads the report directory alone and reproduces the run: every value is written with
``repr``, which reads back as the same float.

Tables validated by a declaration (:mod:`recipsim.schema`) are written from it; the
mechanism and bearing tables, validated by hand in :mod:`recipsim.case.mechanism`, from
the validated dataclasses with :data:`MECHANISM_UNITS`; a key or table this module does
not know is copied as it was read, which loads the same.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import asdict
from pathlib import Path
from typing import Any

from recipsim.case.case import Case
from recipsim.case.case_schema import (
    GEOMETRY_SPEC,
    HEAT_TRANSFER_SPEC,
    LEAKAGE_SPEC,
    OPERATING_POINT_SPEC,
    OPTION_SPEC,
    PRESSURE_CURVE_SPEC,
    SOLVER_SPEC,
    VALVE_SPEC,
    VALVES_TOP_SPEC,
)
from recipsim.case.files import resolve_reference
from recipsim.case.mechanism_schema import MECHANISM_UNITS as DECLARED_MECHANISM_UNITS
from recipsim.case.motor import MOTOR_SPEC
from recipsim.case.overrides import toml_literal
from recipsim.errors import CaseError
from recipsim.physics.mechanics.layout import BEARING_NAMES
from recipsim.physics.thermo.pressure_sources import PRESSURE_SOURCES
from recipsim.schema import Field, Spec, read_table
from recipsim.version import __version__

#: SI unit of each ``[mechanism.*]`` and ``[bearings.*]`` key written from the validated
#: dataclasses (:mod:`recipsim.case.mechanism_schema`); the counterweight keys are copied
#: as read (without a counterweight the dataclass holds radius 0, which is no valid input).
MECHANISM_UNITS = {
    key: unit
    for key, unit in DECLARED_MECHANISM_UNITS.items()
    if not key.startswith("counterweight_")
}

_SIMPLE_TABLES: dict[str, Spec] = {
    "options": OPTION_SPEC,
    "leakage": LEAKAGE_SPEC,
    "heat_transfer": HEAT_TRANSFER_SPEC,
    "motor": MOTOR_SPEC,
}
_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")


def resolved_case(case: Case) -> tuple[str, dict[str, bytes]]:
    """The resolved case file of ``case`` and the files that travel with it.

    Parameters
    ----------
    case : Case
        A validated case (its ``raw`` holds the merged, overridden file).

    Returns
    -------
    text : str
        The TOML text, headed by comments naming the source file and the overrides.
    files : dict of str to bytes
        Relative path (beside the case file) to content: the refrigerant file and the
        pressure-curve CSV of a tabulated case.
    """
    raw = case.raw
    file = case.path
    data: dict[str, Any] = {"name": case.name}
    if case.description:
        data["description"] = case.description
    data["refrigerant"] = case.refrigerant.name
    files = {f"refrigerants/{case.refrigerant.name}.toml": Path(case.refrigerant.path).read_bytes()}
    for key, value in raw.items():
        if key in ("name", "description", "refrigerant", "extends"):
            continue
        if key in _SIMPLE_TABLES:
            data[key] = _declared(read_table(value, _SIMPLE_TABLES[key], file, key), key)
        elif key == "pressure_curve":
            curve = _pressure_curve(case, value, files)
            if curve:
                data[key] = curve
        else:
            data[key] = value  # written below, or copied as read
    data["operating_point"] = _operating_point(case)
    data["geometry"] = _geometry(case)
    data["valves"] = _valves(case)
    data["solver"] = _solver(case)
    for key in ("mechanism", "bearings"):
        if isinstance(raw.get(key), Mapping):
            data[key] = _mechanism_table(raw[key], _mechanism_objects(case, key))
    header = [
        f"# The case as run by recipsim {__version__}, fully resolved: extends, the rating",
        "# point and the overrides applied; values in SI with their units.",
        f"# source: {case.path}",
    ] + [f"# --set {text}" for text in case.overrides]
    return "\n".join(header) + "\n\n" + toml_text(data), files


def _si_text(value: float, unit: str, integer: bool = False) -> Any:
    """A value for the TOML file: a bare number when dimensionless, else ``"<repr> <unit>"``."""
    if unit == "dimensionless":
        return int(value) if integer else value
    return f"{value!r} {unit}"


def _declared(values: Mapping[str, Any], table: str, spec: Spec | None = None) -> dict[str, Any]:
    """Values of a declared table (SI floats, strings, None) written with their units."""
    spec = spec if spec is not None else _SIMPLE_TABLES[table]
    out: dict[str, Any] = {}
    for key, value in values.items():
        if value is None or (isinstance(value, float) and math.isnan(value)):
            continue
        field = spec.get(key)
        if isinstance(field, Field):
            out[key] = _si_text(float(value), field.unit, field.integer)
        else:
            out[key] = value
    return out


def _operating_point(case: Case) -> dict[str, Any]:
    """The operating point as the file gave it (temperatures or pressures), the rating
    point's values written out and the shell pressure made explicit."""
    op = case.operating_point
    given = dict(case.raw.get("operating_point") or {})
    point = given.pop("rating_point", None)
    values = read_table(given, OPERATING_POINT_SPEC, case.path, "operating_point")
    if "ambient_temperature" not in given:
        values["ambient_temperature"] = None  # the default, or the standard's
    # a standard replaces the rating point's values (recipsim.case.rating)
    if point is not None and values["standard"] == "none":
        for key, value in case.refrigerant.rating_points[point].items():
            if key in values and values[key] is None and not _relative_given(key, given):
                values[key] = value
    values["rating_point"] = None
    values["shell_pressure"] = op.shell_pressure
    return _declared(values, "operating_point", OPERATING_POINT_SPEC)


def _relative_given(key: str, given: Mapping[str, Any]) -> bool:
    """Whether the case gives the superheat or subcooling that replaces ``key``."""
    relative = {"suction_temperature": "superheat", "liquid_temperature": "subcooling"}
    return relative.get(key) in given


def _geometry(case: Case) -> dict[str, Any]:
    """Geometry with the clearance as a volume and the liner length resolved."""
    g = case.geometry
    kept = ("bore", "stroke", "connecting_rod_length", "clearance_volume", "liner_length")
    values = {k: getattr(g, k) for k in kept}
    return _declared(values, "geometry", GEOMETRY_SPEC)


def _valves(case: Case) -> dict[str, Any]:
    v = case.valves
    out = _declared({k: getattr(v, k) for k in VALVES_TOP_SPEC}, "valves", VALVES_TOP_SPEC)
    given = case.raw.get("valves") or {}
    for side in ("suction", "discharge"):
        if side in given:  # the lossless valves read no valve data
            spec = getattr(v, side)
            out[side] = _declared({k: getattr(spec, k) for k in VALVE_SPEC}, side, VALVE_SPEC)
    return out


def _solver(case: Case) -> dict[str, Any]:
    s = case.solver
    given = case.raw.get("solver") or {}
    values = read_table(given, SOLVER_SPEC, case.path, "solver")
    values.update({k: getattr(s, k) for k in SOLVER_SPEC if hasattr(s, k)})
    return _declared(values, "solver", SOLVER_SPEC)


def _pressure_curve(case: Case, table: Any, files: dict[str, bytes]) -> dict[str, Any]:
    """The curve's CSV, copied beside the case file (empty when none is named)."""
    values = read_table(table, PRESSURE_CURVE_SPEC, case.path, "pressure_curve")
    if values["file"] is None:
        return {}
    try:
        path = resolve_reference(
            values["file"],
            case.path,
            "pressure_curve.file",
            "pressure curve",
            case.allow_external_paths,
        )
    except CaseError:
        if not PRESSURE_SOURCES[case.options.pressure].solves_gas:
            raise
        return {}  # named but unused, and gone: the resolved case needs none
    files[path.name] = path.read_bytes()
    return {"file": path.name}


def _mechanism_objects(case: Case, table: str) -> dict[str, Any]:
    """The validated dataclass behind each sub-table of ``[mechanism]`` or ``[bearings]``."""
    m = case.mechanism
    if table == "mechanism":
        return {"piston": m.piston, "connecting_rod": m.connecting_rod, "rotor": m.rotor}
    return dict(zip(BEARING_NAMES, m.bearings, strict=True))


def _mechanism_table(raw: Mapping[str, Any], objects: Mapping[str, Any]) -> dict[str, Any]:
    """Each known key from its validated value in SI (defaults included); others as read."""
    out: dict[str, Any] = {}
    for name, table in raw.items():
        spec = objects.get(name)
        if spec is None or not isinstance(table, Mapping):
            out[name] = table
            continue
        sub = dict(table)
        for key, value in asdict(spec).items():
            if key in MECHANISM_UNITS and value is not None:
                sub[key] = _si_text(float(value), MECHANISM_UNITS[key])
            elif isinstance(value, str):
                sub[key] = value
        out[name] = sub
    return out


def toml_text(data: Mapping[str, Any], prefix: str = "") -> str:
    """Write nested dicts of TOML values as TOML text (scalars first, then sub-tables)."""
    lines: list[str] = []
    tables = []
    for key, value in data.items():
        if isinstance(value, Mapping):
            tables.append((key, value))
        else:
            lines.append(f"{_key(key)} = {_value(value)}")
    text = "\n".join(lines) + ("\n" if lines else "")
    for key, value in tables:
        name = f"{prefix}.{_key(key)}" if prefix else _key(key)
        has_scalars = any(not isinstance(v, Mapping) for v in value.values())
        body = toml_text(value, name)
        text += (f"\n[{name}]\n" if has_scalars or not value else "") + body
    return text


def _key(key: str) -> str:
    return key if _BARE_KEY.fullmatch(key) else toml_literal(key)


def _value(value: Any) -> str:
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_value(v) for v in value) + "]"
    return toml_literal(value)
