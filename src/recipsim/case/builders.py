"""One builder per table of a case, from its raw TOML data to its section in SI: the
header, geometry, valves, heat transfer, solver and pressure curve (the operating point,
mechanism, motor and shell have modules of their own); :mod:`.build` runs them in order.
"""

from __future__ import annotations

import math
from dataclasses import replace
from functools import lru_cache
from pathlib import Path
from typing import Any

from recipsim.atomic import checked_name, name_from_stem
from recipsim.case.case_schema import (
    CLEARANCE_KEYS,
    GEOMETRY_SPEC,
    HEADER_SPEC,
    HEAT_TRANSFER_SPEC,
    PRESSURE_CURVE_SPEC,
    SIZE_KEYS,
    SOLVER_SPEC,
    VALVE_SPEC,
    VALVES_TOP_SPEC,
)
from recipsim.case.files import resolve_reference
from recipsim.case.mechanism import MechanismSpec
from recipsim.case.pressure_curve import read_pressure_curve
from recipsim.case.sections import (
    Geometry,
    HeatTransfer,
    Options,
    SolverSettings,
    Valves,
    ValveSpec,
)
from recipsim.errors import CaseError
from recipsim.physics.mechanics.tabulated import PressureCurve
from recipsim.physics.thermo.heat_transfer import HEAT_TRANSFER
from recipsim.physics.thermo.pressure_sources import PRESSURE_SOURCES
from recipsim.physics.thermo.thermal_models import THERMAL_MODELS
from recipsim.physics.thermo.valve_models import VALVE_MODELS
from recipsim.schema import Field, check_keys, read_table


@lru_cache(maxsize=64)
def refrigerant_search(file: str) -> tuple[Path, Path]:
    """The case file's folder and its parent, where its refrigerant file may lie (resolved
    once per file: a sweep validates a case at every point)."""
    folder = Path(file).resolve().parent
    return folder, folder.parent


def header(raw: dict[str, Any], file: str) -> dict[str, Any]:
    """Name, description and refrigerant; the name becomes a directory name."""
    top = read_table({k: raw[k] for k in HEADER_SPEC if k in raw}, HEADER_SPEC, file, "")
    # the name becomes a directory name: a plain file name or refused
    top["name"] = (
        name_from_stem(Path(file).stem) if top["name"] is None else checked_name(top["name"], file)
    )
    return top


def heat_transfer(raw: dict[str, Any] | None, options: Options, file: str) -> HeatTransfer:
    """``[heat_transfer]``: the wall temperature [K] is required unless the cylinder is
    adiabatic or the shell's network gives it; the coefficient [W/(m2 K)] nan: the
    correlation's own."""
    ht = read_table(raw, HEAT_TRANSFER_SPEC, file, "heat_transfer")
    # the network gives the wall temperature
    network = THERMAL_MODELS[options.thermal].shell_network
    exchanges = HEAT_TRANSFER[options.heat_transfer].exchanges_heat
    if exchanges and ht["wall_temperature"] is None and not network:
        raise CaseError(
            file,
            "heat_transfer.wall_temperature",
            f"required with options.heat_transfer = {options.heat_transfer!r} (e.g. '60 degC')",
        )
    return HeatTransfer(
        wall_temperature=ht["wall_temperature"] or math.nan,
        coefficient=math.nan if ht["coefficient"] is None else ht["coefficient"],
    )


def solver_settings(raw: dict[str, Any] | None, file: str) -> SolverSettings:
    """``[solver]``: tolerances, revolution limits, the start and the envelope policy."""
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
        step_budget=int(sv["step_budget"]),
    )


def with_liner_length(geometry: Geometry, mechanism: MechanismSpec) -> Geometry:
    """The liner's length where the case gives none: stroke, piston and clearance height."""
    if geometry.liner_length is not None:
        return geometry
    return replace(
        geometry,
        liner_length=geometry.stroke
        + mechanism.piston.length
        + geometry.clearance_volume / geometry.piston_area,
    )


def geometry(raw: dict[str, Any] | None, file: str, discharge_port_diameter: float) -> Geometry:
    """``[geometry]`` [m, m3]: one of clearance ratio, clearance volume and top clearance,
    a rod longer than the crank radius; the liner's length stays None where not given
    (:func:`with_liner_length`).

    With ``top_clearance`` the dead volume is built as the metal has it: the gap times
    the bore area, the discharge port through the valve plate (``discharge_port_diameter``
    [m], ``valve_plate_thickness`` long: its reed sits on the far side of the plate; the
    suction port lies upstream of its reed and is not dead volume) and
    ``other_dead_volume`` (reed recesses, the gasket's crevice), so a change of bore changes
    the clearance ratio.
    """
    g = read_table(raw, GEOMETRY_SPEC, file, "geometry")
    g["bore"] = _bore(g, file)
    area = math.pi * g["bore"] ** 2 / 4.0
    swept = area * g["stroke"]
    given = [key for key in CLEARANCE_KEYS if g[key] is not None]
    if len(given) != 1:
        raise CaseError(
            file,
            "geometry.clearance_ratio",
            "give exactly one of clearance_ratio, clearance_volume and top_clearance",
        )
    if g["top_clearance"] is not None:
        port = math.pi * discharge_port_diameter**2 / 4.0
        vc = g["top_clearance"] * area + g["valve_plate_thickness"] * port
        vc += g["other_dead_volume"]
    elif g["clearance_volume"] is not None:
        vc = g["clearance_volume"]
    else:
        vc = g["clearance_ratio"] * swept
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


def _bore(g: dict[str, Any], file: str) -> float:
    """The bore [m]: as given, or from ``displacement`` at the stroke (the bore's range
    holds for it too)."""
    given = [key for key in SIZE_KEYS if g[key] is not None]
    if not given:
        raise CaseError(file, "geometry.bore", "missing required key (or give displacement)")
    if len(given) > 1:
        raise CaseError(file, "geometry.bore", "give exactly one of bore and displacement")
    if g["bore"] is not None:
        return float(g["bore"])
    bore = math.sqrt(4.0 * g["displacement"] / (math.pi * g["stroke"]))
    field = GEOMETRY_SPEC["bore"]
    assert isinstance(field, Field)
    if not field.lo <= bore <= field.hi:
        raise CaseError(
            file,
            "geometry.displacement",
            f"{g['displacement']:.4g} m3 at the stroke {g['stroke']:.4g} m needs a bore of "
            f"{bore:.4g} m, outside the bore's {field.lo:g} to {field.hi:g} m",
        )
    return bore


def valves(raw: dict[str, Any] | None, options: Options, file: str) -> Valves:
    """``[valves]`` and its suction and discharge reeds (placeholders for ideal valves,
    which use none); the port position defaults to the reed's length less half its width."""
    raw = dict(raw or {})
    check_keys(raw, {*VALVES_TOP_SPEC, "suction", "discharge"}, file, "valves")
    top = read_table(
        {k: v for k, v in raw.items() if k not in ("suction", "discharge")},
        VALVES_TOP_SPEC,
        file,
        "valves",
    )
    specs = {}
    for side in ("suction", "discharge"):
        table = raw.get(side)
        if table is None and not VALVE_MODELS[options.valves].uses_valve_data:
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


def pressure_curve(
    raw: dict[str, Any] | None, options: Options, file: str, allow_external: bool = False
) -> PressureCurve | None:
    """The tabulated p(theta) curve: a CSV named relative to the case file."""
    table = read_table(raw, PRESSURE_CURVE_SPEC, file, "pressure_curve")
    if PRESSURE_SOURCES[options.pressure].solves_gas:
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
