"""Declarative validation of TOML tables: units, ranges, choices, unknown keys.

A table is described by a mapping of key to :class:`Field` (or :class:`Choice`);
:func:`read_table` converts every value to SI once and raises :class:`CaseError`
naming the file, the dotted key and what is allowed.
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from recipsim.errors import CaseError
from recipsim.units import in_written_unit, to_si

REQUIRED = object()


@dataclass(frozen=True)
class Field:
    """A numeric key: SI unit, default and allowed range.

    Parameters
    ----------
    unit : str
        SI unit of the key in pint syntax (``"dimensionless"`` for pure numbers).
    default : float or REQUIRED or None
        Value used when the key is absent; ``None`` means "not set".
    lo, hi : float
        Allowed range (inclusive unless ``open_lo``/``open_hi``).
    doc : str
        One line for error messages and documentation.
    integer : bool
        The value must be a whole number.
    plausible : (float, float) or None
        Physically plausible range (SI, inside ``lo``-``hi``) of a key that a user may
        calibrate (``recipsim calibrate`` judges a fitted value against it); None: not
        declared.
    plausible_source : str
        Where the plausible range comes from (a publication, a stated estimate).
    plausible_when : (str, str) or None
        ``(dotted option key, value)``: the range holds only for that option (a
        correlation's constant); None: always.
    """

    unit: str
    default: Any = REQUIRED
    lo: float = -math.inf
    hi: float = math.inf
    open_lo: bool = False
    open_hi: bool = False
    doc: str = ""
    integer: bool = False
    plausible: tuple[float, float] | None = None
    plausible_source: str = ""
    plausible_when: tuple[str, str] | None = None

    def allowed(self) -> str:
        unit = "" if self.unit == "dimensionless" else f" {self.unit}"
        return self._brackets(f"{self.lo:g}", f"{self.hi:g}") + unit

    def _brackets(self, lo: str, hi: str) -> str:
        """``lo, hi`` in the brackets of the range: ``(`` for an open end, ``[`` else."""
        return f"{'(' if self.open_lo else '['}{lo}, {hi}{')' if self.open_hi else ']'}"

    def check(self, value: float, file: str, key: str, written: Any = None) -> float:
        """``value`` (SI) if it is in range; else a :class:`CaseError` that also gives the
        value and the range in the unit the user ``written`` it in."""
        bad_lo = value <= self.lo if self.open_lo else value < self.lo
        bad_hi = value >= self.hi if self.open_hi else value > self.hi
        if not math.isfinite(value):
            raise CaseError(
                file, key, f"{value:g} is not a finite number; allowed {self.allowed()}"
            )
        if bad_lo or bad_hi:
            own = in_written_unit(written, self.unit, (self.lo, self.hi))
            shown = f"{written} ({value:g} {self.unit})" if own else f"{value:g}"
            also = f", that is {self._brackets(own[0], own[1])} {own[2]}" if own else ""
            raise CaseError(file, key, f"{shown} is out of range; allowed {self.allowed()}{also}")
        if self.integer and value != int(value):
            raise CaseError(file, key, f"{value:g} must be a whole number")
        return value


@dataclass(frozen=True)
class Choice:
    """A string key with a fixed set of allowed values."""

    choices: tuple[str, ...]
    default: Any = REQUIRED
    doc: str = ""


@dataclass(frozen=True)
class Flag:
    """A boolean key (TOML ``true``/``false``)."""

    default: Any = REQUIRED
    doc: str = ""


@dataclass(frozen=True)
class Text:
    """A free string key."""

    default: Any = REQUIRED
    doc: str = ""


@dataclass(frozen=True)
class TextList:
    """A list of strings (TOML ``["a", "b"]``), read as a tuple."""

    default: Any = REQUIRED
    doc: str = ""


@dataclass(frozen=True)
class Described:
    """A key of a table validated in code, where a rule may involve other keys (the
    piston pin within the piston length, a clearance relative to the diameter).

    The loader reads its unit and the words of its range from here (its messages say
    them); a range that involves no other key is declared here in numbers too
    (``lo``/``hi``, as :class:`Field`'s) and checked from here, a rule that involves other
    keys is checked in code. The case-file reference prints the same.

    Parameters
    ----------
    unit : str
        SI unit in pint syntax (``"dimensionless"`` for pure numbers, ``""`` for a
        string key).
    allowed : str
        The allowed values in words (``"> 0"``, ``"0 ... length"``).
    default : str
        The value when absent, in words; ``""``: none (see ``required``).
    required : str
        ``"yes"``, ``"no"`` or the condition under which the key is required; default
        ``"yes"`` without a default, else ``"no"``.
    doc : str
        What the key is.
    """

    unit: str
    allowed: str
    default: str = ""
    required: str = ""
    doc: str = ""
    #: The range in numbers, where it involves no other key (the words say the same);
    #: a rule that involves other keys is checked in code and declares none.
    lo: float = -math.inf
    hi: float = math.inf
    open_lo: bool = False
    open_hi: bool = False

    @property
    def bounded(self) -> bool:
        """Whether the declaration holds the range in numbers."""
        return self.lo > -math.inf or self.hi < math.inf

    def admits(self, value: float) -> bool:
        """Whether ``value`` (in SI) lies in the declared range."""
        above = value > self.lo if self.open_lo else value >= self.lo
        below = value < self.hi if self.open_hi else value <= self.hi
        return above and below

    def requirement(self) -> str:
        """Whether the key is required: ``"yes"``, ``"no"`` or a condition."""
        return self.required or ("no" if self.default else "yes")


Spec = Mapping[str, Field | Choice | Flag | Text]
#: A table of any input file: a :data:`Spec`, or one with lists of strings too (a list is
#: not a case value: ``--set`` and sweeps assign scalars).
FileSpec = Mapping[str, Field | Choice | Flag | Text | TextList]
#: Keys of a table validated in code, in the order of the table.
DescribedSpec = Mapping[str, Described]


def check_keys(
    raw: Mapping[str, Any], allowed: set[str] | FileSpec, file: str, prefix: str
) -> None:
    """Refuse keys that are not in ``allowed``, suggesting the closest one."""
    for key in raw:
        if key not in allowed:
            close = difflib.get_close_matches(key, list(allowed), n=1)
            hint = f"; did you mean {close[0]!r}?" if close else ""
            names = ", ".join(sorted(allowed))
            raise CaseError(file, _join(prefix, key), f"unknown key{hint} (allowed: {names})")


def read_table(
    raw: Mapping[str, Any] | None, spec: FileSpec, file: str, prefix: str
) -> dict[str, Any]:
    """Validate one table and return its values in SI.

    Parameters
    ----------
    raw : mapping or None
        The table as read by ``tomllib`` (``None`` for a missing table).
    spec : mapping of key to Field, Choice or Text
        What the table may contain.
    file, prefix : str
        File path and dotted prefix of the table, for messages.

    Returns
    -------
    dict
        Every key of ``spec``: floats in SI, strings, or ``None`` where unset.
    """
    raw = {} if raw is None else raw
    if not isinstance(raw, Mapping):
        raise CaseError(file, prefix, "expected a table")
    check_keys(raw, spec, file, prefix)
    out: dict[str, Any] = {}
    for key, field in spec.items():
        dotted = _join(prefix, key)
        if key not in raw:
            if field.default is REQUIRED:
                raise CaseError(file, dotted, f"missing required key ({_describe(field)})")
            out[key] = field.default
            continue
        value = raw[key]
        if isinstance(field, Field):
            out[key] = field.check(to_si(value, field.unit, file, dotted), file, dotted, value)
        elif isinstance(field, Choice):
            if value not in field.choices:
                raise CaseError(
                    file, dotted, f"{value!r} is not allowed; choose one of {list(field.choices)}"
                )
            out[key] = value
        elif isinstance(field, Flag):
            if not isinstance(value, bool):
                raise CaseError(file, dotted, f"expected true or false, got {value!r}")
            out[key] = value
        elif isinstance(field, TextList):
            if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
                raise CaseError(file, dotted, f"expected a list of strings, got {value!r}")
            out[key] = tuple(value)
        else:
            if not isinstance(value, str):
                raise CaseError(file, dotted, f"expected a string, got {value!r}")
            out[key] = value
    return out


def _describe(field: Field | Choice | Flag | Text | TextList) -> str:
    """What a key allows, and what it is (its ``doc``), for a missing key's message."""
    if isinstance(field, Field):
        allowed = f"allowed {field.allowed()}"
    elif isinstance(field, Choice):
        allowed = f"one of {list(field.choices)}"
    elif isinstance(field, Flag):
        allowed = "true or false"
    elif isinstance(field, TextList):
        allowed = "a list of strings"
    else:
        allowed = "a string"
    return allowed + (f"; {field.doc}" if field.doc else "")


def _join(prefix: str, key: str) -> str:
    return f"{prefix}.{key}" if prefix else key
