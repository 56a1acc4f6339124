"""Layout of the cylinder on a rigid crank at constant speed: states, integer and float
parameters and outputs, each declared once in a table
(:class:`~recipsim.physics.layout_table.Layout`: name, unit, meaning) that hands out the
index constants the compiled code reads.

States (time is the independent variable, ``theta = theta0 + omega t``):
gas temperature T [K] and density rho [kg/m3] (CoolProp's equations of state are
explicit in them), suction and discharge reed lift [m] and velocity [m/s], then
quadratures (cumulative mass, enthalpy, heat and work over the revolution) that the
summary and the closure checks read. Only the first ``N_ERR`` states are under
error control.

Modes (``mode[0]`` suction, ``mode[1]`` discharge): ideal 0 closed / 1 open; reed
0 seated / 1 free / 2 at the stop.

Tables: :data:`STATES`, :data:`IPAR` (integer parameters), :data:`PAR` (float
parameters; :data:`VALVE` is one valve's row of it), :data:`OUTPUTS` (the auxiliary
outputs; their names and units are the report's cycle columns where it writes them).
Option codes (``VALVES_REED``, ``LEAK_ISOTHERMAL``, ...) are plain constants.

The compiled right-hand side is :mod:`recipsim.physics.thermo.cylinder_rhs`, the valve
events and impacts :mod:`recipsim.physics.thermo.cylinder_events`.
"""

from __future__ import annotations

from recipsim.physics.layout_table import Layout

# ---- states -----------------------------------------------------------------------
STATES = Layout("cylinder states")
_s = STATES.add
Y_T = _s("gas_temperature", "K", "gas temperature in the cylinder")
Y_RHO = _s("gas_density", "kg/m3", "gas density in the cylinder")
Y_XS = _s("suction_valve_lift", "m", "suction reed lift")
Y_VS = _s("suction_valve_velocity", "m/s", "suction reed velocity")
Y_XD = _s("discharge_valve_lift", "m", "discharge reed lift")
Y_VD = _s("discharge_valve_velocity", "m/s", "discharge reed velocity")
#: States under error control: those above; the quadratures below are not.
N_ERR = STATES.size
Q_MSUC_IN = _s("suction_mass_in", "kg", "mass in through the suction valve")
Q_MSUC_OUT = _s("suction_mass_out", "kg", "back-flow out through the suction valve")
Q_MDIS_OUT = _s("discharge_mass_out", "kg", "mass out through the discharge valve")
Q_MDIS_IN = _s("discharge_mass_in", "kg", "back-flow in through the discharge valve")
Q_MLEAK_OUT = _s("leakage_mass_out", "kg", "mass out through the piston gap")
Q_MLEAK_IN = _s("leakage_mass_in", "kg", "mass in from the shell through the piston gap")
Q_HSUC_IN = _s("suction_enthalpy_in", "J", "enthalpy carried in through the suction valve")
Q_HSUC_OUT = _s("suction_enthalpy_out", "J", "enthalpy carried out through the suction valve")
Q_HDIS_OUT = _s("discharge_enthalpy_out", "J", "enthalpy carried out through the discharge valve")
Q_HDIS_IN = _s("discharge_enthalpy_in", "J", "enthalpy carried in through the discharge valve")
Q_HLEAK_OUT = _s("leakage_enthalpy_out", "J", "enthalpy carried out through the piston gap")
Q_HLEAK_IN = _s("leakage_enthalpy_in", "J", "enthalpy carried in through the piston gap")
Q_HEAT = _s("heat_to_gas", "J", "heat into the gas")
Q_WORK = _s("work_on_gas", "J", "work on the gas, -int p dV")
Q_SHAFT = _s("shaft_work", "J", "shaft work, int tau omega dt (0 on the rigid crank)")
N_STATE = STATES.size
N_MODES = 2
N_EVENTS = 4

# ---- integer parameters --------------------------------------------------------------
IPAR = Layout("cylinder integer parameters")
I_SCENE = IPAR.add("scene", "code", "scene code (recipsim.model.scenes.SCENE_*)")
I_VALVES = IPAR.add("valves", "code", "valve model (VALVES_*)")
I_FLOW = IPAR.add("flow", "code", "valve flow model (FLOW_*)")
I_HT = IPAR.add("heat_transfer", "code", "heat-transfer correlation (heat_transfer.HT_*)")
I_LEAK = IPAR.add("leakage", "code", "piston-gap leakage model (LEAK_*)")
I_PROPS = IPAR.add("properties", "code", "property backend (PROPS_*)")
N_IPAR = IPAR.size
PROPS_HEOS = 0  # the ``props`` callback
PROPS_TABLE = 1  # table in pbuf after the outputs (property_table); HEOS where it has no data
VALVES_IDEAL = 0
VALVES_QUASI_STATIC = 1
VALVES_REED = 2
FLOW_REAL_GAS = 0
FLOW_IDEAL_GAS = 1
LEAK_NONE = 0
LEAK_INCOMPRESSIBLE = 1
LEAK_ISOTHERMAL = 2

