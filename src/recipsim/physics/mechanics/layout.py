"""Index constants of the compiled mechanism: parameter array, state vector, outputs.

Everything the compiled (numba) functions need is passed as one float64 parameter
array ``par`` whose entries are named by the ``P_*`` constants below; integer codes
(drive, bearing law, bearing axis) are stored as floats and converted inside. Only
integer constants live at module level: numba freezes module-level arrays into its
cache, integers are harmless.

State vector ``y`` (``N_STATE`` = 22 entries): ``N_COORD`` = 11 coordinates followed
by their time derivatives in the same order (``y[N_COORD + i] = d y[i] / dt``).

======  =====================  ==========================================================
index   name                   meaning [unit]
======  =====================  ==========================================================
0       ``Y_ROTOR_X``          rotor centre of mass, X [m] (0 when centred)
1       ``Y_ROTOR_Y``          rotor centre of mass, Y [m]
2       ``Y_ROTOR_TILT_X``     rotor tilt about X, first Cardan angle [rad]
3       ``Y_ROTOR_TILT_Y``     rotor tilt about the once-tilted Y, second angle [rad]
4       ``Y_CRANK_ANGLE``      spin about the twice-tilted Z = crank angle from TDC [rad]
5       ``Y_ROD_DX``           rod centre of mass minus its rigid slider-crank position, X [m]
6       ``Y_ROD_DY``           same, Y [m]
7       ``Y_ROD_DANGLE``       rod angle minus its rigid slider-crank angle [rad]
8       ``Y_PISTON_DX``        piston centre of mass minus its rigid position, X [m]
9       ``Y_PISTON_Y``         piston centre of mass, lateral Y [m]
10      ``Y_PISTON_TILT``      piston tilt about Z (pin axis), secondary rotation [rad]
11..21  ``Y_*_V*``, ...        time derivatives of 0..10; ``Y_CRANK_SPEED`` = 15 [rad/s]
======  =====================  ==========================================================

Rod and piston coordinates are deviations from the rigid slider-crank at the current
crank angle ``y[Y_CRANK_ANGLE]``: they are of the size of the bearing deflections
(micrometres) whatever the crank angle, so one absolute tolerance fits them, and an
error in the crank angle is a phase error, not a spurious spring force.
"""

from __future__ import annotations

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

#: Bearing law codes (``par[P_BEARINGS + i * N_BEARING_PAR + BP_LAW]``).
LAW_LINEAR = 0
LAW_SHORT_JOURNAL = 1  # Ocvirk short bearing, Guembel cavitation (journal.py)
LAW_FINITE_JOURNAL = 2  # finite-length impedance table (journal_finite.py)
LAW_SKIRT_FILM = 3  # piston_top + piston_skirt as one lubricated skirt (skirt.py)
LAW_CODES: dict[str, int] = {
    "linear": LAW_LINEAR,
    "short_journal": LAW_SHORT_JOURNAL,
    "finite_journal": LAW_FINITE_JOURNAL,
    "skirt_film": LAW_SKIRT_FILM,
}
#: Laws each bearing accepts (the pin stays linear: its journal does not turn against
#: its bushing by more than the rod's swing, so it runs squeeze-only at eps near 1).
JOURNAL_LAWS = ("linear", "short_journal", "finite_journal")
BEARING_LAWS: dict[str, tuple[str, ...]] = {
    "primary": JOURNAL_LAWS,
    "secondary": JOURNAL_LAWS,
    "eccentric": JOURNAL_LAWS,
    "pin": ("linear",),
    "piston_top": ("linear", "skirt_film"),
    "piston_skirt": ("linear", "skirt_film"),
}

#: Bearing axis codes: the law acts in the plane normal to this axis.
AXIS_X = 0
AXIS_Y = 1
AXIS_Z = 2

#: Per-bearing parameter row (offset ``P_BEARINGS + i * N_BEARING_PAR``).
BP_LAW = 0  # law code
BP_AXIS = 1  # axis code; the force is normal to it
BP_STIFFNESS = 2  # [N/m]
BP_DAMPING = 3  # [N s/m]
BP_CLEARANCE = 4  # radial clearance [m] (hydrodynamic laws; 0 for linear)
BP_DIAMETER = 5  # journal diameter [m] (hydrodynamic laws)
BP_LENGTH = 6  # bearing length [m] (hydrodynamic laws)
BP_VISCOSITY = 7  # oil dynamic viscosity at the film temperature [Pa s] (hydrodynamic laws)
BP_CONTACT_FILM = 8  # film thickness below which asperity contact starts [m]
BP_CONTACT_STIFFNESS = 9  # contact penalty stiffness (law of the kernel) [N/m^1.5]
BP_CONTACT_FRICTION = 10  # Coulomb friction coefficient of the contact [-]
BP_TABLE = 11  # offset of the finite_journal table in the bearing-table array (-1: none)
N_BEARING_PAR = 12

