"""Layout of the compiled mechanism: parameter array, state vector, outputs, each
declared once in a table (:class:`~recipsim.physics.layout_table.Layout`: name, unit,
meaning) that hands out the index constants the compiled code reads.

Everything the compiled (numba) functions need is passed as one float64 parameter
array ``par`` whose entries are named by the ``P_*`` constants (table :data:`PAR`, with
one :data:`BEARING` row per bearing); integer codes (drive, bearing law, bearing axis)
are stored as floats and converted inside. Only integer constants live at module
level: numba freezes module-level arrays into its cache, integers are harmless (the
tables are Python objects the compiled code never reads).

State vector ``y`` (table :data:`STATES`, ``N_STATE`` = 22 entries): ``N_COORD`` = 11
coordinates followed by their time derivatives in the same order
(``y[N_COORD + i] = d y[i] / dt``). Outputs: table :data:`OUTPUTS`; the names of the
slots the report writes are its column names.

Rod and piston coordinates are deviations from the rigid slider-crank at the current
crank angle ``y[Y_CRANK_ANGLE]``: they are of the size of the bearing deflections
(micrometres) whatever the crank angle, so one absolute tolerance fits them, and an
error in the crank angle is a phase error, not a spurious spring force.
"""

from __future__ import annotations

from recipsim.physics.layout_table import Layout

# --------------------------------------------------------------------------- bearings
#: Bearing numbers, as in the paper (1 primary ... 6 piston skirt), zero-based.
B_PRIMARY = 0
B_SECONDARY = 1
B_ECCENTRIC = 2
B_PIN = 3
B_PISTON_TOP = 4
B_PISTON_SKIRT = 5
N_BEARINGS = 6
BEARING_NAMES: tuple[str, ...] = (
    "primary",
    "secondary",
    "eccentric",
    "pin",
    "piston_top",
    "piston_skirt",
)

#: The rotor and eccentric journals (a journal law's bearings) and the piston's two
#: stations (the lubricated skirt's). The pin stays on the linear law: its journal does
#: not turn against its bushing by more than the rod's swing, so it runs squeeze-only at
#: eps near 1. The laws each bearing accepts are the bearing laws' registry's.
JOURNAL_NAMES: tuple[str, ...] = BEARING_NAMES[:3]
PISTON_STATION_NAMES: tuple[str, ...] = BEARING_NAMES[4:]

#: Bearing axis codes: the law acts in the plane normal to this axis.
AXIS_X = 0
AXIS_Y = 1
AXIS_Z = 2

#: Per-bearing parameter row (offsets within a row; row i starts at
#: ``P_BEARINGS + i * N_BEARING_PAR``).
BEARING = Layout("bearing parameters")
_b = BEARING.add
BP_LAW = _b("law", "code", "bearing law (the code of its bearing_laws module)")
BP_AXIS = _b("axis", "code", "axis code (AXIS_*); the force is normal to it")
BP_STIFFNESS = _b("stiffness", "N/m", "stiffness of the linear law")
BP_DAMPING = _b("damping", "N s/m", "damping of the linear law")
BP_CLEARANCE = _b("clearance", "m", "radial clearance (hydrodynamic laws; 0 for linear)")
BP_DIAMETER = _b("diameter", "m", "journal diameter (hydrodynamic laws)")
BP_LENGTH = _b("length", "m", "bearing length (hydrodynamic laws)")
BP_VISCOSITY = _b("viscosity", "Pa s", "oil dynamic viscosity at the film temperature")
BP_CONTACT_FILM = _b("contact_film", "m", "film thickness below which asperity contact starts")
BP_CONTACT_STIFFNESS = _b("contact_stiffness", "N/m^1.5", "contact penalty stiffness")
BP_CONTACT_FRICTION = _b("contact_friction", "-", "Coulomb friction coefficient of the contact")
BP_TABLE = _b(
    "table", "index", "offset of the finite_journal table in the bearing tables (-1: none)"
)
N_BEARING_PAR = BEARING.size

