"""The declared keys of a case file's own tables: one :class:`~recipsim.schema.Field`
or :class:`~recipsim.schema.Choice` per key, with its unit, default, range and meaning.

The tables that have their own modules declare their keys there (``[motor]`` in
:mod:`.motor`, ``[thermal]`` in :mod:`.thermal`, ``[oil]`` in :mod:`.lubrication`,
``[mechanism]`` and ``[bearings]`` in :mod:`.mechanism_schema`). The case-file reference
in the docs is generated from these mappings (``docs/_ext/case_reference.py``).
"""

from __future__ import annotations

import math
from typing import Any

from recipsim.case.rating import RATING_SPEC
from recipsim.physics.friction_models import FRICTION_MODELS
from recipsim.physics.mechanics.bearing_laws.registry import BEARING_LAWS, JOURNAL_LAWS
from recipsim.physics.mechanics.crank_trains import CRANK_TRAINS
from recipsim.physics.mechanics.drives import DRIVES
from recipsim.physics.motor_models import MOTOR_MODELS
from recipsim.physics.speed_models import SPEED_MODELS
from recipsim.physics.thermo.heat_transfer import ANNAND, HEAT_TRANSFER
from recipsim.physics.thermo.leakage_models import GAP_LAWS, LEAKAGE
from recipsim.physics.thermo.pressure_sources import PRESSURE_SOURCES
from recipsim.physics.thermo.property_backends import PROPERTY_BACKENDS
from recipsim.physics.thermo.thermal_models import THERMAL_MODELS
from recipsim.physics.thermo.valve_models import VALVE_MODELS
from recipsim.schema import Choice, Field, Flag, Spec, Text

#: the top of the file: the case's name, its description and its refrigerant
HEADER_SPEC: Spec = {"name": Text(None), "description": Text(""), "refrigerant": Text()}

OPTION_SPEC: Spec = {
    "pressure": PRESSURE_SOURCES.schema_choice(),
    "properties": PROPERTY_BACKENDS.schema_choice(),
    "valves": VALVE_MODELS.schema_choice(),
    "heat_transfer": HEAT_TRANSFER.schema_choice(),
    "leakage": LEAKAGE.schema_choice(),
    "mechanics": CRANK_TRAINS.schema_choice(),
    "bearing_law": BEARING_LAWS.schema_choice(JOURNAL_LAWS),
    "drive": DRIVES.schema_choice(),
    "friction": FRICTION_MODELS.schema_choice(),
    "motor": MOTOR_MODELS.schema_choice(),
    "thermal": THERMAL_MODELS.schema_choice(),
    "speed": SPEED_MODELS.schema_choice(),
}

OPERATING_POINT_SPEC: Spec = {
    "rating_point": Text(None, "name of a rating point in the refrigerant file"),
    "evaporating_temperature": Field("K", None, lo=50.0, hi=700.0),
    "condensing_temperature": Field("K", None, lo=50.0, hi=700.0),
    "suction_pressure": Field("Pa", None, lo=0.0, open_lo=True, hi=1e9),
    "discharge_pressure": Field("Pa", None, lo=0.0, open_lo=True, hi=1e9),
    "suction_temperature": Field("K", None, lo=50.0, hi=700.0),
    "liquid_temperature": Field("K", None, lo=50.0, hi=700.0),
    "shell_pressure": Field("Pa", None, lo=0.0, open_lo=True, hi=1e9),
    "shaft_speed": Field("rad/s", lo=0.0, hi=2000.0, open_lo=True, doc="e.g. '3500 rpm'"),
    **RATING_SPEC,
}

