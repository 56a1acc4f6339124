"""A sweep built in Python (:func:`recipsim.sweep`): a case and a grid of case values
as the :class:`~recipsim.studies.sweep.spec.SweepSpec` that a sweep file would give."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from recipsim.case.case import Case
from recipsim.case.overrides import parse_override, toml_literal
from recipsim.errors import CaseError
from recipsim.studies.sweep.spec import SweepSpec


def grid_spec(
    case: Case, name: str, grid: tuple[tuple[str, tuple[Any, ...]], ...], max_points: int
) -> SweepSpec:
    """The sweep file that :func:`recipsim.sweep` runs: the case's file and overrides, the axes."""
    fixed = tuple((".".join(path), value) for path, value in map(parse_override, case.overrides))
    lines = [f"name = {toml_literal(name)}", f"base = {toml_literal(case.path)}"]
    lines += ["[set]"] + [f"{toml_key(k)} = {toml_literal(v)}" for k, v in fixed]
    lines += ["[axes]"]
    lines += [f"{toml_key(k)} = [{', '.join(toml_literal(v) for v in vs)}]" for k, vs in grid]
    return SweepSpec(
        name=name,
        description=f"recipsim.sweep of {case.name}",
        path=Path(case.path),
        text="\n".join(lines) + "\n",
        base=Path(case.path).resolve(),
        fixed=fixed,
        axes=grid,
        points=(),
        max_points=max_points,
    )


def checked_axes(axes: Any) -> tuple[tuple[str, tuple[Any, ...]], ...]:
    """A sweep's axes as (dotted key, values); each axis a non-empty list of numbers,
    strings or booleans (a string is one value, never a list of characters)."""
    if not isinstance(axes, Mapping) or not axes:
        raise CaseError("recipsim.sweep", "axes", "a non-empty mapping of case key to values")
    grid = []
    for key, values in axes.items():
        where = f"axes[{key!r}]"
        if not isinstance(key, str) or not key:
            raise CaseError("recipsim.sweep", where, "an axis is named by a dotted case key")
        if isinstance(values, (str, bytes)) or not isinstance(values, Sequence):
            raise CaseError("recipsim.sweep", where, f"a list of values, got {values!r:.60}")
        if not values:
            raise CaseError("recipsim.sweep", where, "an axis needs at least one value")
        for value in values:
            if not isinstance(value, (str, int, float, bool, np.generic)):
                raise CaseError(
                    "recipsim.sweep", where, f"{value!r:.60} is not a number, text or boolean"
                )
        grid.append((key, tuple(values)))
    return tuple(grid)


def toml_key(dotted: str) -> str:
    """A dotted case key as a TOML key (each part quoted)."""
    return ".".join(toml_literal(part) for part in dotted.split("."))
