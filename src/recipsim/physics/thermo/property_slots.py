"""Layout of the property buffer shared by the HEOS callback and the property table:
the slot of each property a state evaluation fills (table :data:`PROPS`, declared once
with unit and meaning, :class:`~recipsim.physics.layout_table.Layout`), and the status
it returns.
"""

from recipsim.physics.layout_table import Layout

PROPS = Layout("property buffer")
_p = PROPS.add
PROP_PRESSURE = _p("pressure", "Pa", "pressure")
PROP_ENTHALPY = _p("enthalpy", "J/kg", "specific enthalpy")
PROP_CV = _p("cv", "J/(kg K)", "isochoric specific heat (mixture value in the dome)")
PROP_DPDT = _p("dpdt", "Pa/K", "(dp/dT)_rho (dp_sat/dT in the dome)")
PROP_KAPPA = _p("kappa", "-", "isentropic exponent rho c^2 / p (1 in the dome, see docs)")
PROP_K0 = _p("k0", "-", "ideal-gas c_p0 / c_v0")
PROP_VISCOSITY = _p("viscosity", "Pa s", "dynamic viscosity (only with transport)")
PROP_CONDUCTIVITY = _p("conductivity", "W/(m K)", "thermal conductivity (only with transport)")
PROP_CP = _p("cp", "J/(kg K)", "isobaric specific heat (only with transport)")
PROP_QUALITY = _p("quality", "-", "vapour quality, -1 for single phase")
PROP_DPDRHO = _p("dpdrho", "Pa m3/kg", "(dp/drho)_T")
PROP_RESERVED = _p("reserved", "-", "spare slot: no property is stored there")
N_PROPS = PROPS.size

STATUS_OK = 0
STATUS_DOMAIN = 1
#: the answer to :data:`SIGNAL_CHECK` when a Ctrl-C arrived during the solve
STATUS_INTERRUPTED = 2
#: a temperature [K] that asks the property callback only whether the user interrupted
#: (the callback runs Python, where a pending Ctrl-C is handled); no state is evaluated
SIGNAL_CHECK = 0.0

__all__ = [
    "PROPS",
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
    "PROP_RESERVED",
    "N_PROPS",
    "STATUS_OK",
    "STATUS_DOMAIN",
    "STATUS_INTERRUPTED",
    "SIGNAL_CHECK",
]
