"""Layout of the cylinder on a rigid crank at constant speed: states, modes, events,
integer and float parameters and outputs, as index constants.

States (time is the independent variable, ``theta = theta0 + omega t``):
gas temperature T [K] and density rho [kg/m3] (CoolProp's equations of state are
explicit in them), suction and discharge reed lift [m] and velocity [m/s], then
quadratures (cumulative mass, enthalpy, heat and work over the revolution) that the
summary and the closure checks read. Only the first ``N_ERR`` states are under
error control.

Modes (``mode[0]`` suction, ``mode[1]`` discharge): ideal 0 closed / 1 open; reed
0 seated / 1 free / 2 at the stop.

The compiled right-hand side is :mod:`recipsim.physics.thermo.cylinder_rhs`, the valve
events and impacts :mod:`recipsim.physics.thermo.cylinder_events`.
"""

from __future__ import annotations

# ---- states -----------------------------------------------------------------------
Y_T = 0
Y_RHO = 1
Y_XS = 2
Y_VS = 3
Y_XD = 4
Y_VD = 5
N_ERR = 6
Q_MSUC_IN = 6  # mass in through the suction valve [kg]
Q_MSUC_OUT = 7  # back-flow out through the suction valve [kg]
Q_MDIS_OUT = 8
Q_MDIS_IN = 9
Q_MLEAK_OUT = 10
Q_MLEAK_IN = 11
Q_HSUC_IN = 12  # enthalpy carried [J]
Q_HSUC_OUT = 13
Q_HDIS_OUT = 14
Q_HDIS_IN = 15
Q_HLEAK_OUT = 16
Q_HLEAK_IN = 17
Q_HEAT = 18  # heat into the gas [J]
Q_WORK = 19  # work on the gas, -int p dV [J]
Q_SHAFT = 20  # shaft work, int tau omega dt [J]
N_STATE = 21
N_MODES = 2
N_EVENTS = 4

# ---- integer parameters --------------------------------------------------------------
I_SCENE = 0
I_VALVES = 1
I_FLOW = 2
I_HT = 3
I_LEAK = 4
I_PROPS = 5  # property backend: PROPS_HEOS (the ``props`` callback) or PROPS_TABLE
N_IPAR = 6
PROPS_HEOS = 0
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
C_OMEGA = 0
C_THETA0 = 1
C_R = 2
C_L = 3
C_AP = 4
C_VC = 5
C_BORE = 6
C_STROKE = 7
C_PISTON_LEN = 8
C_LINER_LEN = 9
C_PS = 10
C_RHOS = 11
C_HS = 12
C_KAPPAS = 13
C_K0S = 14
C_TS = 15
C_PD = 16
C_RHOD = 17
C_HD = 18
C_KAPPAD = 19
C_K0D = 20
C_TD = 21
C_PSHELL = 22
C_RHOSHELL = 23
C_HSHELL = 24
C_MUSHELL = 25
C_RGAS = 26
C_DPLAM = 27
C_VSTICK = 28
C_LEAK_DELTA = 29
C_LEAK_ECC = 30
C_HT_COEF = 31
C_TWALL = 32
C_MPISTON = 33
C_MROD = 34
C_AROD = 35
C_IROD = 36
C_BAUMGARTE = 37
C_VALVE0 = 40  # first valve block; valve i starts at C_VALVE0 + i * VALVE_BLOCK
VALVE_BLOCK = 11
V_PORT_D = 0
V_CFLOW = 1
V_AFORCE = 2
V_MASS = 3
V_STIFF = 4
V_DAMP = 5
V_STOP = 6
V_REST = 7
V_PRELOAD = 8
V_CURTAIN_D = 9  # diameter of the curtain flow area [m]
V_MOMENTUM = 10  # 1.0: the jet's momentum pushes on the reed
N_PAR = C_VALVE0 + 2 * VALVE_BLOCK

# ---- auxiliary outputs --------------------------------------------------------------
A_THETA = 0
A_VOLUME = 1
A_DVDT = 2
A_PRESSURE = 3
A_TEMPERATURE = 4
A_DENSITY = 5
A_MASS = 6
A_ENTHALPY = 7
A_QUALITY = 8
A_MDOT_SUC = 9  # into the cylinder through the suction valve [kg/s]
A_MDOT_DIS = 10  # out of the cylinder through the discharge valve [kg/s]
A_MDOT_LEAK = 11  # out of the cylinder through the piston gap [kg/s]
A_QDOT = 12  # heat into the gas [W]
A_HTC = 13
A_LIFT_S = 14
A_LIFT_D = 15
A_VEL_S = 16
A_VEL_D = 17
A_FORCE_GAS = 18  # (p - p_shell) A_p on the piston, towards the crank [N]
A_TORQUE_GAS = 19  # (p - p_shell) A_p dx/dtheta [N m]
A_TORQUE_INERTIA = 20
A_TORQUE_SHAFT = 21  # driving torque for constant speed [N m]
A_DISPLACEMENT = 22  # piston displacement from TDC [m]
A_PISTON_VELOCITY = 23  # dx/dt [m/s]
A_FORCE_REED_S = 24  # net opening force on the suction reed (spring excluded) [N]
A_FORCE_REED_D = 25
A_STATUS = 26
A_LEAK_ECC = 27  # eccentricity ratio of the piston in the bore seen by the leak [-]
N_AUX = 28
