"""The sections of a case from its raw TOML data, one builder per table, in the order
the checks run: the header and refrigerant, options, operating point, geometry, valves,
leakage, heat transfer, solver, mechanism, then the checks across sections
(:mod:`.consistency`), the pressure curve, motor and shell.

:func:`case_sections` returns the keyword arguments of
:class:`~recipsim.case.case.Case`; :func:`recipsim.case.case.case_from_dict` builds it.
"""

from __future__ import annotations

import math
from dataclasses import replace
from functools import lru_cache
from pathlib import Path
from typing import Any

from recipsim.atomic import checked_name, name_from_stem
from recipsim.case.case_schema import (
    GEOMETRY_SPEC,
    HEADER_SPEC,
    HEAT_TRANSFER_SPEC,
    LEAKAGE_SPEC,
    OPTION_SPEC,
    PRESSURE_CURVE_SPEC,
    SOLVER_SPEC,
    TOP_KEYS,
    VALVE_SPEC,
    VALVES_TOP_SPEC,
)
from recipsim.case.consistency import (
    check_buildable,
    check_shell_pressure,
    check_solver,
    check_supported,
)
from recipsim.case.files import resolve_reference
from recipsim.case.mechanism import MechanismSpec, mechanism_from_dict
from recipsim.case.motor import case_motor
from recipsim.case.motor_losses import friction_option
from recipsim.case.operating_point import operating_point
from recipsim.case.pressure_curve import read_pressure_curve
from recipsim.case.refrigerant import case_fluid, load_refrigerant
from recipsim.case.schema import check_keys, read_table
from recipsim.case.sections import (
    Geometry,
    HeatTransfer,
    Leakage,
    Options,
    SolverSettings,
    Valves,
    ValveSpec,
)
from recipsim.case.thermal import parse_thermal
from recipsim.errors import CaseError
from recipsim.physics.mechanics.tabulated import PressureCurve


def case_sections(
    raw: dict[str, Any], file: str, *, allow_external_paths: bool = False
) -> dict[str, Any]:
    """Validate the raw TOML data of a case: the keyword arguments of its ``Case``
    (all but ``raw`` and ``source_text``)."""
    check_keys(raw, TOP_KEYS, file, "")
    top = _header(raw, file)
    search = list(_refrigerant_search(file))
    refrigerant = load_refrigerant(top["refrigerant"], file, "refrigerant", search)
    options = Options(**read_table(raw.get("options"), OPTION_SPEC, file, "options"))
    fluid = case_fluid(refrigerant, options.properties)
    op = operating_point(raw.get("operating_point"), refrigerant, fluid, file)
    geometry = _geometry(raw.get("geometry"), file)
    valves = _valves(raw.get("valves"), options, file)
    leakage = Leakage(**read_table(raw.get("leakage"), LEAKAGE_SPEC, file, "leakage"))
    heat = _heat_transfer(raw.get("heat_transfer"), options, file)
    solver = _solver(raw.get("solver"), file)
    check_solver(solver, options, file)
    mechanism = mechanism_from_dict(raw, file, bore=geometry.bore, default_law=options.bearing_law)
    geometry = _with_liner_length(geometry, mechanism)
    options = replace(options, friction=friction_option(options, mechanism, file))
    check_supported(options, file)
    check_buildable(geometry, valves, options, file)
    curve = _pressure_curve(raw.get("pressure_curve"), options, file, allow_external_paths)
    motor, circuit = case_motor(
        raw.get("motor"), options.drive, options.motor, op.shaft_speed, file
    )
    thermal = parse_thermal(raw.get("thermal"), file)
    check_shell_pressure(op, options, file)
    return {
        "name": top["name"],
        "description": top["description"],
        "path": file,
        "refrigerant": refrigerant,
        "options": options,
        "operating_point": op,
        "geometry": geometry,
        "valves": valves,
        "leakage": leakage,
        "heat_transfer": heat,
        "solver": solver,
        "mechanism": mechanism,
        "pressure_curve": curve,
        "motor": motor,
        "motor_circuit": circuit,
        "thermal": thermal,
    }


@lru_cache(maxsize=64)
def _refrigerant_search(file: str) -> tuple[Path, Path]:
    """The case file's folder and its parent, where its refrigerant file may lie (resolved
    once per file: a sweep validates a case at every point)."""
    folder = Path(file).resolve().parent
    return folder, folder.parent


def _header(raw: dict[str, Any], file: str) -> dict[str, Any]:
    """Name, description and refrigerant; the name becomes a directory name."""
    top = read_table({k: raw[k] for k in HEADER_SPEC if k in raw}, HEADER_SPEC, file, "")
    # the name becomes a directory name: a plain file name or refused
    top["name"] = (
        name_from_stem(Path(file).stem) if top["name"] is None else checked_name(top["name"], file)
    )
    return top