# ----------------------------------------------------------------------- parameters
P_CRANK_RADIUS = 0  # r [m]
P_ROD_LENGTH = 1  # L, big-end to small-end centres [m]
P_PISTON_AREA = 2  # crown area pi D^2 / 4 [m^2]
P_SHELL_PRESSURE = 3  # pressure under the piston [Pa]
P_SPEED = 4  # crank speed of the constant_speed drive [rad/s]
P_DRIVE = 5  # drive code (DRIVE_*)
P_ROTOR_MASS = 6  # [kg]
P_ROTOR_POLAR_INERTIA = 7  # about the spin axis [kg m^2]
P_ROTOR_TRANSVERSE_INERTIA = 8  # about a diameter through the centre of mass [kg m^2]
P_ROTOR_COM_Z = 9  # axial position of the rotor centre of mass [m]
P_PRIMARY_Z = 10  # axial position of bearing 1 [m]
P_SECONDARY_Z = 11  # axial position of bearing 2 [m]
P_ROD_MASS = 12  # [kg]
P_ROD_COM_FRACTION = 13  # centre of mass distance from the big end / L [-]
P_ROD_INERTIA = 14  # about Z through the centre of mass [kg m^2]
P_PISTON_MASS = 15  # [kg]
P_PISTON_INERTIA = 16  # about Z (pin axis) through the centre of mass [kg m^2]
P_PISTON_PIN_U = 17  # pin centre along the piston axis from the CoM, + towards crown [m]
P_PISTON_CROWN_U = 18  # crown centre, same convention [m]
P_PISTON_TOP_U = 19  # piston_top bearing marker, same convention [m]
P_PISTON_SKIRT_U = 20  # piston_skirt bearing marker, same convention [m]
P_PIN_FROM_CROWN = 21  # pin distance below the crown [m]
P_MOTOR_SYNC_SPEED = 22  # induction motor: synchronous speed [rad/s]
P_MOTOR_BREAKDOWN_TORQUE = 23  # induction motor: forward-field peak torque [N m]
P_MOTOR_BREAKDOWN_SLIP = 24  # induction motor: slip at the peak [-]
P_MOTOR_BACKWARD_RATIO = 25  # induction motor: backward/forward field ratio [-]
P_COUNTERWEIGHT_MASS = 26  # rotor counterweight (point mass on the rotor) [kg]
P_COUNTERWEIGHT_RADIUS = 27  # its distance from the spin axis [m]
P_COUNTERWEIGHT_ANGLE = 28  # its angle ahead of the crank pin about +Z [rad]
P_COUNTERWEIGHT_Z = 29  # its axial position (eccentric plane z = 0) [m]
P_DETAILED_OUTPUTS = 30  # 1: also compute the post-processing outputs (peak film pressures)
P_BEARINGS = 31  # first bearing row
N_PAR = P_BEARINGS + N_BEARINGS * N_BEARING_PAR

#: Drive codes (``par[P_DRIVE]``).
DRIVE_CONSTANT_SPEED = 0
DRIVE_TORQUE_PROFILE = 1
DRIVE_INDUCTION_MOTOR = 2
DRIVE_CODES: dict[str, int] = {
    "constant_speed": DRIVE_CONSTANT_SPEED,
    "torque_profile": DRIVE_TORQUE_PROFILE,
    "induction_motor": DRIVE_INDUCTION_MOTOR,
}

# ---------------------------------------------------------------------------- state
Y_ROTOR_X = 0
Y_ROTOR_Y = 1
Y_ROTOR_TILT_X = 2
Y_ROTOR_TILT_Y = 3
Y_CRANK_ANGLE = 4
Y_ROD_DX = 5
Y_ROD_DY = 6
Y_ROD_DANGLE = 7
Y_PISTON_DX = 8
Y_PISTON_Y = 9
Y_PISTON_TILT = 10
N_COORD = 11
Y_ROTOR_VX = N_COORD + Y_ROTOR_X
Y_ROTOR_VY = N_COORD + Y_ROTOR_Y
Y_ROTOR_TILT_X_RATE = N_COORD + Y_ROTOR_TILT_X
Y_ROTOR_TILT_Y_RATE = N_COORD + Y_ROTOR_TILT_Y
Y_CRANK_SPEED = N_COORD + Y_CRANK_ANGLE
Y_ROD_DVX = N_COORD + Y_ROD_DX
Y_ROD_DVY = N_COORD + Y_ROD_DY
Y_ROD_DANGLE_RATE = N_COORD + Y_ROD_DANGLE
Y_PISTON_DVX = N_COORD + Y_PISTON_DX
Y_PISTON_VY = N_COORD + Y_PISTON_Y
Y_PISTON_TILT_RATE = N_COORD + Y_PISTON_TILT
N_STATE = 2 * N_COORD

