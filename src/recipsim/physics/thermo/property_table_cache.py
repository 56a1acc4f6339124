"""On-disk cache of property tables (``<recipsim cache>/property_tables``).

Loading a cached table does not import CoolProp; a missing or stale one is built by
:mod:`.property_table_build` (which does). Every file carries the inputs it was built
from (:func:`cache_key`) and a SHA-256 checksum of its table, its entropy sums
(:func:`.table_entropy.entropy_tables`, stored rather than computed again by every
process that loads the table), the fluid's constants
(:class:`.coolprop_info.FluidConstants`), measured error and build time: a file that
cannot be read, is not shaped as a table, or whose inputs or checksum do not match is
discarded with a warning and rebuilt, so the error a run's provenance reports is always
the one measured for the table it used.

The fluid's constants decide the table's temperature range (the refrigerant's limits
within the equation of state's), so they are needed before the table's file can be
named: :func:`fluid_constants` reads them from any valid cached table of the fluid
built with the installed CoolProp, and asks CoolProp where there is none.
"""

from __future__ import annotations

import hashlib
import json
import time
import warnings
import zipfile
from collections.abc import Callable
from dataclasses import asdict, fields
from functools import cache
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np

from recipsim.atomic import atomic_write
from recipsim.cache_dirs import cache_dir, private_dir
from recipsim.physics.thermo.coolprop_info import (
    FluidConstants,
    coolprop_fluid_constants,
    coolprop_version,
)
from recipsim.physics.thermo.property_table import (
    ERROR_SAMPLES,
    H_FORMAT,
    N_HEADER,
    TABLE_FORMAT,
    PropertyTable,
    TableResolution,
)
from recipsim.physics.thermo.table_entropy import table_entropy_sums
from recipsim.progress import timed_step

#: Version of the cache file's own layout (key, checksum, arrays), part of the key
#: (3: the entropy sums stored with the table; 4: the fluid's constants stored with it).
CACHE_FORMAT = 4

# ======================================================================================
# cache
# ======================================================================================


def cache_key(
    coolprop_name: str, t_min: float, t_max: float, res: TableResolution
) -> dict[str, Any]:
    """What a cached table depends on: fluid, CoolProp version, range, resolution, format."""
    return {
        "cache_format": CACHE_FORMAT,
        "format": TABLE_FORMAT,
        "fluid": coolprop_name,
        "coolprop": coolprop_version(),
        "t_min": float(t_min),
        "t_max": float(t_max),
        "resolution": asdict(res),
        "error_samples": ERROR_SAMPLES,
    }


def cache_path(
    coolprop_name: str,
    t_min: float,
    t_max: float,
    res: TableResolution,
    directory: Path | None = None,
) -> Path:
    """File of the cached table for these inputs."""
    key = json.dumps(cache_key(coolprop_name, t_min, t_max, res), sort_keys=True)
    digest = hashlib.sha256(key.encode()).hexdigest()[:16]
    return (directory or cache_dir()) / "property_tables" / f"{_safe(coolprop_name)}-{digest}.npz"


def _safe(coolprop_name: str) -> str:
    """The fluid's name as the start of its table files' names."""
    return "".join(c if c.isalnum() else "_" for c in coolprop_name)


def table_checksum(
    key_text: str,
    data: np.ndarray,
    entropy: np.ndarray,
    error_text: str,
    build_time: float,
    constants_text: str,
) -> str:
    """SHA-256 of what a cached table holds: its key, data, entropy sums, measured error,
    build time and the fluid's constants (the arrays hashed as little-endian float64,
    without a copy where they are laid out so)."""
    digest = hashlib.sha256()
    digest.update(key_text.encode())
    for array in (data, entropy):
        digest.update(np.ascontiguousarray(array, dtype="<f8").data)
    digest.update(error_text.encode())
    digest.update(repr(float(build_time)).encode())
    digest.update(constants_text.encode())
    return digest.hexdigest()


def _write(path: Path, table: PropertyTable, key: dict[str, Any]) -> None:
    key_text = json.dumps(key, sort_keys=True)
    error_text = json.dumps(table.error, sort_keys=True)
    constants_text = json.dumps(asdict(coolprop_fluid_constants(table.coolprop_name)))
    entropy = table_entropy_sums(table)
    checksum = table_checksum(
        key_text, table.data, entropy, error_text, table.build_time, constants_text
    )

    def write(tmp: Path) -> None:
        with open(tmp, "wb") as handle:
            np.savez(
                handle,
                key=np.asarray(key_text),
                error=np.asarray(error_text),
                build_time=np.asarray(table.build_time),
                data=np.ascontiguousarray(table.data, dtype="<f8"),
                entropy=np.ascontiguousarray(entropy, dtype="<f8"),
                constants=np.asarray(constants_text),
                checksum=np.asarray(checksum),
            )

    private_dir(path.parent)
    atomic_write(path, write)


class _Cached(NamedTuple):
    """What a valid cache file holds besides its key."""

    data: np.ndarray
    entropy: np.ndarray
    error: dict[str, Any]
    build_time: float
    constants: FluidConstants


