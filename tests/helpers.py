"""Paths of the shipped cases and a helper that runs a case (tests import it)."""

from __future__ import annotations

import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CASES = ROOT / "cases"
REFERENCE = CASES / "reference_r134a_lbp.toml"
ALL_CASES = sorted(CASES.glob("*.toml"))


def _pressure_source(path: Path) -> str:
    with path.open("rb") as fh:
        return tomllib.load(fh).get("options", {}).get("pressure", "cylinder")


#: The shipped cases whose pressure comes from the CoolProp cylinder.
SHIPPED = [p for p in ALL_CASES if _pressure_source(p) == "cylinder"]
#: The shipped cases driven by a tabulated pressure curve.
TABULATED = [p for p in ALL_CASES if _pressure_source(p) == "tabulated"]


def solve_case(path: Path, overrides: list[str] | None = None):
    """Load, build and solve a case; returns the periodic solution."""
    from recipsim.case import load_case
    from recipsim.model import build_model
    from recipsim.solve.periodic import solve_periodic

    return solve_periodic(build_model(load_case(path, overrides or [])))
