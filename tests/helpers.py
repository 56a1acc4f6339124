"""Paths of the shipped cases and a helper that runs a case (tests import it)."""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CASES = ROOT / "cases"
REFERENCE = CASES / "reference_r134a_lbp.toml"
SHIPPED = sorted(CASES.glob("*.toml"))


def solve_case(path: Path, overrides: list[str] | None = None):
    """Load, build and solve a case; returns the periodic solution."""
    from recipsim.case import load_case
    from recipsim.model import build_model
    from recipsim.solve.periodic import solve_periodic

    return solve_periodic(build_model(load_case(path, overrides or [])))
