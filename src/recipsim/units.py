"""Quantities with units in case files, converted once to SI at load time.

Bare numbers are taken to be in the SI unit of the key (K, Pa, m, kg, rad/s, ...).
Strings carry a unit, e.g. ``"3500 rpm"``, ``"-23.3 degC"`` or ``"22 mm"``; pint does
the conversion, once per distinct (string, unit) pair in a process. pint's parsed unit
definitions are cached on disk only in a folder no one else can write
(:func:`recipsim.cache_dirs.trusted_cache`).

An angular speed (a key in ``rad/s``) given as a frequency without an angle (``"50 Hz"``,
``"50 1/s"``) is read in revolutions per second, as a shaft speed is meant: pint alone
would take 1 Hz for 1 rad/s, since the radian is dimensionless.
"""

from __future__ import annotations

import math
from decimal import Decimal
from functools import lru_cache
from typing import Any

import pint

from recipsim.cache_dirs import cache_dir, trusted_cache
from recipsim.errors import CaseError

#: Significant digits of a decimal number that a float holds exactly (a conversion's
#: decimal result this short is a round number, :func:`correctly_rounded`).
_SHORT_DECIMAL = 15


@lru_cache(maxsize=1)
def _registry() -> Any:
    # autoconvert_offset_to_baseunit: "-23.3 degC" converts to K without an error. pint
    # keeps its parsed definitions (pickled) in a cache folder: only a trusted one.
    folder = trusted_cache(cache_dir() / "pint")
    try:
        registry: Any = pint.UnitRegistry(autoconvert_offset_to_baseunit=True, cache_folder=folder)
    except Exception:  # an unreadable or malformed cache (pint raises several types): parse
        registry = pint.UnitRegistry(autoconvert_offset_to_baseunit=True)
    registry.define("@alias revolution = rev")  # "rev/s", as engineers write it
    return registry


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

    Cached in memory: a sweep reads the same few unit strings at every point. The
    message is returned (not raised) so that it is cached too; :func:`to_si` adds the
    file and the key.
    """
    ureg = _registry()
    try:
        q = ureg.Quantity(value)
    except Exception as exc:  # pint raises several unrelated types for bad strings
        return f"cannot read {value!r} as a quantity ({exc})"
    if not _finite(getattr(q, "magnitude", q)):
        return f"{value!r} is not a finite number"
    try:
        if not hasattr(q, "to"):
            return float(q)
        if unit == "rad/s" and _frequency_without_angle(q):
            return float(q.to("1/s").magnitude) * 2.0 * math.pi  # revolutions per second
        computed = float(q.to(unit).magnitude)
    except Exception as exc:  # pint raises several unrelated types
        if isinstance(exc, OverflowError) or "digits" in str(exc):
            return f"{value!r}: the number is too large for a float"
        return f"{value!r} has the wrong dimension: expected a quantity in {unit}"
    try:  # the unit's SI values at 0 and 1: the conversion, affine
        zero, one = (float(ureg.Quantity(m, q.units).to(unit).magnitude) for m in (0, 1))
    except Exception:  # pint raises several types: the value as pint converted it
        return computed
    return correctly_rounded(float(q.magnitude), zero, one, computed)


def correctly_rounded(magnitude: float, zero: float, one: float, computed: float) -> float:
    """``magnitude`` in a unit whose SI values at 0 and 1 are ``zero`` and ``one``,
    without the float noise of the conversion where the input is a round number.

    The conversion is done again in decimal arithmetic, on the number as written (its
    shortest repr) and on the unit's factor and offset as defined (pint's floats read
    to 15 significant digits), and rounded once to a float; that value is taken where it
    is a short decimal (15 significant digits or fewer) within two units in the last
    place of ``computed``, the float conversion: -23.3 degC is 249.85 K, where the float
    sum ``-23.3 + 273.15`` gives 249.84999999999997 (neither addend is a float, and the
    sum rounds once more); 22 mm is 0.022 m. Elsewhere (an irrational factor, as from
    rpm to rad/s, or a number written with all a float's digits, as a resolved case
    writes them) it is ``computed``.
    """

    def defined(number: float) -> Decimal:
        return Decimal(f"{number:.15g}")

    exact = Decimal(repr(magnitude)) * (defined(one) - defined(zero)) + defined(zero)
    if len(exact.normalize().as_tuple().digits) > _SHORT_DECIMAL:
        return computed
    value = float(exact)
    return value if abs(value - computed) <= 2.0 * math.ulp(computed) else computed


def _finite(magnitude: Any) -> bool:
    """Whether a parsed number is finite (one too large for a float counts as finite
    here: the conversion then says it is too large)."""
    try:
        return math.isfinite(float(magnitude))
    except (OverflowError, TypeError, ValueError):
        return True


def _frequency_without_angle(q: Any) -> bool:
    """Whether ``q`` is a rate (1/time) whose units name no angle (Hz, 1/s, 1/min)."""
    base = q.to_base_units()
    return bool(base.dimensionality == {"[time]": -1} and "radian" not in str(base.units))


def in_written_unit(written: Any, unit: str, values: tuple[float, ...]) -> tuple[str, ...] | None:
    """``values`` in the SI ``unit`` converted to the unit of ``written`` (a string with a
    unit, as in a case file) and formatted, then that unit: ``("0", "19099", "rpm")`` for
    ``"30000 rpm"`` and (0, 2000) rad/s. None where ``written`` has no unit of its own
    (a bare number, an SI unit) or one that cannot be converted back plainly."""
    if not isinstance(written, str):
        return None
    try:
        q = _registry().Quantity(written)
        if not hasattr(q, "units") or str(q.units) in ("", "dimensionless"):
            return None
        if unit == "rad/s" and _frequency_without_angle(q):
            return None  # a frequency read as revolutions: pint would convert it as radians
        if q.units == _registry().Unit(unit):
            return None
        converted = [_registry().Quantity(v, unit).to(q.units).magnitude for v in values]
    except Exception:  # pint raises several types: the SI range alone is shown
        return None
    return (*(f"{v:.5g}" for v in converted), written.strip().split(maxsplit=1)[-1])
