"""On-disk cache of property tables (``<recipsim cache>/property_tables``).

Loading a cached table does not import CoolProp; a missing or stale one is built by
:mod:`.property_table_build` (which does). Every file carries the inputs it was built
from (:func:`cache_key`) and a SHA-256 checksum of its table, its entropy sums
(:func:`.table_entropy.entropy_tables`, stored rather than computed again by every
process that loads the table: 16-27 ms of a warm run), measured error and build time: a
file that cannot be read, is not shaped as a table, or whose inputs or checksum do not
match is discarded with a warning and rebuilt, so the error a run's provenance reports is
always the one measured for the table it used.
"""

from __future__ import annotations

import hashlib
import json
import logging
import time
import warnings
import zipfile
from dataclasses import asdict
from pathlib import Path
from typing import Any

import numpy as np

from recipsim.atomic import atomic_write
from recipsim.cache_dirs import cache_dir, private_dir
from recipsim.physics.thermo.coolprop_info import coolprop_version
from recipsim.physics.thermo.property_table import (
    ERROR_SAMPLES,
    H_FORMAT,
    N_HEADER,
    TABLE_FORMAT,
    PropertyTable,
    TableResolution,
)
from recipsim.physics.thermo.table_entropy import table_entropy_sums

logger = logging.getLogger(__name__)

#: Version of the cache file's own layout (key, checksum, arrays), part of the key
#: (3: the entropy sums stored with the table).
CACHE_FORMAT = 3

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
    safe = "".join(c if c.isalnum() else "_" for c in coolprop_name)
    return (directory or cache_dir()) / "property_tables" / f"{safe}-{digest}.npz"


def table_checksum(
    key_text: str, data: np.ndarray, entropy: np.ndarray, error_text: str, build_time: float
) -> str:
    """SHA-256 of what a cached table holds: its key, data, entropy sums, measured error,
    build time (the arrays hashed as little-endian float64, without a copy where they
    are laid out so)."""
    digest = hashlib.sha256()
    digest.update(key_text.encode())
    for array in (data, entropy):
        digest.update(np.ascontiguousarray(array, dtype="<f8").data)
    digest.update(error_text.encode())
    digest.update(repr(float(build_time)).encode())
    return digest.hexdigest()


def _write(path: Path, table: PropertyTable, key: dict[str, Any]) -> None:
    key_text = json.dumps(key, sort_keys=True)
    error_text = json.dumps(table.error, sort_keys=True)
    entropy = table_entropy_sums(table)
    checksum = table_checksum(key_text, table.data, entropy, error_text, table.build_time)

    def write(tmp: Path) -> None:
        with open(tmp, "wb") as handle:
            np.savez(
                handle,
                key=np.asarray(key_text),
                error=np.asarray(error_text),
                build_time=np.asarray(table.build_time),
                data=np.ascontiguousarray(table.data, dtype="<f8"),
                entropy=np.ascontiguousarray(entropy, dtype="<f8"),
                checksum=np.asarray(checksum),
            )

    private_dir(path.parent)
    atomic_write(path, write)


def _read(
    path: Path, key: dict[str, Any]
) -> tuple[np.ndarray, np.ndarray, dict[str, Any], float] | None:
    """Data, entropy sums, error and build time of a cached table; None if stale or
    unreadable.

    A file for other inputs is stale (None, silently); a file for these inputs that is
    malformed or fails its checksum is reported with a warning, then None.
    """
    key_text = json.dumps(key, sort_keys=True)
    try:
        with np.load(path, allow_pickle=False) as npz:
            if str(npz["key"]) != key_text:
                return None
            data = np.asarray(npz["data"], dtype=np.float64)  # already a new array: no copy
            entropy = np.asarray(npz["entropy"], dtype=np.float64)
            error_text = str(npz["error"])
            error = json.loads(error_text)
            build_time = float(npz["build_time"])
            checksum = str(npz["checksum"])
    except (OSError, ValueError, KeyError, EOFError, TypeError, zipfile.BadZipFile) as exc:
        _discard(path, f"unreadable ({type(exc).__name__})")
        return None
    if (
        data.ndim != 1
        or data.size < N_HEADER
        or data[H_FORMAT] != TABLE_FORMAT
        or entropy.ndim != 1
    ):
        _discard(path, "not shaped as a property table")
        return None
    if not isinstance(error, dict):
        _discard(path, "its measured error is malformed")
        return None
    if checksum != table_checksum(key_text, data, entropy, error_text, build_time):
        _discard(path, "its checksum does not match its content")
        return None
    return data, entropy, error, build_time


def _discard(path: Path, why: str) -> None:
    warnings.warn(f"property table cache {path}: {why}; rebuilding it", stacklevel=3)


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
    cached = _read(path, key) if path.is_file() else None
    if cached is not None:
        data, entropy, error, build_time = cached
        return PropertyTable(
            coolprop_name,
            data,
            entropy=entropy,
            error=error,
            path=path,
            from_cache=True,
            build_time=build_time,
            load_time=time.perf_counter() - start,
        )
    from recipsim.physics.thermo.property_table_build import build_table

    logger.info(
        "building the %s property table (once; 1-6 s, cached in %s)", coolprop_name, path.parent
    )
    table = build_table(coolprop_name, t_min, t_max, res)
    table.path = path
    _write(path, table, key)
    return table
