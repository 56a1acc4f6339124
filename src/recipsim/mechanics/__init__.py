"""Crank train on visco-elastic bearings (after Kurka, Paulino & Izuka, ISMA 2010).

Modules, one job each:

- :mod:`.spec`: mechanism data (frozen dataclasses), case-table parser, reference
  compressor;
- :mod:`.layout`: index constants of the parameter array, state vector and outputs;
- :mod:`.parameters`: spec + geometry -> parameter array;
- :mod:`.bodies`: rigid-body kinematics of rotor, rod and piston markers;
- :mod:`.bearings`: bearing laws (``linear`` now), dispatched per bearing;
- :mod:`.pinned`: rigid slider-crank inverse dynamics (bearing reactions, torque);
- :mod:`.flexible`: compiled right-hand side of the flexible model, outputs,
  initial state, state accessors;
- :mod:`.tabulated`: p(theta) from CSV, periodic interpolation, ideal-cycle curve;
- :mod:`.simulate`: a thin ``solve_ivp`` driver to the periodic response.
"""

from .flexible import (
    flexible_output_history,
    flexible_outputs,
    flexible_rhs,
    flexible_rhs_tabulated,
    initial_state,
    piston_axial_displacement,
    piston_lateral_offset,
    piston_tilt,
    state_scales,
)
from .layout import BEARING_NAMES, N_AUX, N_PAR, N_STATE
from .parameters import mechanism_parameters
from .pinned import PinnedLoads, force_rms, pinned_loads, pinned_reactions
from .simulate import MechanismResult, pinned_torque_profile, simulate_mechanism
from .spec import (
    REFERENCE_SPEED,
    BearingSpec,
    ConnectingRodSpec,
    CrankGeometry,
    MechanismSpec,
    PistonSpec,
    RotorSpec,
    mechanism_from_dict,
    reference_geometry,
    reference_mechanism,
    reference_mechanism_tables,
    scale_bearings,
    with_damping,
)
from .tabulated import (
    PressureCurve,
    ideal_cycle_indicated_work,
    ideal_cycle_pressure_curve,
    periodic_linear_interpolation,
    read_pressure_curve,
    tabulated_pressure,
    tabulated_pressure_curve_from_arrays,
)

__all__ = [
    "BEARING_NAMES",
    "N_AUX",
    "N_PAR",
    "N_STATE",
    "REFERENCE_SPEED",
    "BearingSpec",
    "ConnectingRodSpec",
    "CrankGeometry",
    "MechanismResult",
    "MechanismSpec",
    "PinnedLoads",
    "PistonSpec",
    "PressureCurve",
    "RotorSpec",
    "flexible_output_history",
    "flexible_outputs",
    "flexible_rhs",
    "flexible_rhs_tabulated",
    "force_rms",
    "ideal_cycle_indicated_work",
    "ideal_cycle_pressure_curve",
    "initial_state",
    "mechanism_from_dict",
    "mechanism_parameters",
    "periodic_linear_interpolation",
    "pinned_loads",
    "pinned_reactions",
    "pinned_torque_profile",
    "piston_axial_displacement",
    "piston_lateral_offset",
    "piston_tilt",
    "read_pressure_curve",
    "reference_geometry",
    "reference_mechanism",
    "reference_mechanism_tables",
    "scale_bearings",
    "simulate_mechanism",
    "state_scales",
    "tabulated_pressure",
    "tabulated_pressure_curve_from_arrays",
    "with_damping",
]
