"""Refrigerant files, and the fluid that answers a case's set-up questions.

A refrigerant file (``refrigerants/<name>.toml``, found in :func:`refrigerant_dirs`)
names the CoolProp fluid, optional tighter limits and the rating points of the standards
(ASHRAE LBP, EN 12900, ...).
:class:`~recipsim.physics.thermo.fluid.Fluid` wraps one reused low-level
``AbstractState``; it is used when a case is loaded and when results are post-processed,
never inside the right-hand side, which goes through
:mod:`recipsim.physics.thermo.properties`. With ``properties = "table"``
:func:`case_fluid` answers the same questions from the property table
(:class:`recipsim.physics.thermo.table_states.TableFluid`), and CoolProp is imported only
when the table has no answer.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeAlias

from recipsim.atomic import checked_name
from recipsim.case.envelope_table import read_envelope
from recipsim.case.files import read_toml, shipped_dir
from recipsim.errors import CaseError
from recipsim.physics.thermo.fluid import Fluid
from recipsim.physics.thermo.property_backends import PROPERTY_BACKENDS
from recipsim.physics.thermo.property_table_cache import fluid_constants, load_property_table
from recipsim.physics.thermo.table_states import TableFluid
from recipsim.schema import Field, Spec, Text, check_keys, read_table

if TYPE_CHECKING:
    from recipsim.physics.thermo.table_states import TableFluid

#: The top of a refrigerant file; its tables are ``[limits]`` (:data:`LIMITS_SPEC`),
#: ``[rating_points.<name>]`` (:data:`RATING_POINT_SPEC`) and ``[envelope]``
#: (:data:`recipsim.case.envelope_table.ENVELOPE_SPEC`).
REFRIGERANT_SPEC: Spec = {
    "name": Text(doc="the name case files give as ``refrigerant``"),
    "coolprop_name": Text(doc="CoolProp's name of the fluid"),
    "description": Text("", "one line for people"),
}
REFRIGERANT_TABLES = ("limits", "rating_points", "envelope")

RATING_POINT_SPEC: Spec = {
    "evaporating_temperature": Field("K", lo=100.0, hi=600.0),
    "condensing_temperature": Field("K", None, lo=100.0, hi=600.0),
    "discharge_pressure": Field("Pa", None, lo=0.0, open_lo=True),
    "suction_temperature": Field("K", lo=100.0, hi=600.0),
    "liquid_temperature": Field("K", lo=100.0, hi=600.0),
    "description": Text(""),
}

LIMITS_SPEC: Spec = {
    "min_temperature": Field("K", None, lo=0.0, open_lo=True),
    "max_temperature": Field("K", None, lo=0.0, open_lo=True),
    "max_pressure": Field("Pa", None, lo=0.0, open_lo=True),
}


@dataclass(frozen=True)
class RefrigerantSpec:
    """Contents of a refrigerant file, in SI.

    Attributes
    ----------
    name : str
        Name used in case files (``"R134a"``).
    coolprop_name : str
        CoolProp fluid name (``"R134a"``, ``"Isobutane"``).
    min_temperature, max_temperature : float
        Temperature range of the model [K] (the file's limits within CoolProp's).
    max_pressure : float
        Highest pressure of the model [Pa].
    rating_points : dict
        Name to a dict of SI values (``evaporating_temperature`` [K], ...).
    path : str
        File the spec was read from.
    envelope : dict
        Bounds of the operating envelope in SI (:mod:`recipsim.case.envelope`).
    """

    name: str
    coolprop_name: str
    description: str
    min_temperature: float
    max_temperature: float
    max_pressure: float
    critical_temperature: float
    critical_pressure: float
    rating_points: dict[str, dict[str, Any]] = field(default_factory=dict)
    path: str = ""
    #: operating envelope in SI (:mod:`recipsim.case.envelope`); empty: none documented
    envelope: dict[str, float] = field(default_factory=dict)


def refrigerant_dirs(extra: list[Path] | None = None) -> list[Path]:
    """Directories searched for refrigerant files, in order.

    ``$RECIPSIM_REFRIGERANTS``; then a ``refrigerants/`` folder in each of ``extra``
    (the case's folder and its parent); the working directory's ``refrigerants/``;
    last the shipped refrigerant files (the top-level ``refrigerants/`` of the source
    tree, installed as ``recipsim.shipped_refrigerants``:
    :func:`recipsim.case.files.shipped_dir`), always last: a file of the working
    directory shadows the shipped file of the same name, also for a shipped case (in a
    source tree the shipped ``refrigerants/`` lies beside ``cases/``, so it is one of
    ``extra`` there too; it is moved to the end).
    """
    shipped = shipped_dir("refrigerants")
    dirs: list[Path] = []
    env = os.environ.get("RECIPSIM_REFRIGERANTS")
    if env:
        dirs.append(Path(env))
    for d in extra or []:
        dirs.append(d / "refrigerants")
    dirs.append(Path.cwd() / "refrigerants")
    seen: list[Path] = []
    for d in dirs:
        if d not in seen and d.resolve() != shipped:
            seen.append(d)
    return seen + [shipped]


def available_refrigerants(search: list[Path] | None = None) -> list[str]:
    """Names of the refrigerant files that can be found."""
    names: set[str] = set()
    for d in refrigerant_dirs(search):
        if d.is_dir():
            names.update(p.stem for p in d.glob("*.toml"))
    return sorted(names)


def load_refrigerant(
    name: str, case_file: str = "", key: str = "refrigerant", search: list[Path] | None = None
) -> RefrigerantSpec:
    """Find and read the refrigerant file for ``name``.

    Raises
    ------
    CaseError
        Naming ``case_file`` and ``key`` when no such refrigerant exists, or naming the
        refrigerant file when it is invalid.
    """
    checked_name(name, case_file, key)  # a refrigerant name is a file name, never a path
    path = find_refrigerant_file(name, search)
    if path is not None:
        return read_refrigerant_file(path)
    known = available_refrigerants(search)
    raise CaseError(case_file, key, f"unknown refrigerant {name!r}; available: {known}")


def find_refrigerant_file(name: str, search: list[Path] | None = None) -> Path | None:
    """The first ``<name>.toml`` in :func:`refrigerant_dirs`, or None (``name`` must be a
    plain name: see :func:`load_refrigerant`)."""
    for d in refrigerant_dirs(search):
        path = d / f"{name}.toml"
        if path.is_file():
            return path
    return None


#: Refrigerant files read by this process, by path: (modification time [ns], size, spec).
_READ: dict[str, tuple[int, int, RefrigerantSpec]] = {}


def read_refrigerant_file(path: Path) -> RefrigerantSpec:
    """Read and validate one refrigerant file (once per process while the file is
    unchanged: a sweep loads its refrigerant at every point)."""
    stat = Path(path).stat()
    known = _READ.get(str(path))
    if known is not None and known[:2] == (stat.st_mtime_ns, stat.st_size):
        return known[2]
    spec = _read_refrigerant_file(path)
    _READ[str(path)] = (stat.st_mtime_ns, stat.st_size, spec)
    return spec


def _read_refrigerant_file(path: Path) -> RefrigerantSpec:
    file = str(path)
    raw, _ = read_toml(path, "refrigerant")
    check_keys(raw, {*REFRIGERANT_SPEC, *REFRIGERANT_TABLES}, file, "")
    top = read_table(
        {k: v for k, v in raw.items() if k in REFRIGERANT_SPEC}, REFRIGERANT_SPEC, file, ""
    )
    try:
        constants = fluid_constants(top["coolprop_name"])
    except ValueError:
        raise CaseError(
            file, "coolprop_name", f"CoolProp does not know the fluid {top['coolprop_name']!r}"
        ) from None
    limits = read_table(raw.get("limits"), LIMITS_SPEC, file, "limits")
    t_min = max(constants.t_min, limits["min_temperature"] or 0.0)
    t_max = min(constants.t_max, limits["max_temperature"] or 1e9)
    if not t_min < t_max:
        raise CaseError(
            file,
            "limits",
            f"the temperature range is empty: from {t_min:.6g} K (min_temperature or "
            f"CoolProp's lowest) to {t_max:.6g} K (max_temperature or CoolProp's highest)",
        )
    p_max = min(constants.p_max, limits["max_pressure"] or 1e12)
    points_raw = raw.get("rating_points", {})
    if not isinstance(points_raw, dict):
        raise CaseError(
            file, "rating_points", "expected tables [rating_points.<name>] of rating points"
        )
    points = {
        pname: read_table(ptable, RATING_POINT_SPEC, file, f"rating_points.{pname}")
        for pname, ptable in points_raw.items()
    }
    return RefrigerantSpec(
        name=top["name"],
        coolprop_name=top["coolprop_name"],
        description=top["description"],
        min_temperature=t_min,
        max_temperature=t_max,
        max_pressure=p_max,
        critical_temperature=constants.t_crit,
        critical_pressure=constants.p_crit,
        rating_points=points,
        path=file,
        envelope=read_envelope(raw.get("envelope"), file),
    )


@cache
def _table_fluid(coolprop_name: str, t_min: float, t_max: float) -> TableFluid:

    table = load_property_table(coolprop_name, t_min, t_max)
    constants = fluid_constants(coolprop_name)
    return TableFluid(table, constants.gas_constant, constants.t_crit, constants.p_crit)


def case_fluid(refrigerant: RefrigerantSpec, properties: str) -> AnyFluid:
    """The point-state calculator of a case's refrigerant.

    Parameters
    ----------
    refrigerant : RefrigerantSpec
        The refrigerant (its CoolProp name and model temperature range).
    properties : str
        The case's ``options.properties``: a tabulated backend gives the fluid's
        cached property table (built on first use), one instance per fluid and range in
        a process (a sweep loads it once); else a CoolProp :class:`Fluid`.
    """
    if PROPERTY_BACKENDS[properties].tabulated:
        return _table_fluid(
            refrigerant.coolprop_name, refrigerant.min_temperature, refrigerant.max_temperature
        )
    return Fluid(refrigerant.coolprop_name)


#: what :func:`case_fluid` returns: both answer the same point-state questions
AnyFluid: TypeAlias = "Fluid | TableFluid"
