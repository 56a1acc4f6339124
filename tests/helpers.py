"""Paths of the shipped cases and a helper that runs a case (tests import it)."""

from __future__ import annotations

import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CASES = ROOT / "src" / "recipsim" / "data" / "cases"
REFERENCE = CASES / "reference_r134a_lbp.toml"
ALL_CASES = sorted(CASES.glob("*.toml"))


def _options(path: Path) -> dict:
    """The [options] of a case file, following ``extends``."""
    with path.open("rb") as fh:
        raw = tomllib.load(fh)
    parent = raw.get("extends")
    if parent and not parent.endswith(".toml"):  # a shipped case by name
        parent = str(CASES / f"{parent}.toml")
    base = _options(path.parent / parent) if parent else {}
    return {**base, **raw.get("options", {})}


def _scene(path: Path) -> tuple[str, str]:
    opts = _options(path)
    return opts.get("pressure", "cylinder"), opts.get("mechanics", "pinned")


#: The shipped cases of the CoolProp cylinder on the rigid crank.
SHIPPED = [p for p in ALL_CASES if _scene(p) == ("cylinder", "pinned")]
#: The shipped coupled cases (cylinder + flexible crank train).
COUPLED = [p for p in ALL_CASES if _scene(p) == ("cylinder", "flexible")]
#: The shipped cases driven by a tabulated pressure curve.
TABULATED = [p for p in ALL_CASES if _scene(p)[0] == "tabulated"]


def solve_case(path: Path, overrides: list[str] | None = None):
    """Load, build and solve a case; returns the periodic solution."""
    from recipsim.case.load import load_case
    from recipsim.solve.drive import build_model_for
    from recipsim.solve.periodic import solve_periodic

    return solve_periodic(build_model_for(load_case(path, overrides or [])))