STATE_NAMES: tuple[str, ...] = (
    "rotor_x [m]",
    "rotor_y [m]",
    "rotor_tilt_x [rad]",
    "rotor_tilt_y [rad]",
    "crank_angle [rad]",
    "rod_dx [m]",
    "rod_dy [m]",
    "rod_dangle [rad]",
    "piston_dx [m]",
    "piston_y [m]",
    "piston_tilt [rad]",
    "rotor_vx [m/s]",
    "rotor_vy [m/s]",
    "rotor_tilt_x_rate [rad/s]",
    "rotor_tilt_y_rate [rad/s]",
    "crank_speed [rad/s]",
    "rod_dvx [m/s]",
    "rod_dvy [m/s]",
    "rod_dangle_rate [rad/s]",
    "piston_dvx [m/s]",
    "piston_vy [m/s]",
    "piston_tilt_rate [rad/s]",
)

# ---------------------------------------------------------------------------- outputs
#: Force on the journal-side body (rotor for 1, 2, 3; piston for 4, 5, 6) from the
#: other body, inertial X, Y, Z: ``aux[A_BEARING_FORCE + 3 * i + k]`` [N].
A_BEARING_FORCE = 0
#: Relative displacement journal marker minus bushing marker, inertial X, Y, Z, only
#: the components normal to the bearing axis (others 0): ``A_BEARING_DISPLACEMENT +
#: 3 * i + k`` [m]. Rotor, eccentric and pin bearings: (x, y, 0); piston: (0, y, 0).
A_BEARING_DISPLACEMENT = 3 * N_BEARINGS
A_DRIVE_TORQUE = 6 * N_BEARINGS  # driving torque about the rotor axis [N m]
A_GAS_FORCE = A_DRIVE_TORQUE + 1  # -(p - p_shell) A_p, along the piston axis [N]
A_KINETIC_ENERGY_ROTOR = A_DRIVE_TORQUE + 2  # [J]
A_KINETIC_ENERGY_ROD = A_DRIVE_TORQUE + 3  # [J]
A_KINETIC_ENERGY_PISTON = A_DRIVE_TORQUE + 4  # [J]
A_SPRING_ENERGY = A_DRIVE_TORQUE + 5  # elastic energy of the linear bearings [J]
A_BEARING_POWER = A_DRIVE_TORQUE + 6  # power absorbed by all bearings, -sum F.de/dt [W]
A_DRIVE_POWER = A_DRIVE_TORQUE + 7  # torque x spin rate about the rotor axis [W]
A_GAS_POWER = A_DRIVE_TORQUE + 8  # power of the gas force on the piston [W]
A_PISTON_DISPLACEMENT = A_DRIVE_TORQUE + 9  # crown axial displacement from rigid TDC [m]
A_PISTON_SPEED = A_DRIVE_TORQUE + 10  # its time derivative (dV/dt = A_p * this) [m/s]
A_PISTON_LATERAL = A_DRIVE_TORQUE + 11  # piston centre of mass, Y [m]
A_PISTON_TILT = A_DRIVE_TORQUE + 12  # piston tilt about Z [rad]
A_CRANK_ANGLE = A_DRIVE_TORQUE + 13  # [rad]
A_CRANK_SPEED = A_DRIVE_TORQUE + 14  # [rad/s]
#: Per bearing i: friction torque about the bearing axis on the journal-side body at
#: ``A_BEARING_TORQUE + 2 i`` and on the bushing-side body at ``+ 2 i + 1`` [N m]
#: (zero for the linear law and the piston film).
A_BEARING_TORQUE = A_DRIVE_TORQUE + 15
#: Per bearing i: power dissipated in its film and contact, ``-(F.de/dt + T_j w_j +
#: T_b w_b)`` [W] (the linear law: its damper's power).
A_BEARING_DISSIPATION = A_BEARING_TORQUE + 2 * N_BEARINGS
#: Per bearing i: asperity contact normal force [N] (0 while the film carries the load).
A_BEARING_CONTACT = A_BEARING_DISSIPATION + N_BEARINGS
A_PISTON_FRICTION = A_BEARING_CONTACT + N_BEARINGS  # axial film force on the piston [N]
A_PISTON_FRICTION_POWER = A_PISTON_FRICTION + 1  # power it dissipates [W]
#: Per bearing i: largest film pressure [Pa], only when ``par[P_DETAILED_OUTPUTS]`` is
#: set (post-processing), else 0. The skirt film reports at ``piston_skirt``.
A_BEARING_PEAK_PRESSURE = A_PISTON_FRICTION_POWER + 1
N_AUX = A_BEARING_PEAK_PRESSURE + N_BEARINGS