# ----------------------------------------------------------------------- parameters
PAR = Layout("mechanism parameters")
_p = PAR.add
P_CRANK_RADIUS = _p("crank_radius", "m", "crank radius r")
P_ROD_LENGTH = _p("rod_length", "m", "rod length L, big-end to small-end centres")
P_PISTON_AREA = _p("piston_area", "m2", "crown area pi D^2 / 4")
P_SHELL_PRESSURE = _p("shell_pressure", "Pa", "pressure under the piston")
P_SPEED = _p("speed", "rad/s", "crank speed of the constant_speed drive")
P_DRIVE = _p("drive", "code", "drive code (DRIVE_*)")
P_ROTOR_MASS = _p("rotor_mass", "kg", "rotor mass")
P_ROTOR_POLAR_INERTIA = _p("rotor_polar_inertia", "kg m2", "rotor inertia about the spin axis")
P_ROTOR_TRANSVERSE_INERTIA = _p(
    "rotor_transverse_inertia", "kg m2", "rotor inertia about a diameter through its CoM"
)
P_ROTOR_COM_Z = _p("rotor_com_z", "m", "axial position of the rotor centre of mass")
P_PRIMARY_Z = _p("primary_z", "m", "axial position of bearing 1")
P_SECONDARY_Z = _p("secondary_z", "m", "axial position of bearing 2")
P_ROD_MASS = _p("rod_mass", "kg", "connecting-rod mass")
P_ROD_COM_FRACTION = _p("rod_com_fraction", "-", "rod centre of mass from the big end / L")
P_ROD_INERTIA = _p("rod_inertia", "kg m2", "rod inertia about Z through its centre of mass")
P_PISTON_MASS = _p("piston_mass", "kg", "piston mass")
P_PISTON_INERTIA = _p(
    "piston_inertia", "kg m2", "piston inertia about Z (pin axis) through its CoM"
)
P_PISTON_PIN_U = _p(
    "piston_pin_u", "m", "pin centre along the piston axis from the CoM, + to crown"
)
P_PISTON_CROWN_U = _p("piston_crown_u", "m", "crown centre, same convention")
P_PISTON_TOP_U = _p("piston_top_u", "m", "piston_top bearing marker, same convention")
P_PISTON_SKIRT_U = _p("piston_skirt_u", "m", "piston_skirt bearing marker, same convention")
P_PIN_FROM_CROWN = _p("pin_from_crown", "m", "pin distance below the crown")
P_MOTOR_SYNC_SPEED = _p("motor_sync_speed", "rad/s", "induction motor: synchronous speed")
P_MOTOR_BREAKDOWN_TORQUE = _p(
    "motor_breakdown_torque", "N m", "induction motor: forward-field peak torque"
)
P_MOTOR_BREAKDOWN_SLIP = _p("motor_breakdown_slip", "-", "induction motor: slip at the peak")
P_MOTOR_BACKWARD_RATIO = _p(
    "motor_backward_ratio", "-", "induction motor: backward/forward field ratio"
)
P_COUNTERWEIGHT_MASS = _p("counterweight_mass", "kg", "rotor counterweight (point mass)")
P_COUNTERWEIGHT_RADIUS = _p("counterweight_radius", "m", "its distance from the spin axis")
P_COUNTERWEIGHT_ANGLE = _p(
    "counterweight_angle", "rad", "its angle ahead of the crank pin about +Z"
)
P_COUNTERWEIGHT_Z = _p("counterweight_z", "m", "its axial position (eccentric plane z = 0)")
P_DETAILED_OUTPUTS = _p(
    "detailed_outputs", "code", "1: also compute the post-processing outputs (peak film pressures)"
)
#: First bearing row.
P_BEARINGS = PAR.add_rows(BEARING, BEARING_NAMES)
N_PAR = PAR.size

#: Drive codes (``par[P_DRIVE]``), the drives' ``code`` in :mod:`.drives`.
DRIVE_CONSTANT_SPEED = 0
DRIVE_TORQUE_PROFILE = 1
DRIVE_INDUCTION_MOTOR = 2

