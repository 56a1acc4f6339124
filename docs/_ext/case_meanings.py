"""Meanings of the case-file keys whose declaration carries no ``doc`` (kept by hand:
the declarations in :mod:`recipsim.case` are the source of units, defaults and ranges;
a key missing here shows its declaration's own ``doc``, or nothing)."""

MEANINGS = {
    "refrigerant": "refrigerant file ``refrigerants/<name>.toml`` (beside the case, its "
    "parent, ``$RECIPSIM_REFRIGERANTS`` or shipped)",
    "name": "case name, the report directory's name",
    "description": "one line for people",
    "extends": "base case deep-merged under this one (``name`` and ``description`` are not "
    "inherited)",
    "operating_point.evaporating_temperature": "dew point at the suction pressure",
    "operating_point.condensing_temperature": "bubble point at the discharge pressure",
    "operating_point.suction_pressure": "suction plenum pressure (instead of the evaporating "
    "temperature)",
    "operating_point.discharge_pressure": "discharge plenum pressure (transcritical points)",
    "operating_point.suction_temperature": "suction gas temperature at the compressor inlet",
    "operating_point.liquid_temperature": "liquid temperature at the expansion device (for "
    "the capacity)",
    "operating_point.shell_pressure": "pressure behind the piston; default: suction",
    "geometry.bore": "cylinder bore, the piston diameter",
    "geometry.stroke": "piston stroke, twice the crank radius",
    "geometry.connecting_rod_length": "between the big-end and small-end centres",
    "geometry.clearance_ratio": "clearance volume over swept volume",
    "geometry.clearance_volume": "cylinder volume at top dead centre",
    "valves.port_diameter": "diameter of the port in the valve plate",
    "valves.reed_width": "width of the reed (wider than the port)",
    "valves.reed_thickness": "thickness of the reed",
    "valves.reed_length": "free length of the cantilever reed",
    "valves.port_position": "clamp to port centre; default: reed length - width / 2",
    "valves.stop_height": "lift at which the reed meets its stop",
    "valves.youngs_modulus": "of the reed material",
    "valves.density": "of the reed material",
    "valves.damping_ratio": "of the reed's first mode",
    "valves.restitution": "coefficient of restitution at the seat and the stop",
    "valves.preload": "force holding the reed on its seat",
    "valves.flow_coefficient": "effective over geometric flow area",
    "valves.force_coefficient": "effective over geometric force area",
    "leakage.radial_clearance": "piston-cylinder radial gap",
    "heat_transfer.wall_temperature": "cylinder wall temperature",
    "solver.rtol": "relative tolerance of the integrator",
    "solver.cycle_tolerance": "largest change of the scaled states over a revolution at the "
    "periodic steady state",
    "solver.max_revolutions": "give up (not converged, exit 1) after this many",
    "solver.min_revolutions": "at least this many revolutions",
    "solver.samples_per_revolution": "rows of ``cycle.csv``",
    "motor.rated_torque": "torque at the rated speed",
    "motor.rated_speed": "speed at the rated torque",
    "rating_points.evaporating_temperature": "as in ``[operating_point]``",
    "rating_points.condensing_temperature": "as in ``[operating_point]``",
    "rating_points.discharge_pressure": "as in ``[operating_point]`` (transcritical)",
    "rating_points.suction_temperature": "as in ``[operating_point]``",
    "rating_points.liquid_temperature": "as in ``[operating_point]``",
    "rating_points.description": "one line for people",
    "limits.min_temperature": "lowest temperature of the model",
    "limits.max_temperature": "highest temperature of the model",
    "limits.max_pressure": "highest pressure of the model",
}
