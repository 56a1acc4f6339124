"""The case files of a check and what each is expected to do (``expectations.toml``).

Each case's expectation comes from ``expectations.toml`` beside the case files (a case
not listed there is expected to converge with closed balances): the expected outcome,
a regular expression its refusal or failure message must match, closure tolerances
(:mod:`recipsim.studies.check.metrics`), minimum values of cycle metrics (e.g. the number
of suction-valve openings of a fluttering reed) and extra ``--fast`` overrides.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from recipsim.case.files import read_toml
from recipsim.errors import CaseError
from recipsim.schema import (
    Choice,
    Field,
    FileSpec,
    Spec,
    Text,
    TextList,
    check_keys,
    read_table,
)
from recipsim.studies.check.metrics import METRICS

OUTCOMES = ("converged", "not_converged", "refused", "failed")
EXPECTATIONS_FILE = "expectations.toml"

#: Default closure tolerances [-] (see :mod:`recipsim.studies.check.metrics`).
MASS_TOLERANCE = 1e-3
ENERGY_TOLERANCE = 5e-3
DRIVE_TOLERANCE = 5e-3

#: ``--fast`` settings applied before the case's own fast overrides and ``--set``.
FAST_OVERRIDES = ("solver.rtol=1e-5", "solver.samples_per_revolution=360")


@dataclass(frozen=True)
class Expectation:
    """What a case is expected to do under ``recipsim check``.

    Attributes
    ----------
    expected : str
        One of :data:`OUTCOMES`.
    message : str
        Regular expression (case-insensitive search) that the message of a ``refused``
        or ``failed`` outcome must match; empty: any message.
    reason : str
        Why this is the expectation (documentation, copied to ``check.csv``).
    mass_tolerance, energy_tolerance, drive_tolerance : float
        Largest closures [-] accepted for a converged run.
    fast : tuple of str
        Extra ``KEY=VALUE`` overrides under ``--fast`` (after :data:`FAST_OVERRIDES`).
    minimum : mapping of str to float
        Lower bounds on cycle metrics
        (:data:`~recipsim.studies.check.metrics.METRICS`) of a converged run.
    """

    expected: str = "converged"
    message: str = ""
    reason: str = ""
    mass_tolerance: float = MASS_TOLERANCE
    energy_tolerance: float = ENERGY_TOLERANCE
    drive_tolerance: float = DRIVE_TOLERANCE
    fast: tuple[str, ...] = FAST_OVERRIDES
    minimum: Mapping[str, float] = field(default_factory=dict)


def find_cases(paths: Iterable[Path]) -> list[Path]:
    """Case files named by ``paths``: a directory gives its ``*.toml`` (sorted, without
    the expectations file), a file itself.

    Raises
    ------
    CaseError
        If a path does not exist or nothing is found.
    """
    files: list[Path] = []
    for path in map(Path, paths):
        if path.is_dir():
            files += sorted(p for p in path.glob("*.toml") if p.name != EXPECTATIONS_FILE)
        elif path.is_file():
            files.append(path)
        else:
            raise CaseError(str(path), "", "no such case file or directory")
    if not files:
        raise CaseError(", ".join(map(str, paths)), "", "no case files (*.toml) found")
    return files


#: The keys of ``[defaults]`` and ``[cases.<name>]``, read by
#: :func:`recipsim.schema.read_table` (a key a table leaves out keeps the value of
#: ``[defaults]``, then of :class:`Expectation`); the case-file reference prints them.
EXPECTATION_SPEC: FileSpec = {
    "expected": Choice(OUTCOMES, "converged", "the outcome the case must end with"),
    "message": Text(
        "",
        "regular expression (case-insensitive search) the message of a refused or failed "
        "run must match; empty: any message",
    ),
    "reason": Text("", "why this is the expectation (copied to check.csv)"),
    "mass_tolerance": Field(
        "dimensionless",
        MASS_TOLERANCE,
        lo=0.0,
        open_lo=True,
        doc="largest mass closure of a converged run, over the swept mass",
    ),
    "energy_tolerance": Field(
        "dimensionless",
        ENERGY_TOLERANCE,
        lo=0.0,
        open_lo=True,
        doc="largest energy closure of a converged run, over its isentropic work",
    ),
    "drive_tolerance": Field(
        "dimensionless",
        DRIVE_TOLERANCE,
        lo=0.0,
        open_lo=True,
        doc="largest drive closure (P_shaft = P_gas + P_bearings) of a converged run",
    ),
    "fast": TextList(
        (),
        "extra KEY=VALUE overrides under --fast, after solver.rtol=1e-5, "
        "solver.samples_per_revolution=360 and those of [defaults]",
    ),
}
#: ``minimum``: lower bounds on the metrics of a converged run, a sub-table.
MINIMUM_SPEC: Spec = {
    "suction_reed_openings": Field(
        "dimensionless", None, lo=0.0, doc="openings of the suction reed per revolution"
    ),
    "discharge_reed_openings": Field(
        "dimensionless", None, lo=0.0, doc="openings of the discharge reed per revolution"
    ),
    "volumetric_efficiency": Field(
        "dimensionless", None, lo=0.0, hi=2.0, doc="volumetric efficiency [-]"
    ),
}
_EXPECTATION_KEYS = {*EXPECTATION_SPEC, "minimum"}


def _expectation(raw: Any, base: Expectation, file: str, key: str) -> Expectation:
    """Validate one table of the expectations file on top of ``base``: the keys it gives
    replace ``base``'s; ``fast`` overrides accumulate."""
    if not isinstance(raw, dict):
        raise CaseError(file, key, "expected a table")
    check_keys(raw, _EXPECTATION_KEYS, file, key)
    scalars = {name: value for name, value in raw.items() if name != "minimum"}
    read = read_table(scalars, EXPECTATION_SPEC, file, key)
    values: dict[str, Any] = {name: read[name] for name in scalars}
    if "message" in values:
        try:
            re.compile(values["message"])
        except re.error as exc:
            raise CaseError(file, f"{key}.message", f"not a regular expression: {exc}") from None
    if "fast" in values:
        values["fast"] = base.fast + values["fast"]
    if "minimum" in raw:
        where = f"{key}.minimum"
        if not isinstance(raw["minimum"], dict):
            raise CaseError(file, where, f"expected a table of metrics {METRICS}")
        bounds = read_table(raw["minimum"], MINIMUM_SPEC, file, where)
        values["minimum"] = {m: float(bounds[m]) for m in raw["minimum"]}
    return replace(base, **values)