GEOMETRY_SPEC: Spec = {
    "bore": Field("m", None, lo=1e-3, hi=0.5, doc="cylinder bore (or give displacement)"),
    "displacement": Field(
        "m^3",
        None,
        lo=1e-9,
        hi=0.05,
        doc="swept volume pi bore^2 stroke / 4, given instead of bore: the bore follows at "
        "the case's stroke (a member of a family named by its displacement)",
    ),
    "stroke": Field("m", lo=1e-3, hi=0.5),
    "connecting_rod_length": Field("m", lo=1e-3, hi=2.0),
    "clearance_ratio": Field("dimensionless", None, lo=0.0, hi=1.0, open_lo=True),
    "clearance_volume": Field("m^3", None, lo=0.0, open_lo=True),
    "top_clearance": Field(
        "m",
        None,
        lo=0.0,
        hi=0.01,
        open_lo=True,
        doc="piston crown to valve plate at top dead centre; the dead volume is then this "
        "gap times the bore area, the ports' volume and other_dead_volume",
        plausible=(0.03e-3, 0.15e-3),
        plausible_source="household LBP compressors run the crown 0.03-0.1 mm from the "
        "plate (an engineering estimate; no published survey found)",
    ),
    "valve_plate_thickness": Field(
        "m",
        0.0,
        lo=0.0,
        hi=0.05,
        plausible=(1.5e-3, 4e-3),
        plausible_source="household compressor valve plates, 2-3 mm of steel (an "
        "engineering estimate)",
        doc="length of the discharge port through the valve plate (with top_clearance: "
        "its volume is dead volume; the suction port lies upstream of its reed)",
    ),
    "other_dead_volume": Field(
        "m^3",
        0.0,
        lo=0.0,
        hi=1e-3,
        doc="with top_clearance: dead volume not in the gap or the ports (recesses, "
        "the piston's top land)",
        plausible=(0.0, 4e-8),
        plausible_source="reed recesses, the gasket's crevice and the crown's chamfer: "
        "0.1-0.5 % of a 7 cm3 swept volume, up to 0.04 cm3 (an engineering estimate)",
    ),
    "liner_length": Field("m", None, lo=1e-3, hi=1.0, doc="head to open end of the bore"),
}

#: The dead volume's keys, of which a case gives exactly one.
CLEARANCE_KEYS = ("clearance_ratio", "clearance_volume", "top_clearance")
#: The cylinder's size: its bore, or its displacement at the case's stroke.
SIZE_KEYS = ("bore", "displacement")

#: Groups of keys of which a case gives exactly one: a case (or an override) that sets one
#: of a group replaces whichever the case it extends gave (``{table: (group, ...)}``).
ALTERNATIVE_KEYS: dict[str, tuple[tuple[str, ...], ...]] = {
    "geometry": (CLEARANCE_KEYS, SIZE_KEYS),
}


def drop_replaced_alternatives(merged: dict[str, Any], chosen: dict[str, Any]) -> None:
    """Remove from ``merged`` (a case's raw data, modified in place) the keys of each
    :data:`ALTERNATIVE_KEYS` group that ``chosen`` (the extending case, or an override as
    a nested table) does not give, where ``chosen`` gives one of the group."""
    for table, groups in ALTERNATIVE_KEYS.items():
        mine = chosen.get(table)
        target = merged.get(table)
        if not isinstance(mine, dict) or not isinstance(target, dict):
            continue
        for group in groups:
            if any(key in mine for key in group):
                target = {k: v for k, v in target.items() if k in mine or k not in group}
        merged[table] = target


VALVE_SPEC: Spec = {
    "port_diameter": Field("m", lo=1e-4, hi=0.2),
    "reed_width": Field("m", lo=1e-4, hi=0.2),
    "reed_thickness": Field("m", lo=1e-6, hi=0.01),
    "reed_length": Field("m", lo=1e-4, hi=0.5),
    "port_position": Field("m", None, lo=1e-4, hi=0.5, doc="clamp to port centre"),
    "stop_height": Field("m", lo=1e-5, hi=0.05),
    "youngs_modulus": Field("Pa", 1.93e11, lo=1e9, hi=1e12),
    "density": Field("kg/m^3", 7800.0, lo=100.0, hi=30000.0),
    "damping_ratio": Field("dimensionless", 0.02, lo=0.0, hi=2.0),
    "restitution": Field("dimensionless", 0.3, lo=0.0, hi=1.0),
    "preload": Field("N", 0.0, lo=0.0, hi=1e4),
    "flow_coefficient": Field(
        "dimensionless",
        0.8,
        lo=0.0,
        hi=2.0,
        open_lo=True,
        plausible=(0.5, 1.0),
        plausible_source="effective flow area over the smaller of curtain and port, from "
        "steady-flow tests of reed valves (Ussyk 1984; Soedel, Design and Mechanics of "
        "Compressor Valves)",
    ),
    "force_coefficient": Field(
        "dimensionless",
        1.1,
        lo=0.0,
        hi=3.0,
        open_lo=True,
        plausible=(0.8, 1.6),
        plausible_source="effective force area over the port area: about 1 at small lift, "
        "more where the reed's rim carries pressure (Ussyk 1984; PDSim's reed example 1.17)",
    ),
    "flow_area": Choice(
        ("port", "reed_diameter"),
        "port",
        "curtain pi d x on the port's diameter (edge of the port) or the reed's (its rim)",
    ),
    "momentum_force": Flag(False, "the jet's momentum flux mdot^2/(rho A) pushes on the reed"),
}

