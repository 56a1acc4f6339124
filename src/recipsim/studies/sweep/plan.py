"""Expand a sweep into points, key and label them; check its size and its keys.

The size is checked before anything is expanded (:attr:`SweepSpec.size`). One case
per set of point keys is built here: a key that the case schema does not know (a typo
in an axis key) stops the sweep at once with a message naming the sweep file and the
key. Every point's *values* are validated once, where the point runs: a point whose
values are invalid (a temperature outside a refrigerant's range, an unknown
refrigerant) becomes an ``invalid`` row. Nothing here builds a case per point, so a
large sweep starts computing at once.

Each point gets a stable identifier, a hash of the case it runs (the base case with
its ``extends`` resolved and the overrides applied), of the refrigerant file it
uses and of the recipsim version: a finished point is found again on a rerun, even
if the sweep file was reordered or extended, and is recomputed when any of these
change.
"""

from __future__ import annotations

import hashlib
import json
import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Any

from recipsim.case.files import MAX_TOML_BYTES, read_input_text, read_toml
from recipsim.case.load import (
    GEOMETRY_SPEC,
    HEAT_TRANSFER_SPEC,
    LEAKAGE_SPEC,
    OPERATING_POINT_SPEC,
    OPTION_SPEC,
    SOLVER_SPEC,
    VALVE_SPEC,
    VALVES_TOP_SPEC,
    apply_overrides,
    override,
    parse_override,
    resolve_extends,
)
from recipsim.case.mechanism_schema import MECHANISM_UNITS
from recipsim.case.refrigerant import find_refrigerant_file
from recipsim.errors import CaseError
from recipsim.schema import Choice, Field, Flag, Text
from recipsim.studies.sweep.spec import SweepSpec
from recipsim.studies.sweep.worker import point_case
from recipsim.units import to_si
from recipsim.version import __version__

# Messages of :mod:`recipsim.schema` and :mod:`recipsim.case.mechanism` that mean "this
# key does not exist or is not where a table is expected": an error of the sweep file.
_KEY_ERRORS = ("unknown key", "expected a table", "is not a table", "empty part in")

_TABLE_SPECS = {
    "operating_point": OPERATING_POINT_SPEC,
    "geometry": GEOMETRY_SPEC,
    "leakage": LEAKAGE_SPEC,
    "heat_transfer": HEAT_TRANSFER_SPEC,
    "solver": SOLVER_SPEC,
    "options": OPTION_SPEC,
    "valves": VALVES_TOP_SPEC,
    "valves.suction": VALVE_SPEC,
    "valves.discharge": VALVE_SPEC,
    "": {"refrigerant": Text(), "name": Text(), "description": Text()},
}


@dataclass(frozen=True)
class PlannedPoint:
    """A validated point, ready to be run or looked up.

    Attributes
    ----------
    index : int
        Position in the sweep, from 0 (the ``point`` column).
    point_id : str
        Stable identifier (hex), the name of the point's result file.
    overrides : tuple of str
        ``KEY=VALUE`` overrides applied to the base case, as for ``recipsim run --set``.
    columns : dict
        Axis columns of the summary row: column name to value in SI (a string for
        text keys such as ``refrigerant``).
    """

    index: int
    point_id: str
    overrides: tuple[str, ...]
    columns: dict[str, Any] = field(default_factory=dict)


def _field_for(key: str) -> Field | Choice | Flag | Text | None:
    """Schema entry of a dotted case key, if it is known here."""
    table, _, leaf = key.rpartition(".")
    spec = _TABLE_SPECS.get(table)
    if spec is not None:
        return spec.get(leaf)
    if table.startswith(("mechanism.", "bearings.")) and leaf in MECHANISM_UNITS:
        return Field(MECHANISM_UNITS[leaf])
    return None


def _unit_label(unit: str) -> str:
    return "-" if unit == "dimensionless" else unit


def axis_column_names(keys: Iterable[str]) -> dict[str, str]:
    """Summary column of each varying key: ``<last key segment> [SI unit]``.

    Keys whose last segment is shared (``valves.suction.reed_thickness`` and
    ``valves.discharge.reed_thickness``) keep their whole dotted path. Text and choice
    keys (``refrigerant``, ``options.valves``) have no unit.
    """
    keys = list(keys)
    leaves = [k.rpartition(".")[2] for k in keys]
    names: dict[str, str] = {}
    for key, leaf in zip(keys, leaves, strict=True):
        label = leaf if leaves.count(leaf) == 1 else key
        spec = _field_for(key)
        names[key] = f"{label} [{_unit_label(spec.unit)}]" if isinstance(spec, Field) else label
    return names


def axis_value(key: str, value: Any, file: str) -> Any:
    """Value of an axis column: SI float for a numeric key, else the value as given."""
    spec = _field_for(key)
    if isinstance(spec, Field):
        try:
            return to_si(value, spec.unit, file, key)
        except CaseError:
            return math.nan
    return value


def _read_base(spec: SweepSpec, allow_external_paths: bool = False) -> dict[str, Any]:
    """The base case's TOML data with its ``extends`` chain merged in."""
    raw, _ = read_toml(spec.base, "case")
    return resolve_extends(raw, spec.base, [spec.base.resolve()], allow_external_paths)


def point_id(case_data: Mapping[str, Any], refrigerant_text: str) -> str:
    """Stable identifier of a point: hash of its case data, refrigerant file and version.

    The SHA-256 (first 16 hex digits) of the JSON of ``{"case": ..., "recipsim": ...,
    "refrigerant": ...}``, keys sorted, built from its parts: the case's JSON, then the
    rest, encoded once per refrigerant file (:func:`_id_tail`).
    """
    whole = f'{{"case": {_id_json(case_data)}{_id_tail(refrigerant_text)}'
    return hashlib.sha256(whole.encode()).hexdigest()[:16]