# ---------------------------------------------------------------------------- state
#: Coordinates, then their time derivatives in the same order.
STATES = Layout("mechanism states")
_y = STATES.add
Y_ROTOR_X = _y("rotor_x", "m", "rotor centre of mass, X (0 when centred)")
Y_ROTOR_Y = _y("rotor_y", "m", "rotor centre of mass, Y")
Y_ROTOR_TILT_X = _y("rotor_tilt_x", "rad", "rotor tilt about X, first Cardan angle")
Y_ROTOR_TILT_Y = _y("rotor_tilt_y", "rad", "rotor tilt about the once-tilted Y, second angle")
Y_CRANK_ANGLE = _y("crank_angle", "rad", "spin about the twice-tilted Z: crank angle from TDC")
Y_ROD_DX = _y("rod_dx", "m", "rod CoM minus its rigid slider-crank position, X")
Y_ROD_DY = _y("rod_dy", "m", "rod CoM minus its rigid slider-crank position, Y")
Y_ROD_DANGLE = _y("rod_dangle", "rad", "rod angle minus its rigid slider-crank angle")
Y_PISTON_DX = _y("piston_dx", "m", "piston CoM minus its rigid position, X")
Y_PISTON_Y = _y("piston_y", "m", "piston centre of mass, lateral Y")
Y_PISTON_TILT = _y("piston_tilt", "rad", "piston tilt about Z (pin axis), secondary rotation")
N_COORD = STATES.size
Y_ROTOR_VX = _y("rotor_vx", "m/s", "d rotor_x / dt")
Y_ROTOR_VY = _y("rotor_vy", "m/s", "d rotor_y / dt")
Y_ROTOR_TILT_X_RATE = _y("rotor_tilt_x_rate", "rad/s", "d rotor_tilt_x / dt")
Y_ROTOR_TILT_Y_RATE = _y("rotor_tilt_y_rate", "rad/s", "d rotor_tilt_y / dt")
Y_CRANK_SPEED = _y("crank_speed", "rad/s", "d crank_angle / dt")
Y_ROD_DVX = _y("rod_dvx", "m/s", "d rod_dx / dt")
Y_ROD_DVY = _y("rod_dvy", "m/s", "d rod_dy / dt")
Y_ROD_DANGLE_RATE = _y("rod_dangle_rate", "rad/s", "d rod_dangle / dt")
Y_PISTON_DVX = _y("piston_dvx", "m/s", "d piston_dx / dt")
Y_PISTON_VY = _y("piston_vy", "m/s", "d piston_y / dt")
Y_PISTON_TILT_RATE = _y("piston_tilt_rate", "rad/s", "d piston_tilt / dt")
N_STATE = STATES.size

#: State names with units (``"rotor_x [m]"``), in state order.
STATE_NAMES: tuple[str, ...] = tuple(e.column for e in STATES.entries)

