"""``--set KEY=VALUE`` overrides: reading them, writing a value as one, and applying them
to the raw TOML data of a case before it is validated (so that they are checked exactly
like the file itself).
"""

from __future__ import annotations

import copy
import json
import math
import tomllib
from collections.abc import Mapping, Sequence
from functools import lru_cache
from typing import Any

import numpy as np

from recipsim.case.case_schema import drop_replaced_alternatives
from recipsim.errors import CaseError


def parse_override(text: str) -> tuple[list[str], Any]:
    """Split ``"a.b.c=VALUE"`` into a key path and a TOML-typed value.

    The value is read as a TOML value when it parses (``1e-9``, ``"3000 rpm"``,
    ``true``), otherwise as a bare string (``ideal``).
    """
    path, parsed = _parsed_override(text)
    return list(path), copy.deepcopy(parsed)


@lru_cache(maxsize=4096)
def _parsed_override(text: str) -> tuple[tuple[str, ...], Any]:
    """:func:`parse_override`, once per text: a sweep's points repeat their axes' few
    texts, each read twice per point."""
    if "=" not in text:
        raise CaseError("--set", text, "expected KEY=VALUE, e.g. solver.rtol=1e-9")
    key, value = text.split("=", 1)
    path = tuple(k.strip() for k in key.strip().split("."))
    if not all(path):
        raise CaseError("--set", key, "empty part in the dotted key")
    try:
        parsed = tomllib.loads(f"v = {value.strip()}")["v"]
    except tomllib.TOMLDecodeError:
        parsed = value.strip()
    return path, parsed


def toml_literal(value: Any) -> str:
    """Write a scalar as a TOML value, the right-hand side of a ``--set`` override (numpy
    scalars as the Python numbers they equal)."""
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        value = float(value)
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    raise TypeError(f"not a TOML scalar: {value!r}")


def override(key: str, value: Any) -> str:
    """``KEY=VALUE`` text for one case value (checked to read back as ``value``).

    Raises
    ------
    CaseError
        Naming the key, if ``value`` is not a TOML scalar that reads back unchanged.
    """
    try:
        literal = toml_literal(value)
    except TypeError:
        raise CaseError(
            "overrides", key, f"{value!r} is not allowed; a number, a string or a boolean"
        ) from None
    text = f"{key}={literal}"
    _, parsed = parse_override(text)
    if parsed != value and not (isinstance(value, float) and math.isnan(value)):
        raise CaseError("--set", key, f"{value!r} cannot be written as an override")
    return text


def override_texts(overrides: Mapping[str, Any] | Sequence[str] | None) -> list[str]:
    """``KEY=VALUE`` texts from a mapping of dotted keys to values, or from such texts."""
    if overrides is None:
        return []
    if isinstance(overrides, Mapping):
        return [override(str(key), value) for key, value in overrides.items()]
    if isinstance(overrides, str):
        return [overrides]
    return [str(text) for text in overrides]


def override_tables(overrides: list[str]) -> set[str]:
    """The top-level keys of the case that ``--set`` overrides change (``"operating_point"``
    for ``operating_point.shaft_speed=...``)."""
    return {_parsed_override(text)[0][0] for text in overrides}


def apply_overrides(raw: dict[str, Any], overrides: list[str], file: str) -> dict[str, Any]:
    """Return a copy of ``raw`` with ``--set`` overrides applied.

    Only the tables on an override's path are copied; the others are shared with
    ``raw`` (a sweep applies overrides to its base case at every point, when planning
    it and again when solving it). Case data is never modified in place once read, so
    sharing is safe.
    """
    data = dict(raw)
    for text in overrides:
        path, value = _parsed_override(text)
        if isinstance(value, (list, dict)):  # a TOML array or table: the cache's own
            value = copy.deepcopy(value)
        node = data
        for part in path[:-1]:
            nxt = node.get(part, {})
            if not isinstance(nxt, dict):
                raise CaseError(file, ".".join(path), f"{part!r} is not a table")
            nxt = node[part] = dict(nxt)
            node = nxt
        node[path[-1]] = value
        if len(path) == 2:
            drop_replaced_alternatives(data, {path[0]: {path[1]: value}})
    return data


def blamed_on_override(error: CaseError, texts: Sequence[str]) -> CaseError:
    """``error`` attributed to the override that set its key, if one did (the last one
    of that key or of a table above it): the message then names ``override KEY=VALUE``
    instead of the case file, whose value was replaced. Otherwise ``error`` itself."""
    for text in reversed(texts):
        key = ".".join(parse_override(text)[0])
        if error.key == key or error.key.startswith(key + "."):
            return CaseError(f"override {text}", error.key, error.message)
    return error
