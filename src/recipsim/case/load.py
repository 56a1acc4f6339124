"""Load and validate a case file into frozen dataclasses, in SI.

A case is one TOML file: refrigerant, operating point, geometry, valves, leakage,
heat transfer, mechanism data, an ``[options]`` table with one entry per submodel
slot and a ``[solver]`` table. ``--set KEY=VALUE`` overrides are applied to the raw
TOML data before validation, so they are checked exactly like the file itself.
Everything that can be checked before integrating is checked: ranges, unknown
keys, unknown refrigerant, a suction state inside the two-phase dome, condensing
below evaporating.

This module holds :func:`load_case`; the work is done by modules of one job each, whose
public names it re-exports so that ``from recipsim.case.load import ...`` keeps working:

* :mod:`.case_schema`: the declared keys of the case's own tables (``OPTION_SPEC``, ...);
* :mod:`.sections`: the sections' dataclasses (``Options``, ``OperatingPoint``, ...);
* :mod:`.case`: :class:`Case` and :func:`case_from_dict`;
* :mod:`.build`: one builder per table; :mod:`.operating_point`: ``[operating_point]``;
* :mod:`.consistency`: the checks across sections;
* :mod:`.overrides`: ``--set`` overrides; :mod:`.extends`: ``extends`` and shipped cases.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import replace
from pathlib import Path
from typing import Any

from recipsim.case.case import Case, case_from_dict
from recipsim.case.case_schema import (
    GEOMETRY_SPEC,
    HEADER_SPEC,
    HEAT_TRANSFER_SPEC,
    LEAKAGE_SPEC,
    OPERATING_POINT_SPEC,
    OPTION_SPEC,
    PRESSURE_CURVE_SPEC,
    SOLVER_SPEC,
    TOP_KEYS,
    VALVE_SPEC,
    VALVES_TOP_SPEC,
)
from recipsim.case.extends import resolve_extends, shipped_case
from recipsim.case.files import read_toml
from recipsim.case.overrides import (
    apply_overrides,
    blamed_on_override,
    override,
    override_texts,
    parse_override,
    toml_literal,
)
from recipsim.case.sections import (
    Geometry,
    HeatTransfer,
    Leakage,
    OperatingPoint,
    Options,
    SolverSettings,
    Valves,
    ValveSpec,
)
from recipsim.errors import CaseError


def load_case(
    path: str | Path,
    overrides: Mapping[str, Any] | Sequence[str] | None = None,
    *,
    allow_external_paths: bool = False,
) -> Case:
    """Read, override and validate a case file.

    Parameters
    ----------
    path : str or Path
        The TOML case file, or the name of a case (``"reference_r134a_lbp"``): the
        working directory's ``cases/<name>.toml``, else the shipped case of that name.
    overrides : mapping or list of str, optional
        Dotted case keys to values (``{"operating_point.shaft_speed": "3000 rpm"}``), or
        ``KEY=VALUE`` strings as on the command line (``--set``); validated exactly like
        the file.
    allow_external_paths : bool
        Let ``extends`` and ``pressure_curve.file`` name files outside the case file's
        directory (absolute paths, ``..``); by default only files beside the case, below
        it, or shipped cases by name are read.

    Returns
    -------
    Case

    Raises
    ------
    CaseError
        With the file, the key and what is allowed.
    """
    file, texts, raw, text = _overridden_raw(path, overrides, allow_external_paths)
    try:
        case = case_from_dict(raw, file, text, allow_external_paths=allow_external_paths)
    except CaseError as exc:
        raise blamed_on_override(exc, texts) from None
    return replace(case, overrides=tuple(texts), allow_external_paths=allow_external_paths)


def _overridden_raw(
    path: str | Path,
    overrides: Mapping[str, Any] | Sequence[str] | None,
    allow_external_paths: bool,
) -> tuple[str, list[str], dict[str, Any], str]:
    """A case file's raw data with its ``extends`` resolved and ``overrides`` applied:
    ``(file, override texts, data, the file's text)``."""
    path = shipped_case(path)
    file = str(path)
    texts = override_texts(overrides)
    raw, text = read_toml(path, "case")
    raw = resolve_extends(raw, path, [path.resolve()], allow_external_paths)
    return file, texts, apply_overrides(raw, texts, file), text


__all__ = [
    "GEOMETRY_SPEC",
    "HEADER_SPEC",
    "HEAT_TRANSFER_SPEC",
    "LEAKAGE_SPEC",
    "OPERATING_POINT_SPEC",
    "OPTION_SPEC",
    "PRESSURE_CURVE_SPEC",
    "SOLVER_SPEC",
    "TOP_KEYS",
    "VALVES_TOP_SPEC",
    "VALVE_SPEC",
    "Case",
    "Geometry",
    "HeatTransfer",
    "Leakage",
    "OperatingPoint",
    "Options",
    "SolverSettings",
    "ValveSpec",
    "Valves",
    "apply_overrides",
    "case_from_dict",
    "load_case",
    "override",
    "override_texts",
    "parse_override",
    "read_toml",
    "resolve_extends",
    "shipped_case",
    "toml_literal",
]
