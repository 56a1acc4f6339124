"""Quantities with units in case files, converted once to SI at load time.

Bare numbers are taken to be in the SI unit of the key (K, Pa, m, kg, rad/s, ...).
Strings carry a unit, e.g. ``"3500 rpm"``, ``"-23.3 degC"`` or ``"22 mm"``; pint does
the conversion. pint is imported lazily so that runs without unit strings do not pay
for it; each distinct (string, unit) pair is converted once per process.
"""

from __future__ import annotations

from functools import lru_cache
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
    :func:`to_si` adds the file and the key.
    """
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
