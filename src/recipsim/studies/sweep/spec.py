"""Read and check a sweep file (TOML).

Format (paths relative to the sweep file; every value is written as in a case file,
a bare number in the key's SI unit or a string with a unit)::

    name = "lbp_map"                      # optional; default: the file name
    description = "R134a and R600a at LBP"
    base = "reference_r134a_lbp"          # the case every point starts from: a file
                                          # beside this one or a shipped case by name
    max_points = 100000                   # optional; refuse larger sweeps (default 100 000)

    [set]                                 # overrides applied to every point
    solver.max_revolutions = 100

    [axes]                                # dotted case key = list of values: a grid
    refrigerant = ["R134a", "R600a"]
    operating_point.condensing_temperature = ["45 degC", "55 degC"]
    operating_point.evaporating_temperature = ["-35 degC", "-30 degC", "-25 degC"]

    [[points]]                            # optional explicit points, each crossed
    operating_point.condensing_temperature = "45 degC"   # with the grid of [axes]
    operating_point.liquid_temperature = "36.7 degC"

The first axis varies slowest. Without ``[axes]`` the sweep is exactly the list of
``[[points]]``; with both, every explicit point is combined with every grid point
(an explicit point is then one value of an extra, compound axis, which is how keys
that must change together, such as condensing and liquid temperature, are swept).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from recipsim.atomic import checked_name, name_from_stem
from recipsim.case.case import Case
from recipsim.case.files import find_case_file, read_toml, resolve_reference
from recipsim.case.overrides import parse_override, toml_literal
from recipsim.errors import CaseError
from recipsim.schema import Field, FileSpec, Text, check_keys, read_table

#: Largest sweep run unless the sweep file (``max_points``) or ``--max-points`` allows more.
DEFAULT_MAX_POINTS = 100_000

#: The sweep file's top level, read by :func:`recipsim.schema.read_table` (the
#: case-file reference prints it); ``[set]``, ``[axes]`` and ``[[points]]`` hold case keys,
#: validated by the case schema when the points are planned.
SWEEP_SPEC: FileSpec = {
    "name": Text(
        None,
        "the sweep's name and its output directory's (a plain file name); default: the file's stem",
    ),
    "description": Text("", "one line for people"),
    "base": Text(
        doc="the case every point starts from: a case file beside the sweep file or a "
        "shipped case by name"
    ),
    "max_points": Field(
        "dimensionless",
        DEFAULT_MAX_POINTS,
        lo=1,
        integer=True,
        doc="refuse the sweep if it has more points (--max-points overrides it)",
    ),
}
#: The sweep file's tables of case keys.
SWEEP_TABLES = ("set", "axes", "points")
SWEEP_KEYS = {*SWEEP_SPEC, *SWEEP_TABLES}

Scalar = str | int | float | bool
Assignment = tuple[tuple[str, Any], ...]
"""Ordered (dotted case key, value) pairs."""


@dataclass(frozen=True)
class SweepPoint:
    """One point of a sweep, before validation.

    Attributes
    ----------
    index : int
        Position in the sweep (grid order, first axis slowest), from 0.
    values : tuple of (str, value)
        The axis and explicit-point values of this point, dotted case key to value
        as written in the sweep file (units as strings, e.g. ``"-30 degC"``).
    """

    index: int
    values: Assignment


@dataclass(frozen=True)
class SweepSpec:
    """A parsed sweep file.

    Attributes
    ----------
    name : str
        Sweep name, the name of its output directory.
    description : str
        One line for people.
    path : Path
        The sweep file.
    text : str
        The sweep file's text (copied into the output directory).
    base : Path
        The base case file (absolute).
    fixed : tuple of (str, value)
        ``[set]``: dotted case key to value, applied to every point.
    axes : tuple of (str, tuple)
        ``[axes]``: dotted case key to its values, in file order.
    points : tuple of Assignment
        ``[[points]]``: explicit points, each a tuple of (dotted key, value).
    max_points : int
        Largest number of points this sweep may have (``max_points``).
    """

    name: str
    description: str
    path: Path
    text: str
    base: Path
    fixed: Assignment
    axes: tuple[tuple[str, tuple[Any, ...]], ...]
    points: tuple[Assignment, ...]
    max_points: int = DEFAULT_MAX_POINTS

    @property
    def size(self) -> int:
        """Number of points, computed from the axis lengths without expanding them."""
        grid = math.prod(len(values) for _, values in self.axes)
        return grid * max(1, len(self.points))

    def check_size(self, limit: int | None = None) -> None:
        """Refuse a sweep larger than ``limit`` (default :attr:`max_points`).

        Raises
        ------
        CaseError
            Naming the sweep file, ``max_points``, the count and the limit.
        """
        limit = self.max_points if limit is None else limit
        if self.size > limit:
            raise CaseError(
                str(self.path),
                "max_points",
                f"the sweep has {self.size:,} points, more than the limit of {limit:,}; "
                "split it, or raise the limit with max_points in the sweep file or "
                "--max-points",
            )

    @property
    def varying_keys(self) -> list[str]:
        """Dotted keys that change from point to point: axes, then explicit-point keys."""
        keys = [key for key, _ in self.axes]
        for point in self.points:
            keys.extend(key for key, _ in point if key not in keys)
        return keys

    def source_of(self, key: str) -> str:
        """Where a dotted case key is set in the sweep file (``axes.KEY``, ...)."""
        if any(k == key for k, _ in self.axes):
            return f"axes.{key}"
        for i, point in enumerate(self.points):
            if any(k == key for k, _ in point):
                return f"points[{i}].{key}"
        if any(k == key for k, _ in self.fixed):
            return f"set.{key}"
        return key

    def expand(self) -> Iterator[SweepPoint]:
        """All points, one at a time: the grid of the axes crossed with the explicit points."""
        grid = itertools.product(*(values for _, values in self.axes))
        keys = [key for key, _ in self.axes]
        explicit: tuple[Assignment, ...] = self.points or ((),)
        index = 0
        for combo in grid:
            for point in explicit:
                yield SweepPoint(index=index, values=tuple(zip(keys, combo, strict=True)) + point)
                index += 1


def _flatten(table: Mapping[str, Any], prefix: str = "") -> Iterator[tuple[str, Any]]:
    """Yield (dotted key, leaf value) of a nested TOML table."""
    for key, value in table.items():
        dotted = f"{prefix}.{key}" if prefix else key
        if isinstance(value, Mapping):
            yield from _flatten(value, dotted)
        else:
            yield dotted, value


def _assignment(table: Any, file: str, where: str, lists: bool) -> dict[str, Any]:
    """Flatten one table of dotted keys, checking keys and value types."""
    if not isinstance(table, Mapping):
        raise CaseError(file, where, "expected a table of dotted case keys")
    out: dict[str, Any] = {}
    for key, value in _flatten(table):
        parts = [p.strip() for p in key.split(".")]
        dotted = ".".join(parts)
        if not all(parts):
            raise CaseError(file, f"{where}.{key}", "empty part in the dotted key")
        if dotted in out:
            raise CaseError(file, f"{where}.{dotted}", "given twice")
        if lists:
            if not isinstance(value, list) or not value:
                raise CaseError(
                    file,
                    f"{where}.{dotted}",
                    'expected a non-empty list of values, e.g. ["-30 degC", "-25 degC"]',
                )
            for item in value:
                _check_scalar(item, file, f"{where}.{dotted}")
            if len({repr(v) for v in value}) != len(value):
                raise CaseError(file, f"{where}.{dotted}", "a value is repeated")
            out[dotted] = tuple(value)
        else:
            _check_scalar(value, file, f"{where}.{dotted}")
            out[dotted] = value
    return out


def _check_scalar(value: Any, file: str, key: str) -> None:
    if not isinstance(value, Scalar):
        raise CaseError(
            file,
            key,
            f'{value!r} is not allowed; a value is a number, a string ("22 mm", "R600a") '
            "or a boolean",
        )


def load_sweep(path: str | Path, allow_external_paths: bool = False) -> SweepSpec:
    """Read and check a sweep file.

    The case keys themselves are checked later, when the points are planned
    (:func:`recipsim.studies.sweep.plan.plan_sweep`).

    Parameters
    ----------
    path : str or Path
        The sweep file (TOML), or the name of a sweep: ``./cases/sweeps/<name>.toml``
        of the working directory, else a shipped sweep
        (:func:`recipsim.case.files.find_case_file`).
    allow_external_paths : bool
        Let ``base`` name a file outside the sweep file's directory (absolute or
        ``..``); cases by name (``./cases`` or shipped) are always allowed.

    Returns
    -------
    SweepSpec

    Raises
    ------
    CaseError
        Naming the sweep file, the key and what is allowed.
    """
    path = find_case_file(path, "sweeps", "sweep")
    file = str(path)
    raw, text = read_toml(path, "sweep")
    check_keys(raw, SWEEP_KEYS, file, "")
    top = read_table({k: v for k, v in raw.items() if k in SWEEP_SPEC}, SWEEP_SPEC, file, "")
    # the name becomes a directory name: a plain file name or refused
    name = name_from_stem(path.stem) if top["name"] is None else checked_name(top["name"], file)
    base = resolve_reference(
        top["base"], file, "base", "case file", allow_external_paths, by_name=True
    )
    fixed = _assignment(raw.get("set", {}), file, "set", lists=False)
    axes = _assignment(raw.get("axes", {}), file, "axes", lists=True)
    points_raw = raw.get("points", [])
    if not isinstance(points_raw, list):
        raise CaseError(file, "points", "expected an array of tables: [[points]]")
    points: list[Assignment] = []
    for i, table in enumerate(points_raw):
        point = _assignment(table, file, f"points[{i}]", lists=False)
        if not point:
            raise CaseError(file, f"points[{i}]", "an explicit point sets no key")
        points.append(tuple(point.items()))
    if not axes and not points:
        raise CaseError(file, "axes", "a sweep needs [axes] or [[points]] (or both)")
    for key in axes:
        if key in fixed:
            raise CaseError(
                file, f"set.{key}", "also an axis; give it in [axes] or [set], not both"
            )
    for i, explicit in enumerate(points):
        for key, _ in explicit:
            if key in axes or key in fixed:
                other = "[axes]" if key in axes else "[set]"
                raise CaseError(file, f"points[{i}].{key}", f"also in {other}; give it once")
    return SweepSpec(
        name=name,
        description=top["description"],
        path=path,
        text=text,
        base=base,
        fixed=tuple(fixed.items()),
        axes=tuple(axes.items()),
        points=tuple(points),
        max_points=int(top["max_points"]),
    )


def toml_key(dotted: str) -> str:
    """A dotted case key as a TOML key (each part quoted)."""
    return ".".join(toml_literal(part) for part in dotted.split("."))


def case_sweep_spec(
    case: Case,
    name: str,
    axes: tuple[tuple[str, tuple[Any, ...]], ...] = (),
    points: tuple[Assignment, ...] = (),
    max_points: int = DEFAULT_MAX_POINTS,
    description: str = "",
) -> SweepSpec:
    """The sweep of ``case`` (its file, its overrides as ``[set]``) over ``axes`` and
    explicit ``points``, built in Python as :func:`load_sweep` would read its file.

    Parameters
    ----------
    case : Case
        The base case; its overrides apply to every point.
    name : str
        Sweep name (its output directory's).
    axes, points : tuple
        As :attr:`SweepSpec.axes` and :attr:`SweepSpec.points`.
    max_points : int
        Refuse larger sweeps.
    description : str
        One line for people (default: ``recipsim.sweep of <case name>``).
    """
    fixed = tuple((".".join(path), value) for path, value in map(parse_override, case.overrides))
    lines = [f"name = {toml_literal(name)}", f"base = {toml_literal(case.path)}"]
    lines += ["[set]"] + [f"{toml_key(k)} = {toml_literal(v)}" for k, v in fixed]
    lines += ["[axes]"]
    lines += [f"{toml_key(k)} = [{', '.join(toml_literal(v) for v in vs)}]" for k, vs in axes]
    for point in points:
        lines += ["[[points]]"] + [f"{toml_key(k)} = {toml_literal(v)}" for k, v in point]
    return SweepSpec(
        name=name,
        description=description or f"recipsim.sweep of {case.name}",
        path=Path(case.path),
        text="\n".join(lines) + "\n",
        base=Path(case.path).resolve(),
        fixed=fixed,
        axes=axes,
        points=points,
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
