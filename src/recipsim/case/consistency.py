"""Checks across sections of a case, before integrating: option combinations this version
cannot simulate, geometry that cannot be built, solver settings that contradict the
options, a shell pressure the thermal network cannot model.

Each refusal is a :class:`~recipsim.errors.CaseError` naming the file, the key and what
is allowed.
"""

from __future__ import annotations

from recipsim.case.sections import (
    Geometry,
    OperatingPoint,
    Options,
    SolverSettings,
    Valves,
    ValveSpec,
)
from recipsim.errors import CaseError
from recipsim.physics.mechanics.crank_trains import CRANK_TRAINS
from recipsim.physics.mechanics.drives import DRIVES
from recipsim.physics.motor_models import MOTOR_MODELS
from recipsim.physics.speed_models import SPEED_MODELS
from recipsim.physics.thermo.thermal_models import THERMAL_MODELS
from recipsim.physics.thermo.valve_models import VALVE_MODELS


def check_solver(solver: SolverSettings, options: Options, file: str) -> None:
    """Refuse a start-up from rest the options cannot run, and a revolution range upside down."""
    if solver.start == "rest" and not DRIVES[options.drive].motor_curve:
        raise CaseError(
            file,
            "solver.start",
            f"'rest' (start-up from standstill) needs a motor that starts the crank: "
            f"options.drive = 'induction_motor' (with options.mechanics = 'flexible'), "
            f"not {options.drive!r}; allowed with this drive: 'periodic'",
        )
    if solver.start == "rest" and THERMAL_MODELS[options.thermal].shell_network:
        raise CaseError(
            file,
            "solver.start",
            "'rest' moves the plenums along the pull-down ramp, which the shell's thermal "
            "network would overwrite; allowed with options.thermal = 'network': 'periodic'",
        )
    if solver.min_revolutions > solver.max_revolutions:
        raise CaseError(file, "solver.min_revolutions", "must not exceed solver.max_revolutions")


def check_shell_pressure(op: OperatingPoint, options: Options, file: str) -> None:
    """The shell's thermal network models a low-side shell: at the suction pressure."""
    if THERMAL_MODELS[options.thermal].shell_network and op.shell_pressure != op.suction_pressure:
        raise CaseError(
            file,
            "operating_point.shell_pressure",
            f"{op.shell_pressure:.4g} Pa: options.thermal = 'network' models a low-side shell, "
            f"at the suction pressure {op.suction_pressure:.4g} Pa; allowed: not set",
        )


def check_buildable(geometry: Geometry, valves: Valves, options: Options, file: str) -> None:
    """Refuse geometry that cannot be built: ports wider than the bore, reeds narrower
    than their port, a liner too short for the stroke."""
    crown_at_bdc = geometry.stroke + geometry.clearance_volume / geometry.piston_area
    if geometry.liner_length is not None and geometry.liner_length <= crown_at_bdc:
        raise CaseError(
            file,
            "geometry.liner_length",
            f"{geometry.liner_length:.4g} m is too short: the piston crown travels "
            f"{crown_at_bdc:.4g} m from the head (stroke + clearance height); allowed: longer",
        )
    if not VALVE_MODELS[options.valves].uses_valve_data:
        return  # the lossless valves use no valve data
    for side in ("suction", "discharge"):
        valve: ValveSpec = getattr(valves, side)
        if valve.port_diameter >= geometry.bore:
            raise CaseError(
                file,
                f"valves.{side}.port_diameter",
                f"{valve.port_diameter:.4g} m; a port in the valve plate must be narrower than "
                f"the bore {geometry.bore:.4g} m",
            )
        if valve.reed_width <= valve.port_diameter:
            raise CaseError(
                file,
                f"valves.{side}.reed_width",
                f"{valve.reed_width:.4g} m cannot cover its port of {valve.port_diameter:.4g} m; "
                "allowed: wider than port_diameter",
            )


def check_supported(options: Options, file: str) -> None:
    """Refuse option combinations this version cannot simulate, before integrating."""
    if not CRANK_TRAINS[options.mechanics].flexible and DRIVES[options.drive].free_speed:
        raise CaseError(
            file,
            "options.drive",
            f"{options.drive!r} needs a crank whose speed can vary; the pinned mechanism turns "
            "at constant speed by definition: use options.drive = 'constant_speed' or "
            "options.mechanics = 'flexible'",
        )
    if SPEED_MODELS[options.speed].at_motor_load and (
        DRIVES[options.drive].free_speed or not MOTOR_MODELS[options.motor].circuit
    ):
        raise CaseError(
            file,
            "options.speed",
            "'motor_slip' runs the constant-speed cycle at the equivalent circuit's speed at "
            "load: it needs options.drive = 'constant_speed' and options.motor = "
            "'equivalent_circuit' (the induction_motor drive finds its speed itself)",
        )