# ---- float parameters ----------------------------------------------------------------
#: One valve's row of parameters (offsets within the row).
VALVE = Layout("valve parameters")
V_PORT_D = VALVE.add("port_diameter", "m", "port diameter")
V_CFLOW = VALVE.add("flow_coefficient", "-", "flow (discharge) coefficient of the port")
V_AFORCE = VALVE.add("force_area", "m2", "force coefficient times port area")
V_MASS = VALVE.add("mass", "kg", "effective reed mass")
V_STIFF = VALVE.add("stiffness", "N/m", "reed stiffness")
V_DAMP = VALVE.add("damping", "N s/m", "reed damping coefficient")
V_STOP = VALVE.add("stop_height", "m", "lift at the stop")
V_REST = VALVE.add("restitution", "-", "coefficient of restitution at seat and stop")
V_PRELOAD = VALVE.add("preload", "N", "preload holding the reed on its seat")
V_CURTAIN_D = VALVE.add("curtain_diameter", "m", "diameter of the curtain flow area")
V_MOMENTUM = VALVE.add("momentum_force", "-", "1.0: the jet's momentum pushes on the reed")
VALVE_BLOCK = VALVE.size

PAR = Layout("cylinder float parameters")
_p = PAR.add
C_OMEGA = _p("shaft_speed", "rad/s", "crank speed")
C_THETA0 = _p("start_angle", "rad", "crank angle at t = 0 of a revolution")
C_R = _p("crank_radius", "m", "crank radius")
C_L = _p("rod_length", "m", "connecting-rod length")
C_AP = _p("piston_area", "m2", "piston crown area")
C_VC = _p("clearance_volume", "m3", "cylinder volume at top dead centre")
C_BORE = _p("bore", "m", "cylinder bore")
C_STROKE = _p("stroke", "m", "piston stroke")
C_PISTON_LEN = _p("piston_length", "m", "piston length")
C_LINER_LEN = _p("liner_length", "m", "cylinder liner length")
C_PS = _p("suction_pressure", "Pa", "suction plenum pressure")
C_RHOS = _p("suction_density", "kg/m3", "suction plenum density")
C_HS = _p("suction_enthalpy", "J/kg", "suction plenum specific enthalpy")
C_KAPPAS = _p("suction_kappa", "-", "suction plenum isentropic exponent")
C_K0S = _p("suction_k0", "-", "suction plenum ideal-gas isentropic exponent")
C_TS = _p("suction_temperature", "K", "suction plenum temperature")
C_PD = _p("discharge_pressure", "Pa", "discharge plenum pressure")
C_RHOD = _p("discharge_density", "kg/m3", "discharge plenum density")
C_HD = _p("discharge_enthalpy", "J/kg", "discharge plenum specific enthalpy")
C_KAPPAD = _p("discharge_kappa", "-", "discharge plenum isentropic exponent")
C_K0D = _p("discharge_k0", "-", "discharge plenum ideal-gas isentropic exponent")
C_TD = _p("discharge_temperature", "K", "discharge plenum temperature")
C_PSHELL = _p("shell_pressure", "Pa", "shell pressure (under the piston)")
C_RHOSHELL = _p("shell_density", "kg/m3", "shell gas density")
C_HSHELL = _p("shell_enthalpy", "J/kg", "shell gas specific enthalpy")
C_MUSHELL = _p("shell_viscosity", "Pa s", "shell gas dynamic viscosity")
C_RGAS = _p("gas_constant", "J/(kg K)", "specific gas constant (ideal-gas flow)")
C_DPLAM = _p("laminar_pressure_difference", "Pa", "valve flow turns laminar below it")
C_VSTICK = _p("stick_velocity", "m/s", "a slower reed impact against a closing force sticks")
C_LEAK_DELTA = _p("leakage_clearance", "m", "radial piston-cylinder clearance of the leak")
C_LEAK_ECC = _p("leakage_eccentricity", "-", "eccentricity ratio of the piston in the bore")
C_HT_COEF = _p("heat_transfer_coefficient", "-", "coefficient of the heat-transfer correlation")
C_TWALL = _p("wall_temperature", "K", "cylinder wall temperature")
C_MPISTON = _p("piston_mass", "kg", "piston mass")
C_MROD = _p("rod_mass", "kg", "connecting-rod mass")
C_AROD = _p("rod_com_fraction", "-", "rod centre of mass from the big end / rod length")
C_IROD = _p("rod_inertia", "kg m2", "rod moment of inertia about its centre of mass")
C_BAUMGARTE = _p("baumgarte_rate", "1/s", "decay rate of the ideal valves' pressure drift")
#: First valve row; valve i (0 suction, 1 discharge) starts at C_VALVE0 + i * VALVE_BLOCK.
C_VALVE0 = PAR.add_rows(VALVE, ("suction_valve", "discharge_valve"))
N_PAR = PAR.size