def _heat_transfer(raw: dict[str, Any] | None, options: Options, file: str) -> HeatTransfer:
    ht = read_table(raw, HEAT_TRANSFER_SPEC, file, "heat_transfer")
    network = options.thermal == "network"  # the network gives the wall temperature
    if options.heat_transfer != "adiabatic" and ht["wall_temperature"] is None and not network:
        raise CaseError(
            file,
            "heat_transfer.wall_temperature",
            f"required with options.heat_transfer = {options.heat_transfer!r} (e.g. '60 degC')",
        )
    return HeatTransfer(
        wall_temperature=ht["wall_temperature"] or math.nan,
        coefficient=math.nan if ht["coefficient"] is None else ht["coefficient"],
    )


def _solver(raw: dict[str, Any] | None, file: str) -> SolverSettings:
    sv = read_table(raw, SOLVER_SPEC, file, "solver")
    return SolverSettings(
        method=sv["method"],
        rtol=sv["rtol"],
        atol=sv["atol"] if sv["atol"] is not None else sv["rtol"],
        cycle_tolerance=sv["cycle_tolerance"],
        max_revolutions=int(sv["max_revolutions"]),
        min_revolutions=int(sv["min_revolutions"]),
        samples_per_revolution=int(sv["samples_per_revolution"]),
        max_step=sv["max_step"],
        periodic=sv["periodic"],
        start=sv["start"],
        standstill_pressure=math.nan
        if sv["standstill_pressure"] is None
        else sv["standstill_pressure"],
        pull_down_time=sv["pull_down_time"],
        envelope=sv["envelope"],
    )


def _with_liner_length(geometry: Geometry, mechanism: MechanismSpec) -> Geometry:
    """The liner's length where the case gives none: stroke, piston and clearance height."""
    if geometry.liner_length is not None:
        return geometry
    return replace(
        geometry,
        liner_length=geometry.stroke
        + mechanism.piston.length
        + geometry.clearance_volume / geometry.piston_area,
    )


def _geometry(raw: dict[str, Any] | None, file: str) -> Geometry:
    g = read_table(raw, GEOMETRY_SPEC, file, "geometry")
    area = math.pi * g["bore"] ** 2 / 4.0
    swept = area * g["stroke"]
    if (g["clearance_ratio"] is None) == (g["clearance_volume"] is None):
        raise CaseError(
            file,
            "geometry.clearance_ratio",
            "give exactly one of clearance_ratio and clearance_volume",
        )
    vc = (
        g["clearance_volume"] if g["clearance_volume"] is not None else g["clearance_ratio"] * swept
    )
    if g["connecting_rod_length"] <= 0.5 * g["stroke"]:
        raise CaseError(
            file,
            "geometry.connecting_rod_length",
            f"must exceed the crank radius {0.5 * g['stroke']:.4g} m",
        )
    return Geometry(
        bore=g["bore"],
        stroke=g["stroke"],
        connecting_rod_length=g["connecting_rod_length"],
        clearance_volume=vc,
        liner_length=g["liner_length"],  # None: set from the piston length by the caller
    )


def _valves(raw: dict[str, Any] | None, options: Options, file: str) -> Valves:
    raw = dict(raw or {})
    top = read_table(
        {k: v for k, v in raw.items() if k not in ("suction", "discharge")},
        VALVES_TOP_SPEC,
        file,
        "valves",
    )
    specs = {}
    for side in ("suction", "discharge"):
        table = raw.get(side)
        if table is None and options.valves == "ideal":
            table = _IDEAL_PLACEHOLDER
        v = read_table(table, VALVE_SPEC, file, f"valves.{side}")
        if v["port_position"] is None:
            v["port_position"] = v["reed_length"] - 0.5 * v["reed_width"]
        if v["port_position"] > v["reed_length"]:
            raise CaseError(file, f"valves.{side}.port_position", "must not exceed reed_length")
        specs[side] = ValveSpec(**v)
    return Valves(suction=specs["suction"], discharge=specs["discharge"], **top)


# the lossless valve model needs no valve data; these values are never used by it
_IDEAL_PLACEHOLDER = {
    "port_diameter": 5e-3,
    "reed_width": 6e-3,
    "reed_thickness": 2e-4,
    "reed_length": 1.5e-2,
    "stop_height": 1.5e-3,
}


def _pressure_curve(
    raw: dict[str, Any] | None, options: Options, file: str, allow_external: bool = False
) -> PressureCurve | None:
    """The tabulated p(theta) curve: a CSV named relative to the case file."""
    table = read_table(raw, PRESSURE_CURVE_SPEC, file, "pressure_curve")
    if options.pressure != "tabulated":
        return None
    if table["file"] is None:
        raise CaseError(
            file,
            "pressure_curve.file",
            "required with options.pressure = 'tabulated': a CSV beside the case with columns "
            "'crank_angle [deg]' (0 at top dead centre) and 'cylinder_pressure [Pa]'",
        )
    path = resolve_reference(
        table["file"], file, "pressure_curve.file", "pressure curve", allow_external
    )
    return read_pressure_curve(path, file)