def _id_json(value: Any) -> str:
    """JSON of ``value`` as a point's identifier reads it: keys sorted, ASCII, other
    objects as str."""
    return json.dumps(value, sort_keys=True, default=str, ensure_ascii=True)


@lru_cache(maxsize=16)
def _id_tail(refrigerant_text: str) -> str:
    """The end of a point's identifier JSON after its case data: the version and the
    refrigerant file's text, encoded once per refrigerant file (the bulk of the JSON)."""
    return f', "recipsim": {_id_json(__version__)}, "refrigerant": {_id_json(refrigerant_text)}}}'


class _RefrigerantTexts:
    """The text of each refrigerant file a sweep names, read once (``""`` if unknown)."""

    def __init__(self, base: Path) -> None:
        self.search = [base.parent, base.parent.parent]
        self.texts: dict[str, str] = {}

    def __call__(self, name: Any) -> str:
        key = str(name)
        if key not in self.texts:
            self.texts[key] = ""
            safe = isinstance(name, str) and "/" not in key and "\\" not in key
            path = find_refrigerant_file(key, self.search) if safe else None
            if path is not None:
                try:
                    self.texts[key] = read_input_text(path, "refrigerant", MAX_TOML_BYTES)
                except CaseError:
                    pass  # the point's case load reports it
        return self.texts[key]


def plan_sweep(
    spec: SweepSpec,
    extra: Iterable[str] = (),
    max_points: int | None = None,
    allow_external_paths: bool = False,
) -> list[PlannedPoint]:
    """Expand a sweep into points, key and label them, without building their cases.

    The size is checked first (from the axis lengths, nothing expanded); then one case
    per explicit point is built, which catches every key the case schema does not know
    (the keys are the same at every grid point). The *values* of each point are
    validated once, where the point runs (an invalid point is an ``invalid`` row).

    Parameters
    ----------
    spec : SweepSpec
        The parsed sweep file.
    extra : iterable of str
        ``KEY=VALUE`` overrides from the command line, applied to every point after
        ``[set]``; they may not name an axis or explicit-point key.
    max_points : int, optional
        Refuse more points than this (default: the sweep file's ``max_points``).
    allow_external_paths : bool
        See :func:`recipsim.case.load.load_case`.

    Returns
    -------
    list of PlannedPoint
        In sweep order.

    Raises
    ------
    CaseError
        A sweep larger than the limit; an unknown or misplaced case key in the sweep
        (naming the sweep file and ``axes.KEY``, ``set.KEY`` or ``points[i].KEY``), or
        an invalid base case file.
    """
    spec.check_size(max_points)
    file = str(spec.path)
    varying = spec.varying_keys
    extra = list(extra)
    for text in extra:
        key = ".".join(parse_override(text)[0])
        if key in varying:
            raise CaseError("--set", key, f"is an axis of {file}; it cannot be set for all points")
    fixed = [override(k, v) for k, v in spec.fixed] + extra
    names = axis_column_names(varying)
    base_data = _read_base(spec, allow_external_paths)
    base_file = str(spec.base)
    refrigerant_text = _RefrigerantTexts(spec.base)
    explicit_checked: set[tuple[str, ...]] = set()
    planned: list[PlannedPoint] = []
    for point in spec.expand():
        overrides = tuple(fixed + [override(k, v) for k, v in point.values])
        keys = tuple(k for k, _ in point.values)
        if keys not in explicit_checked:  # the first point of each set of keys
            explicit_checked.add(keys)
            _check_keys(spec, overrides, point.values, extra, allow_external_paths)
        try:
            data = apply_overrides(base_data, list(overrides), base_file)
        except CaseError as exc:
            raise _sweep_key_error(spec, exc, point.values, extra) from None
        planned.append(
            PlannedPoint(
                index=point.index,
                point_id=point_id(data, refrigerant_text(data.get("refrigerant"))),
                overrides=overrides,
                columns={names[k]: axis_value(k, v, file) for k, v in point.values},
            )
        )
    return planned


def _check_keys(
    spec: SweepSpec,
    overrides: tuple[str, ...],
    values: tuple[tuple[str, Any], ...],
    extra: list[str],
    allow_external_paths: bool,
) -> None:
    """Build one point's case; raise a key error as an error of the sweep file.

    The case is built as the point will be (:func:`~.worker.point_case`: the base case
    read once per process, the overrides applied to it), with the same errors as
    :func:`~recipsim.case.load.load_case`.
    """
    try:
        point_case(str(spec.base), overrides, allow_external_paths)
    except CaseError as exc:
        if exc.message.startswith(_KEY_ERRORS):
            raise _sweep_key_error(spec, exc, values, extra) from None
        # an invalid value: the point (and any other like it) becomes an invalid row


def _sweep_key_error(
    spec: SweepSpec, exc: CaseError, values: tuple[tuple[str, Any], ...], extra: list[str]
) -> CaseError:
    """Turn a case error about a key into an error of the sweep file naming its entry."""
    keys = [k for k, _ in spec.fixed] + [k for k, _ in values]
    for key in keys:
        if exc.key == key or exc.key.startswith(key + ".") or key.startswith(exc.key + "."):
            return CaseError(
                str(spec.path), spec.source_of(key), f"{exc.message} (in the case {exc.file})"
            )
    for text in extra:
        key = ".".join(parse_override(text)[0])
        if exc.key == key or exc.key.startswith(key + ".") or key.startswith(exc.key + "."):
            return CaseError("--set", key, exc.message)
    return exc
