"""Quantities with units in case files, converted once to SI at load time.

Bare numbers are taken to be in the SI unit of the key (K, Pa, m, kg, rad/s, ...).
Strings carry a unit, e.g. ``"3500 rpm"``, ``"-23.3 degC"`` or ``"22 mm"``; pint does
the conversion. pint is imported lazily so that runs without unit strings do not pay
for it; each distinct (string, unit) pair is converted once per process.
"""

from __future__ import annotations

import atexit
import json
from functools import lru_cache
from pathlib import Path
from typing import Any

from recipsim.errors import CaseError


@lru_cache(maxsize=1)
def _registry() -> Any:
    import pint

    # autoconvert_offset_to_baseunit: "-23.3 degC" converts to K without an error.
    # pint's own cache of the parsed definitions (in recipsim's cache directory) takes
    # the registry from 0.11 s to 0.015 s; without a usable cache, parse them.
    try:
        from recipsim.cache_dirs import cache_dir, private_dir

        folder = private_dir(cache_dir() / "pint")
        return pint.UnitRegistry(autoconvert_offset_to_baseunit=True, cache_folder=folder)
    except Exception:  # unwritable or malformed cache (pint raises several types): parse
        return pint.UnitRegistry(autoconvert_offset_to_baseunit=True)


def to_si(value: Any, unit: str, file: str, key: str) -> float:
    """Convert a case value to a float in the SI unit ``unit``.

    Parameters
    ----------
    value : float, int or str
        A bare number (already in ``unit``) or a string with a unit.
    unit : str
        SI unit expected for the key, in pint syntax (``"K"``, ``"Pa"``, ``"m"``,
        ``"rad/s"``, ``"dimensionless"``).
    file, key : str
        Where the value comes from, for the error message.

    Returns
    -------
    float
        The value in ``unit``.

    Raises
    ------
    CaseError
        If the value is not a number or a quantity of the right dimension.
    """
    if isinstance(value, bool):
        raise CaseError(file, key, f"expected a number or a quantity in {unit}, got {value!r}")
    if isinstance(value, (int, float)):
        return float(value)
    if not isinstance(value, str):
        raise CaseError(file, key, f"expected a number or a quantity in {unit}, got {value!r}")
    converted = _convert(value, unit)
    if isinstance(converted, str):
        raise CaseError(file, key, converted)
    return converted


@lru_cache(maxsize=8192)
def _convert(value: str, unit: str) -> float | str:
    """``value`` in ``unit``, or the message saying why it cannot be.

    Cached: a sweep reads the same few unit strings at every point, and pint parses
    one in about 50 us. The message is returned (not raised) so that it is cached too;
    :func:`to_si` adds the file and the key. Conversions are also kept on disk
    (:func:`_known`): a process that meets only known strings never imports pint
    (0.3 s).
    """
    known = _known()
    key = f"{unit}\n{value}"
    if key in known.values:
        return known.values[key]
    converted = _pint_convert(value, unit)
    known.add(key, converted)
    return converted


def _pint_convert(value: str, unit: str) -> float | str:
    ureg = _registry()
    try:
        q = ureg.Quantity(value)
    except Exception as exc:  # pint raises several unrelated types for bad strings
        return f"cannot read {value!r} as a quantity ({exc})"
    try:
        if not hasattr(q, "to"):
            return float(q)
        return float(q.to(unit).magnitude)
    except Exception:
        return f"{value!r} has the wrong dimension: expected a quantity in {unit}"


class _KnownConversions:
    """Conversions pint made before, in a JSON file of recipsim's cache directory.

    One file per pint version (a new pint may read a unit differently); JSON, so a
    cache file written by someone else can at worst give a wrong number, never run
    code. A missing, unreadable or malformed file is an empty cache; a write that
    fails is skipped. New conversions are written when the process exits (not by the
    forked workers of a sweep, which end without exit handlers: the parent's are).
    """

    def __init__(self, path: Path | None) -> None:
        self.path = path
        self.values: dict[str, float | str] = {}
        self.dirty = False
        if path is None:
            return
        try:
            data = json.loads(path.read_text())
        except (OSError, ValueError):
            return
        if isinstance(data, dict):
            self.values = {
                k: v for k, v in data.items() if isinstance(v, (float, str)) and isinstance(k, str)
            }

    def add(self, key: str, converted: float | str) -> None:
        """Remember a conversion; the file is written once, when the process exits."""
        if not self.dirty and self.path is not None:
            atexit.register(self.save)
        self.values[key] = converted
        self.dirty = True

    def save(self) -> None:
        """Write the known conversions (at most :data:`_MAX_KNOWN`) atomically."""
        if self.path is None or not self.dirty:
            return
        self.dirty = False
        try:
            from recipsim.atomic import atomic_file
            from recipsim.cache_dirs import private_dir

            private_dir(self.path.parent)
            kept = dict(list(self.values.items())[:_MAX_KNOWN])
            with atomic_file(self.path) as handle:
                json.dump(kept, handle)
        except OSError:
            pass


#: Conversions kept on disk at most (a sweep over 10 000 distinct strings keeps the
#: first ones only; the in-memory cache holds the rest).
_MAX_KNOWN = 4096


@lru_cache(maxsize=1)
def _known() -> _KnownConversions:
    try:
        from importlib.metadata import version

        from recipsim.cache_dirs import cache_dir

        return _KnownConversions(cache_dir() / "pint" / f"conversions-{version('pint')}.json")
    except Exception:  # no metadata for pint, no cache directory: memory only
        return _KnownConversions(None)
