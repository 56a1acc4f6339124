"""Layout of the property buffer shared by the HEOS callback and the property table:
the slot of each property a state evaluation fills, and the status it returns.
"""

PROP_PRESSURE = 0  # p [Pa]
PROP_ENTHALPY = 1  # h [J/kg]
PROP_CV = 2  # c_v [J/(kg K)] (mixture value in the dome)
PROP_DPDT = 3  # (dp/dT)_rho [Pa/K] (dp_sat/dT in the dome)
PROP_KAPPA = 4  # isentropic exponent rho c^2 / p [-] (1 in the dome, see docs)
PROP_K0 = 5  # ideal-gas c_p0/c_v0 [-]
PROP_VISCOSITY = 6  # [Pa s] (only with transport)
PROP_CONDUCTIVITY = 7  # [W/(m K)] (only with transport)
PROP_CP = 8  # [J/(kg K)] (only with transport)
PROP_QUALITY = 9  # vapour quality, -1 for single phase
PROP_DPDRHO = 10  # (dp/drho)_T [Pa m3/kg]
N_PROPS = 12

STATUS_OK = 0
STATUS_DOMAIN = 1

__all__ = [
    "PROP_PRESSURE",
    "PROP_ENTHALPY",
    "PROP_CV",
    "PROP_DPDT",
    "PROP_KAPPA",
    "PROP_K0",
    "PROP_VISCOSITY",
    "PROP_CONDUCTIVITY",
    "PROP_CP",
    "PROP_QUALITY",
    "PROP_DPDRHO",
    "N_PROPS",
    "STATUS_OK",
    "STATUS_DOMAIN",
]