def load_expectations(path: Path) -> tuple[Expectation, dict[str, Expectation]]:
    """Read an expectations file: ``[defaults]`` and ``[cases.<case file stem>]`` tables.

    Returns
    -------
    default : Expectation
        For cases the file does not list.
    cases : dict
        Case file stem -> expectation.

    Raises
    ------
    CaseError
        Naming the file and key of anything invalid, including a ``[cases.<name>]``
        with no ``<name>.toml`` beside the file.
    """
    raw, _ = read_toml(path, "expectations")
    file = str(path)
    check_keys(raw, {"defaults", "cases"}, file, "")
    default = _expectation(raw.get("defaults", {}), Expectation(), file, "defaults")
    cases: dict[str, Expectation] = {}
    table = raw.get("cases", {})
    if not isinstance(table, dict):
        raise CaseError(file, "cases", "expected a table of [cases.<case name>] tables")
    for name, value in table.items():
        if not (path.parent / f"{name}.toml").is_file():
            raise CaseError(file, f"cases.{name}", f"no case file {name}.toml beside this file")
        cases[name] = _expectation(value, default, file, f"cases.{name}")
    return default, cases


def expectations_for(
    files: Sequence[Path], expectations_file: Path | None = None
) -> list[Expectation]:
    """The expectation of each case file: from ``expectations_file`` if given, otherwise
    from the ``expectations.toml`` beside each case (default: converge, closed balances).
    """
    loaded: dict[Path, tuple[Expectation, dict[str, Expectation]]] = {}
    out = []
    for file in files:
        source = expectations_file or file.parent / EXPECTATIONS_FILE
        if source not in loaded:
            missing = expectations_file is None and not source.is_file()
            loaded[source] = (Expectation(), {}) if missing else load_expectations(source)
        default, cases = loaded[source]
        out.append(cases.get(file.stem, default))
    return out
