"""What recipsim needs to know about CoolProp without importing it.

``import CoolProp`` loads the whole fluid library (about 2 s). A run with
``properties = "table"`` gets its states from a cached table, so it should not pay
that: the CoolProp version (part of every cache key) comes from the package metadata,
and a fluid's constants (temperature and pressure limits, critical point, gas
constant) from a small cache filled by CoolProp the first time a fluid is used.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from functools import cache, lru_cache
from importlib import metadata
from pathlib import Path

from recipsim.cache_dirs import cache_dir
from recipsim.physics.json_cache import read_record, write_record


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
    atomically the first time a fluid is asked for; an unreadable, malformed or tampered
    one (another fluid, missing or extra keys, values that are not finite numbers) is
    recomputed and replaced.

    Raises
    ------
    ValueError
        If CoolProp does not know the fluid.
    """
    safe = "".join(c if c.isalnum() else "_" for c in coolprop_name)
    path = cache_dir() / "fluid_constants" / coolprop_version() / f"{safe}.json"
    cached = _read_constants(path, coolprop_name)
    if cached is not None:
        return cached
    constants = _from_coolprop(coolprop_name)
    write_record(path, asdict(constants))
    return constants


def _read_constants(path: Path, coolprop_name: str) -> FluidConstants | None:
    """The cached constants, or None if the file is missing, malformed or not this fluid's."""
    data = read_record(path, FluidConstants.__dataclass_fields__, ("coolprop_name",))
    if data is None or data["coolprop_name"] != coolprop_name:
        return None
    return FluidConstants(**data)
