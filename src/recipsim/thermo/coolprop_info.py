"""What recipsim needs to know about CoolProp without importing it.

``import CoolProp`` loads the whole fluid library (about 2 s). A run with
``properties = "table"`` gets its states from a cached table, so it should not pay
that: the CoolProp version (part of every cache key) comes from the package metadata,
and a fluid's constants (temperature and pressure limits, critical point, gas
constant) from a small cache filled by CoolProp the first time a fluid is used.
"""

from __future__ import annotations

import json
import os
from dataclasses import asdict, dataclass
from functools import cache, lru_cache
from importlib import metadata
from pathlib import Path

from ..atomic import atomic_write


@lru_cache(maxsize=1)
def coolprop_version() -> str:
    """Version of the installed CoolProp package (from its metadata, no import)."""
    try:
        return metadata.version("CoolProp")
    except metadata.PackageNotFoundError:  # e.g. a source build without metadata
        import CoolProp

        return str(CoolProp.__version__)


def cache_dir() -> Path:
    """recipsim's cache directory: ``$RECIPSIM_CACHE`` or ``~/.cache/recipsim``."""
    env = os.environ.get("RECIPSIM_CACHE")
    return Path(env) if env else Path.home() / ".cache" / "recipsim"


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


def _from_coolprop(coolprop_name: str) -> FluidConstants:
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


@cache
def fluid_constants(coolprop_name: str) -> FluidConstants:
    """The constants of a CoolProp fluid, from the cache or from CoolProp.

    The cache file (``fluid_constants/<CoolProp version>/<name>.json``) is written
    atomically the first time a fluid is asked for; an unreadable one is recomputed.

    Raises
    ------
    ValueError
        If CoolProp does not know the fluid.
    """
    safe = "".join(c if c.isalnum() else "_" for c in coolprop_name)
    path = cache_dir() / "fluid_constants" / coolprop_version() / f"{safe}.json"
    try:
        data = json.loads(path.read_text())
        if data.get("coolprop_name") == coolprop_name:
            return FluidConstants(**data)
    except (OSError, ValueError, TypeError):
        pass
    constants = _from_coolprop(coolprop_name)
    text = json.dumps(asdict(constants), indent=1)

    def write(tmp: Path) -> None:
        tmp.write_text(text)

    atomic_write(path, write)
    return constants