VALVES_TOP_SPEC: Spec = {
    "flow_model": Choice(("real_gas", "ideal_gas"), "real_gas", "isentropic nozzle form"),
    "laminar_pressure_difference": Field(
        "Pa", 100.0, lo=0.0, hi=1e5, open_lo=True, doc="below it the flow goes linear in dp"
    ),
    "stick_velocity": Field("m/s", 0.01, lo=0.0, hi=10.0, doc="impacts slower than this stick"),
}

LEAKAGE_SPEC: Spec = {
    "model": GAP_LAWS.schema_choice(),
    "radial_clearance": Field(
        "m",
        6e-6,
        lo=0.0,
        hi=1e-3,
        open_lo=True,
        plausible=(3e-6, 15e-6),
        plausible_source="oil-sealed ringless pistons of household compressors, 5-15 um "
        "(c/R about 1e-3; Prata, Fernandes & Fagotti), 3 um for the tightest fits",
    ),
    "eccentricity_ratio": Field(
        "dimensionless",
        0.0,
        lo=0.0,
        hi=1.0,
        open_hi=True,
        doc="piston offset/clearance, rigid crank",
    ),
}

HEAT_TRANSFER_SPEC: Spec = {
    "wall_temperature": Field("K", None, lo=50.0, hi=900.0),
    "coefficient": Field(
        "dimensionless",
        None,
        lo=0.0,
        hi=100.0,
        doc="correlation constant a",
        plausible=(0.35, 0.8),
        plausible_when=(HEAT_TRANSFER.option, ANNAND.name),
        plausible_source="Annand (1963): a = 0.35-0.8 with the intensity of the gas motion",
    ),
}

SOLVER_SPEC: Spec = {
    "method": Choice(("dopri5", "dopri5_stiff", "ros34pw2"), "dopri5", "integrator"),
    "rtol": Field("dimensionless", 1e-6, lo=1e-13, hi=1e-2),
    "atol": Field("dimensionless", None, lo=1e-16, hi=1e-2, doc="on scaled states; default rtol"),
    "cycle_tolerance": Field("dimensionless", 1e-4, lo=1e-12, hi=0.1),
    "max_revolutions": Field("dimensionless", 60, lo=1, hi=10000, integer=True),
    "min_revolutions": Field("dimensionless", 2, lo=1, hi=1000, integer=True),
    "samples_per_revolution": Field("dimensionless", 720, lo=36, hi=100000, integer=True),
    "max_step": Field(
        "rad", math.radians(2.0), lo=1e-7, hi=math.pi, doc="largest crank-angle step"
    ),
    "step_budget": Field(
        "dimensionless",
        20_000_000,
        lo=1000,
        hi=1e12,
        integer=True,
        doc="most integration steps a solve may take; a case whose max_step alone needs "
        "more is refused before it starts, with an estimate",
    ),
    "start": Choice(
        ("periodic", "rest"),
        "periodic",
        "periodic steady state; 'rest': start-up from standstill (induction_motor drive)",
    ),
    "standstill_pressure": Field(
        "Pa",
        None,
        lo=0.0,
        open_lo=True,
        hi=1e9,
        doc="start = 'rest': equalised pressure; default saturation at the ambient temperature",
    ),
    "pull_down_time": Field(
        "s",
        2.5,
        lo=0.0,
        hi=60.0,
        doc="start = 'rest': plenums ramp from the standstill to the case's pressures",
    ),
    "periodic": Choice(("auto", "revolutions", "shooting"), "auto", "periodic steady-state solver"),
    "envelope": Choice(
        ("refuse", "ignore"), "refuse", "a point outside the refrigerant's [envelope]"
    ),
}

TOP_KEYS = {
    "name",
    "description",
    "refrigerant",
    "options",
    "operating_point",
    "geometry",
    "valves",
    "leakage",
    "heat_transfer",
    "solver",
    "mechanism",
    "bearings",
    "pressure_curve",
    "motor",
    "oil",
    "thermal",
    "friction",
}


PRESSURE_CURVE_SPEC: Spec = {
    "file": Text(None, "CSV with 'crank_angle [deg]' (from TDC) and 'cylinder_pressure [Pa]'"),
}
