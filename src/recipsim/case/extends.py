"""``extends``: a case file built on another one (a file beside it, or a case by name:
the working directory's ``cases/`` or a shipped case), and the case a bare name stands
for.
"""

from __future__ import annotations

import copy
from pathlib import Path
from typing import Any

from recipsim.case.case_schema import drop_replaced_alternatives
from recipsim.case.files import MAX_EXTENDS_DEPTH, find_case_file, read_toml, resolve_reference
from recipsim.errors import CaseError


def shipped_case(path: str | Path) -> Path:
    """``path`` itself, or the case a bare name means: ``./cases/<name>.toml`` of the
    working directory, else the shipped case (:func:`recipsim.case.files.find_case_file`).

    Raises
    ------
    CaseError
        A bare name that is neither a file nor a case name, with the closest names.
    """
    return find_case_file(path)


def _deep_merge(base: dict[str, Any], child: dict[str, Any]) -> dict[str, Any]:
    out = copy.deepcopy(base)
    for key, value in child.items():
        if isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = _deep_merge(out[key], value)
        else:
            out[key] = copy.deepcopy(value)
    return out


def resolve_extends(
    raw: dict[str, Any], path: Path, chain: list[Path], allow_external: bool = False
) -> dict[str, Any]:
    """Merge the case named by ``extends`` under this one.

    ``extends`` names a file beside this one (``"base.toml"``) or a shipped case by
    name (``"reference_r134a_lbp"``), see :func:`recipsim.case.files.resolve_reference`.
    ``name`` and ``description`` are not inherited: a case's name defaults to its
    file name.
    """
    parent_name = raw.pop("extends", None)
    if parent_name is None:
        return raw
    if len(chain) > MAX_EXTENDS_DEPTH:
        raise CaseError(
            str(path), "extends", f"chain of extends deeper than {MAX_EXTENDS_DEPTH} files"
        )
    parent = resolve_reference(
        parent_name, str(path), "extends", "case file", allow_external, by_name=True
    )
    if parent in chain:
        raise CaseError(str(path), "extends", f"circular extends through {parent.name}")
    base, _ = read_toml(parent, "case")
    curve = base.get("pressure_curve")
    if isinstance(curve, dict) and isinstance(curve.get("file"), str):
        # a file named in the base case is relative to the base case, not to this one:
        # resolved (and checked) here, where the base case is known
        curve["file"] = str(
            resolve_reference(
                curve["file"],
                str(parent),
                "pressure_curve.file",
                "pressure curve",
                allow_external,
            )
        )
    base = resolve_extends(base, parent, chain + [parent], allow_external)
    base.pop("name", None)
    base.pop("description", None)
    merged = _deep_merge(base, raw)
    drop_replaced_alternatives(merged, raw)
    return merged
