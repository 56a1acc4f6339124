"""What recipsim needs to know about CoolProp: its version and a fluid's constants.

The CoolProp version (part of every cache key) comes from the package metadata, without
importing CoolProp. A fluid's constants (temperature and pressure limits of the equation
of state, critical point, gas constant) come from CoolProp's HEOS backend
(:func:`coolprop_fluid_constants`); each cached property table stores them with its
data, and :func:`recipsim.physics.thermo.property_table_cache.fluid_constants` reads them
from there when a table of the fluid is cached.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from functools import lru_cache
from importlib import metadata

from recipsim.progress import timed_step


@lru_cache(maxsize=1)
def coolprop_version() -> str:
    """Version of the installed CoolProp package (from its metadata, no import)."""
    try:
        return metadata.version("CoolProp")
    except metadata.PackageNotFoundError:  # e.g. a source build without metadata
        import CoolProp

        return str(CoolProp.__version__)


@dataclass(frozen=True)
class FluidConstants:
    """Constants of one CoolProp fluid (HEOS backend), SI units.

    Attributes
    ----------
    coolprop_name : str
        CoolProp fluid name.
    t_min, t_max : float
        Temperature range of the equation of state [K].
    p_max : float
        Highest pressure of the equation of state [Pa].
    t_crit, p_crit, rho_crit : float
        Critical temperature [K], pressure [Pa] and density [kg/m3].
    molar_mass : float
        [kg/mol]
    gas_constant : float
        Specific gas constant R/M [J/(kg K)].
    """

    coolprop_name: str
    t_min: float
    t_max: float
    p_max: float
    t_crit: float
    p_crit: float
    rho_crit: float
    molar_mass: float
    gas_constant: float


def coolprop_fluid_constants(coolprop_name: str) -> FluidConstants:
    """The constants of a fluid from CoolProp's HEOS backend (imports CoolProp).

    Raises
    ------
    ValueError
        If CoolProp does not know the fluid.
    """
    if "CoolProp.CoolProp" not in sys.modules:  # its first import takes seconds
        with timed_step("import CoolProp", "loading CoolProp", "its equation of state"):
            import CoolProp.CoolProp
    import CoolProp.CoolProp as CP

    state = CP.AbstractState("HEOS", coolprop_name)  # ValueError for an unknown fluid
    molar_mass = state.molar_mass()
    return FluidConstants(
        coolprop_name=coolprop_name,
        t_min=state.Tmin(),
        t_max=state.Tmax(),
        p_max=state.pmax(),
        t_crit=state.T_critical(),
        p_crit=state.p_critical(),
        rho_crit=state.rhomass_critical(),
        molar_mass=molar_mass,
        gas_constant=state.gas_constant() / molar_mass,
    )