# ---- auxiliary outputs --------------------------------------------------------------
OUTPUTS = Layout("cylinder outputs")
_a = OUTPUTS.add
A_THETA = _a("crank_angle", "rad", "crank angle (not wrapped)")
A_VOLUME = _a("cylinder_volume", "m3", "clearance volume + piston area x displacement")
A_DVDT = _a("volume_rate", "m3/s", "dV/dt")
A_PRESSURE = _a("cylinder_pressure", "Pa", "gas pressure in the cylinder")
A_TEMPERATURE = _a("gas_temperature", "K", "gas temperature in the cylinder")
A_DENSITY = _a("gas_density", "kg/m3", "gas density in the cylinder")
A_MASS = _a("gas_mass", "kg", "gas mass in the cylinder")
A_ENTHALPY = _a("gas_specific_enthalpy", "J/kg", "specific enthalpy of the cylinder gas")
A_QUALITY = _a(
    "vapour_quality",
    "-",
    "vapour mass fraction inside the two-phase dome; -1 for a single-phase state (or no gas state)",
)
A_MDOT_SUC = _a(
    "suction_mass_flow",
    "kg/s",
    "flow into the cylinder through the suction valve (negative: back-flow)",
)
A_MDOT_DIS = _a(
    "discharge_mass_flow",
    "kg/s",
    "flow out of the cylinder through the discharge valve (negative: back-flow)",
)
A_MDOT_LEAK = _a(
    "leakage_mass_flow",
    "kg/s",
    "flow out of the cylinder through the piston-cylinder gap (negative: into it)",
)
A_QDOT = _a("heat_flow_to_gas", "W", "heat from the wall into the gas")
A_HTC = _a(
    "heat_transfer_coefficient",
    "W/(m2 K)",
    "convective gas-wall coefficient of the heat-transfer correlation (0 when adiabatic)",
)
A_LIFT_S = _a(
    "suction_valve_lift", "m", "suction reed lift at the port (0 for `ideal` and `quasi_static`)"
)
A_LIFT_D = _a("discharge_valve_lift", "m", "discharge reed lift at the port")
A_VEL_S = _a("suction_valve_velocity", "m/s", "suction reed velocity, positive opening")
A_VEL_D = _a("discharge_valve_velocity", "m/s", "discharge reed velocity, positive opening")
A_FORCE_GAS = _a(
    "gas_force",
    "N",
    "(cylinder - shell pressure) x piston area, pushing the piston towards the crank",
)
A_TORQUE_GAS = _a(
    "gas_torque",
    "N m",
    "torque of the gas force on the crankshaft, positive along the rotation (negative while "
    'compressing; "Torques" in reports/README.md): (p - p_shell) A dx/dtheta on the pinned '
    "crank, gas power on the piston / crank speed on the flexible one",
)
A_TORQUE_INERTIA = _a(
    "inertia_torque",
    "N m",
    "driving torque + gas torque: what accelerates the bodies (and loads the flexible bearings)",
)
A_TORQUE_SHAFT = _a(
    "shaft_torque",
    "N m",
    "driving torque on the crankshaft, positive along the rotation: inertia torque - gas torque",
)
A_DISPLACEMENT = _a("piston_displacement", "m", "piston distance from top dead centre")
A_PISTON_VELOCITY = _a(
    "piston_velocity", "m/s", "rate of the displacement (positive towards bottom dead centre)"
)
A_FORCE_REED_S = _a(
    "suction_reed_force", "N", "net opening force on the suction reed (spring excluded)"
)
A_FORCE_REED_D = _a(
    "discharge_reed_force", "N", "net opening force on the discharge reed (spring excluded)"
)
A_STATUS = _a("property_status", "code", "status of the property call (property_slots.STATUS_*)")
A_LEAK_ECC = _a(
    "leakage_eccentricity",
    "-",
    "eccentricity ratio of the piston in the bore used by the gap leakage, (1 + 1.5 eps^2) in "
    "the flow: the case's `leakage.eccentricity_ratio` on the rigid crank, the land-averaged "
    "offset of the flexible piston (lateral displacement and tilt, series resistance) in the "
    "coupled scene",
)
N_AUX = OUTPUTS.size