def _read(path: Path, accepts: Callable[[str], bool], warn: bool = True) -> _Cached | None:
    """The content of a cached table whose key (its JSON text) ``accepts``; None if the
    file is for other inputs (silently), or unreadable, malformed or fails its checksum
    (reported with a warning where ``warn``).
    """

    def discard(why: str) -> None:
        if warn:  # attributed to the caller of _read
            warnings.warn(f"property table cache {path}: {why}; rebuilding it", stacklevel=3)

    try:
        with np.load(path, allow_pickle=False) as npz:
            key_text = str(npz["key"])
            if not accepts(key_text):
                return None
            data = np.asarray(npz["data"], dtype=np.float64)  # already a new array: no copy
            entropy = np.asarray(npz["entropy"], dtype=np.float64)
            error_text = str(npz["error"])
            error = json.loads(error_text)
            build_time = float(npz["build_time"])
            constants_text = str(npz["constants"])
            constants = json.loads(constants_text)
            checksum = str(npz["checksum"])
    except (OSError, ValueError, KeyError, EOFError, TypeError, zipfile.BadZipFile) as exc:
        discard(f"unreadable ({type(exc).__name__})")
        return None
    if (
        data.ndim != 1
        or data.size < N_HEADER
        or data[H_FORMAT] != TABLE_FORMAT
        or entropy.ndim != 1
    ):
        discard("not shaped as a property table")
        return None
    if not isinstance(error, dict):
        discard("its measured error is malformed")
        return None
    names = {f.name for f in fields(FluidConstants)}
    if not isinstance(constants, dict) or set(constants) != names:
        discard("its fluid constants are malformed")
        return None
    if checksum != table_checksum(key_text, data, entropy, error_text, build_time, constants_text):
        discard("its checksum does not match its content")
        return None
    return _Cached(data, entropy, error, build_time, FluidConstants(**constants))


def load_property_table(
    coolprop_name: str,
    t_min: float,
    t_max: float,
    res: TableResolution | None = None,
    directory: Path | None = None,
) -> PropertyTable:
    """The property table of a fluid: from the cache, else built, measured and cached.

    Parameters
    ----------
    coolprop_name : str
        CoolProp fluid name.
    t_min, t_max : float
        Temperature range [K] (the refrigerant's model range).
    res : TableResolution, optional
        Resolution and tolerance (default :class:`TableResolution`).
    directory : Path, optional
        Cache directory (default :func:`cache_dir`).

    Returns
    -------
    PropertyTable
        With :attr:`PropertyTable.error` measured against HEOS when it was built. A
        missing, stale (another key), unreadable or tampered (checksum) cache file is
        rebuilt and replaced atomically.
    """
    res = res or TableResolution()
    key = cache_key(coolprop_name, t_min, t_max, res)
    path = cache_path(coolprop_name, t_min, t_max, res, directory)
    start = time.perf_counter()
    key_text = json.dumps(key, sort_keys=True)
    cached = _read(path, lambda text: text == key_text) if path.is_file() else None
    if cached is not None:
        return PropertyTable(
            coolprop_name,
            cached.data,
            entropy=cached.entropy,
            error=cached.error,
            path=path,
            from_cache=True,
            build_time=cached.build_time,
            load_time=time.perf_counter() - start,
        )
    from recipsim.physics.thermo.property_table_build import build_table

    doing = f"building the {coolprop_name} property table"
    # the step's duration is measured and quoted the next time a table is built
    with timed_step(
        f"property table {coolprop_name}", doing, f"once; cached in {path.parent}", "property table"
    ):
        table = build_table(coolprop_name, t_min, t_max, res)
        table.path = path
        try:
            _write(path, table, key)
        except OSError as exc:  # an unusable cache directory: the run goes on without it
            warnings.warn(
                f"property table cache {path.parent} is not usable ({exc.strerror or exc}); "
                "the table is kept in memory for this run only (see RECIPSIM_CACHE)",
                stacklevel=2,
            )
    return table


@cache
def fluid_constants(coolprop_name: str) -> FluidConstants:
    """The constants of a CoolProp fluid (HEOS), once per process.

    Read from a valid cached property table of the fluid (any range and resolution)
    built with the installed CoolProp, so that a run with a cached table does not import
    CoolProp; else from CoolProp (:func:`.coolprop_info.coolprop_fluid_constants`). A
    cached file that is unreadable or fails its checksum is passed over here (loading it
    as a table reports it and rebuilds it).

    Raises
    ------
    ValueError
        If CoolProp does not know the fluid.
    """
    wanted = {"cache_format": CACHE_FORMAT, "fluid": coolprop_name, "coolprop": coolprop_version()}

    def same_fluid(key_text: str) -> bool:
        key = json.loads(key_text)
        return isinstance(key, dict) and all(key.get(k) == v for k, v in wanted.items())

    directory = cache_dir() / "property_tables"
    try:
        paths = sorted(directory.glob(f"{_safe(coolprop_name)}-*.npz"))
    except OSError:  # an unusable cache directory: nothing cached
        paths = []
    for path in paths:
        cached = _read(path, same_fluid, warn=False)
        if cached is not None:
            return cached.constants
    return coolprop_fluid_constants(coolprop_name)
