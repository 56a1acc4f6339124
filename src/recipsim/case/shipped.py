"""What is shipped: every case, sweep and hard case file, with its kind and one line
describing it (``recipsim cases``, :func:`recipsim.cases`).

The files are those of the shipped ``cases/`` folder
(:func:`recipsim.case.files.shipped_dir`): the cases at its top, the sweep files in
``sweeps/`` and the hard cases in ``hard/`` (its ``expectations.toml`` is not a case). A
case or a sweep runs by its name (``recipsim run NAME``, ``recipsim sweep NAME``); the
hard cases run together (``recipsim check hard``).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from recipsim.case.files import read_toml, shipped_dir

if TYPE_CHECKING:
    import pandas as pd

#: The kinds of shipped file, each with its folder under ``cases/``, in listing order.
KIND_FOLDERS = {"case": "", "sweep": "sweeps", "hard case": "hard"}
#: Files of those folders that are not cases.
NOT_CASES = frozenset({"expectations.toml"})


@dataclass(frozen=True)
class ShippedCase:
    """One shipped case, sweep or hard case file.

    Attributes
    ----------
    name : str
        The file's stem: the name that runs it (``reference_r134a_lbp``).
    kind : str
        ``"case"``, ``"sweep"`` or ``"hard case"`` (:data:`KIND_FOLDERS`).
    description : str
        One line: the file's ``description``, else its first comment line.
    path : Path
        The file.
    """

    name: str
    kind: str
    description: str
    path: Path


def shipped_cases(kinds: tuple[str, ...] = tuple(KIND_FOLDERS)) -> list[ShippedCase]:
    """Every shipped file of the given kinds: by kind (cases, sweeps, hard cases), then
    by name.

    Parameters
    ----------
    kinds : tuple of str
        Any of :data:`KIND_FOLDERS`; default all.

    Raises
    ------
    ValueError
        An unknown kind.
    CaseError
        A shipped file that cannot be read (a broken installation).
    """
    unknown = [k for k in kinds if k not in KIND_FOLDERS]
    if unknown:
        raise ValueError(f"unknown kind {unknown[0]!r}; one of {list(KIND_FOLDERS)}")
    root = shipped_dir("cases")
    listed: list[ShippedCase] = []
    for kind, folder in KIND_FOLDERS.items():
        if kind not in kinds:
            continue
        for path in sorted((root / folder).glob("*.toml")):
            if path.name not in NOT_CASES:
                listed.append(ShippedCase(path.stem, kind, describe(path), path))
    return listed


def describe(path: Path) -> str:
    """One line describing a case or sweep file: its top-level ``description`` when it
    has one, else its first comment line (without ``#``), else ``""``."""
    data, text = read_toml(path, "case")
    description = data.get("description")
    if isinstance(description, str) and description.strip():
        return " ".join(description.split())
    for line in text.splitlines():
        if line.startswith("#") and line.strip("# \t"):
            return line.strip("# \t")
    return ""


def shipped_cases_table(kinds: tuple[str, ...] = tuple(KIND_FOLDERS)) -> pd.DataFrame:
    """:func:`shipped_cases` as a table: columns ``name``, ``kind``, ``description`` and
    ``path`` (a string), one row per file."""
    import pandas as pd

    rows = [
        {"name": c.name, "kind": c.kind, "description": c.description, "path": str(c.path)}
        for c in shipped_cases(kinds)
    ]
    return pd.DataFrame(rows, columns=["name", "kind", "description", "path"])
