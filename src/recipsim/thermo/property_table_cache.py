"""On-disk cache of property tables (``$RECIPSIM_CACHE/property_tables``).

Loading a cached table does not import CoolProp; a missing or stale one is built by
:mod:`.property_table_build` (which does).
"""

from __future__ import annotations

import hashlib
import json
import time
import zipfile
from dataclasses import asdict
from pathlib import Path
from typing import Any

import numpy as np

from ..atomic import atomic_write
from .coolprop_info import cache_dir, coolprop_version
from .property_table import (
    ERROR_SAMPLES,
    H_FORMAT,
    N_HEADER,
    TABLE_FORMAT,
    PropertyTable,
    TableResolution,
)

# ======================================================================================
# cache
# ======================================================================================


def cache_key(
    coolprop_name: str, t_min: float, t_max: float, res: TableResolution
) -> dict[str, Any]:
    """What a cached table depends on: fluid, CoolProp version, range, resolution, format."""
    return {
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


def _write(path: Path, table: PropertyTable, key: dict[str, Any]) -> None:
    def write(tmp: Path) -> None:
        with open(tmp, "wb") as handle:
            np.savez(
                handle,
                key=np.asarray(json.dumps(key, sort_keys=True)),
                error=np.asarray(json.dumps(table.error)),
                build_time=np.asarray(table.build_time),
                data=table.data,
            )

    atomic_write(path, write)


def _read(path: Path, key: dict[str, Any]) -> tuple[np.ndarray, dict[str, Any], float] | None:
    """Data, error and build time of a cached table; None if stale or unreadable."""
    try:
        with np.load(path, allow_pickle=False) as npz:
            if json.loads(str(npz["key"])) != json.loads(json.dumps(key, sort_keys=True)):
                return None
            data = np.array(npz["data"], dtype=np.float64)
            error = json.loads(str(npz["error"]))
            build_time = float(npz["build_time"])
    except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile):
        return None
    if data.ndim != 1 or data.size < N_HEADER or data[H_FORMAT] != TABLE_FORMAT:
        return None
    return data, error, build_time


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
        missing, stale (another key) or unreadable cache file is rebuilt and replaced
        atomically.
    """
    res = res or TableResolution()
    key = cache_key(coolprop_name, t_min, t_max, res)
    path = cache_path(coolprop_name, t_min, t_max, res, directory)
    start = time.perf_counter()
    cached = _read(path, key) if path.is_file() else None
    if cached is not None:
        data, error, build_time = cached
        return PropertyTable(
            coolprop_name,
            data,
            error=error,
            path=path,
            from_cache=True,
            build_time=build_time,
            load_time=time.perf_counter() - start,
        )
    from .property_table_build import build_table

    table = build_table(coolprop_name, t_min, t_max, res)
    table.path = path
    _write(path, table, key)
    return table
