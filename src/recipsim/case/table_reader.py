"""Reading keys of one case table with units, ranges and messages that name the key."""

from __future__ import annotations

import math
from collections.abc import Callable, Collection, Mapping
from typing import Any

from recipsim.errors import CaseError
from recipsim.units import to_si


class TableReader:
    """Reads keys from one case table; every error names the file and the dotted key.

    Parameters
    ----------
    data : mapping
        The table as parsed from TOML.
    file : str
        The case file, for messages.
    prefix : str
        Dotted path of the table (``"bearings.primary"``).
    """

    def __init__(self, data: Any, file: str, prefix: str) -> None:
        if not isinstance(data, Mapping):
            raise CaseError(file, prefix, f"expected a table, got {data!r}")
        self.data = data
        self.file = file
        self.prefix = prefix

    def key(self, name: str) -> str:
        """Dotted path of key ``name``."""
        return f"{self.prefix}.{name}"

    def check_keys(self, allowed: Collection[str]) -> None:
        """Refuse any key not in ``allowed``."""
        unknown = sorted(set(self.data) - set(allowed))
        if unknown:
            raise CaseError(
                self.file,
                self.key(unknown[0]),
                f"unknown key; allowed: {', '.join(sorted(allowed))}",
            )

    def quantity(
        self,
        name: str,
        unit: str,
        check: Callable[[float], bool],
        allowed: str,
        default: float | None = None,
    ) -> float:
        """Key ``name`` in SI ``unit``; ``default`` when absent (None: required)."""
        if name not in self.data:
            if default is not None:
                return default
            raise CaseError(self.file, self.key(name), f"missing; allowed: {allowed} ({unit})")
        value = to_si(self.data[name], unit, self.file, self.key(name))
        if not math.isfinite(value) or not check(value):
            raise CaseError(
                self.file, self.key(name), f"{value!r} {unit} is out of range; allowed: {allowed}"
            )
        return value

    def described(
        self,
        spec: Mapping[str, Any],
        name: str,
        check: Callable[[float], bool] | None = None,
        default: float | None = None,
        context: str = "",
    ) -> float:
        """Key ``name`` with the unit and the range words of its declaration
        (:class:`recipsim.schema.Described` in ``spec``), checked against the
        declared range (``check``: a rule involving other keys, for a declaration
        without one); ``context`` (e.g. the length a range refers to) is appended to the
        range in messages."""
        key = spec[name]
        if check is None:
            check = key.admits
        elif key.bounded:
            raise ValueError(f"{self.key(name)}: the range is declared, the rule in code too")
        allowed = f"{key.allowed} ({context})" if context else key.allowed
        return self.quantity(name, key.unit, check, allowed, default)

    def choice(self, name: str, allowed: Collection[str], default: str | None = None) -> str:
        """Key ``name`` as one of the names in ``allowed``."""
        value = self.data.get(name, default)
        if value is None:
            raise CaseError(self.file, self.key(name), f"missing; allowed: {', '.join(allowed)}")
        if value not in allowed:
            raise CaseError(
                self.file,
                self.key(name),
                f"{value!r} is not allowed; allowed: {', '.join(allowed)}",
            )
        return str(value)