# ---------------------------------------------------------------------------- outputs
#: Bearing forces, displacements and per-bearing results come in series over
#: ``BEARING_NAMES`` (``A_BEARING_FORCE + 3 * i + k``, k = X, Y, Z).
OUTPUTS = Layout("mechanism outputs")
_a = OUTPUTS.add
_XYZ = tuple(f"{b}_{ax}" for b in BEARING_NAMES for ax in "xyz")
A_BEARING_FORCE = OUTPUTS.add_series(
    "bearing_force_{}",
    _XYZ,
    "N",
    "force on the journal-side body of the bearing (rotor for primary, secondary, eccentric; "
    "piston for pin, piston_top, piston_skirt) from the other body, inertial X, Y, Z (Z: 0, "
    "no gravity and no axial load in the model)",
)
A_BEARING_DISPLACEMENT = OUTPUTS.add_series(
    "bearing_displacement_{}",
    _XYZ,
    "m",
    "journal minus bushing marker, inertial X, Y, Z, only the components normal to the "
    "bearing axis (others 0): rotor, eccentric and pin (x, y, 0); piston bearings slide "
    "along X (0, y, 0); 0 on the pinned crank",
)
A_DRIVE_TORQUE = _a("drive_torque", "N m", "driving torque about the rotor axis")
A_GAS_FORCE = _a("gas_force", "N", "-(p - p_shell) A_p, along the piston axis")
A_KINETIC_ENERGY_ROTOR = _a("kinetic_energy_rotor", "J", "kinetic energy of the rotor")
A_KINETIC_ENERGY_ROD = _a("kinetic_energy_rod", "J", "kinetic energy of the rod")
A_KINETIC_ENERGY_PISTON = _a("kinetic_energy_piston", "J", "kinetic energy of the piston")
A_SPRING_ENERGY = _a("spring_energy", "J", "elastic energy of the linear bearings")
A_BEARING_POWER = _a(
    "bearing_power_loss",
    "W",
    "power absorbed by all bearings at this instant, -sum F.de/dt (as "
    "`bearing_dissipation_power`, not averaged)",
)
A_DRIVE_POWER = _a("drive_power", "W", "torque x spin rate about the rotor axis")
A_GAS_POWER = _a("gas_power", "W", "power of the gas force on the piston")
A_PISTON_DISPLACEMENT = _a("piston_displacement", "m", "crown axial displacement from rigid TDC")
A_PISTON_SPEED = _a("piston_speed", "m/s", "its time derivative (dV/dt = A_p * this)")
A_PISTON_LATERAL = _a(
    "piston_lateral_displacement", "m", "piston centre of mass off the bore axis, Y (flexible only)"
)
A_PISTON_TILT = _a("piston_tilt", "rad", "piston rotation about the pin axis Z (flexible only)")
A_CRANK_ANGLE = _a("crank_angle", "rad", "crank angle")
A_CRANK_SPEED = _a("crank_speed", "rad/s", "crank speed (constant for `constant_speed`)")
#: Per bearing i: friction torque about the bearing axis on the journal-side body at
#: ``A_BEARING_TORQUE + 2 i`` and on the bushing-side body at ``+ 2 i + 1``.
A_BEARING_TORQUE = OUTPUTS.add_series(
    "friction_torque_{}",
    tuple(f"{b}{side}" for b in BEARING_NAMES for side in ("", "_bushing")),
    "N m",
    "friction torque of the film (and contact) about the bearing axis on the journal-side body "
    "(rotor for primary, secondary, eccentric; the `_bushing` slots, not reported: on the "
    "bushing-side body); 0 for the linear law and the piston film",
)
A_BEARING_DISSIPATION = OUTPUTS.add_series(
    "bearing_power_loss_{}",
    BEARING_NAMES,
    "W",
    "power absorbed by the bearing at this instant: the film and contact, -(F.de/dt + T_j w_j "
    "+ T_b w_b) (the linear law: its damper's power)",
)
A_BEARING_CONTACT = OUTPUTS.add_series(
    "contact_force_{}",
    BEARING_NAMES,
    "N",
    "asperity contact normal force (0 while the film carries the load)",
)
A_PISTON_FRICTION = _a(
    "piston_friction_force",
    "N",
    "axial force of the piston film on the piston, positive towards the head",
)
A_PISTON_FRICTION_POWER = _a("piston_friction_power", "W", "power the axial film force dissipates")
#: Per bearing i: only when ``par[P_DETAILED_OUTPUTS]`` is set (post-processing), else 0.
A_BEARING_PEAK_PRESSURE = OUTPUTS.add_series(
    "film_peak_pressure_{}",
    BEARING_NAMES,
    "Pa",
    "largest film pressure at this instant (computed with P_DETAILED_OUTPUTS, else 0; the "
    "skirt film reports at piston_skirt)",
)
#: The skirt film's cache (not a result): its last two evaluations, each a row of
#: :data:`FILM_CACHE` (a validity flag, the arguments the film and its contact read and
#: their results), and the row used last at ``A_SKIRT_CACHE``. The film is the costliest
#: part of the right-hand side (8-20 us); the finite-difference Jacobian's columns of the
#: states that do not move the piston (the rotor's, the rod's, the gas's: 21 of 28)
#: find their arguments here and take the results bit for bit
#: (:func:`recipsim.physics.mechanics.bearing_forces.piston_skirt_forces`).
FILM_CACHE = Layout("film cache row")
_f = FILM_CACHE.add
FC_VALID = _f("valid", "code", "1 once the row holds an evaluation")
FC_ARGUMENTS = FILM_CACHE.add_series(
    "argument_{}",
    (
        "e_top", "e_skirt", "v_top", "v_skirt", "sliding_speed", "length", "radius",
        "clearance", "viscosity", "contact_film", "contact_stiffness", "contact_friction",
    ),
    "-",
    "argument of the film and its contact, in SI units (m, m/s, Pa s, N/m^1.5, -)",
)  # fmt: skip
N_FILM_ARGUMENTS = FILM_CACHE.size - FC_ARGUMENTS
FC_RESULTS = FILM_CACHE.add_series(
    "result_{}",
    ("f_top", "f_skirt", "friction", "contact_top", "contact_skirt"),
    "N",
    "forces at the stations, friction, and the contact's normal forces",
)
N_FILM_CACHE = FILM_CACHE.size
A_SKIRT_CACHE = _a("skirt_film_cache_last", "index", "row of the skirt film's cache used last")
A_SKIRT_CACHE_ROWS = OUTPUTS.add_rows(FILM_CACHE, ("skirt_film_cache_0", "skirt_film_cache_1"))
N_AUX = OUTPUTS.size
