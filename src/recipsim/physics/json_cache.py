"""Small JSON records in recipsim's cache: read only when well formed, written atomically.

A record is a flat JSON object of numbers and a few named text fields (a fluid's
constants, a motor's fitted circuit). A file that is missing, larger than 100 kB,
malformed, that lacks a key or has an extra one, or holds anything but a finite number
outside its text fields is treated as absent: the caller computes the record again and
:func:`write_record` replaces the file.
"""

from __future__ import annotations

import json
import math
from collections.abc import Collection
from pathlib import Path
from typing import Any

from recipsim.atomic import atomic_write
from recipsim.cache_dirs import private_dir

#: larger files are not records of this kind
_MOST_BYTES = 100_000


def read_json(path: Path, most_bytes: int = _MOST_BYTES) -> Any:
    """The JSON content of ``path``, or None if it is missing, unreadable, larger than
    ``most_bytes`` or not JSON."""
    try:
        if path.stat().st_size > most_bytes:
            return None
        return json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None


def read_record(
    path: Path, keys: Collection[str], text_keys: Collection[str] = ()
) -> dict[str, Any] | None:
    """The record in ``path`` if it has exactly ``keys``, text (str) under ``text_keys``
    and finite numbers under the others; else None."""
    data = read_json(path)
    if not isinstance(data, dict) or set(data) != set(keys):
        return None
    for key, value in data.items():
        if key in text_keys:
            if not isinstance(value, str):
                return None
        elif (
            not isinstance(value, (int, float))
            or isinstance(value, bool)
            or not math.isfinite(value)
        ):
            return None
    return data


def write_record(path: Path, record: dict[str, Any]) -> None:
    """Write ``record`` to ``path`` as JSON, atomically, in a private directory.

    Raises
    ------
    OSError
        If the directory cannot be made or the file written.
    """
    text = json.dumps(record, indent=1)

    def write(tmp: Path) -> None:
        tmp.write_text(text, encoding="utf-8")

    private_dir(path.parent)
    atomic_write(path, write)
