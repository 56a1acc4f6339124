"""Paths of the shipped cases and a helper that runs a case (tests import it)."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
CASES = ROOT / "cases"
#: The shipped refrigerant files.
REFRIGERANTS = ROOT / "refrigerants"
#: The reference compressor as an ideal machine (adiabatic, no leakage, friction or motor
#: losses): the ideal-cycle, closure and pinned-number tests run it.
REFERENCE = CASES / "reference_r134a_lbp_ideal.toml"
#: The reference compressor with every loss on (motor, friction, shell, leakage, heat).
REFERENCE_REAL = CASES / "reference_r134a_lbp.toml"
ALL_CASES = sorted(CASES.glob("*.toml"))
#: Overrides that take a real case (``reference_r134a_lbp`` and the cases extending it) to
#: the ideal machine of ``reference_r134a_lbp_ideal``; no-ops on an ideal case.
LOSSES_OFF = [
    "options.motor=lossless",
    "options.friction=off",
    "options.thermal=fixed_wall",
    "options.speed=case",
    "options.heat_transfer=adiabatic",
    "options.leakage=none",
]


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


# ---- hostile-input tests: sentinels around --out, one-line errors -------------------


class Sandbox:
    """Sentinels beside and above ``out``, another report inside it, inputs apart."""

    def __init__(self, root: Path) -> None:
        self.root = root
        self.work = root / "work"
        self.out = self.work / "out"
        self.inputs = root / "inputs"
        self.inputs.mkdir(exist_ok=True)
        (self.out / "other_report").mkdir(parents=True)
        (root / "above.txt").write_text("above")
        (self.work / "beside.txt").write_text("beside")
        (self.out / "other_report" / "keep.csv").write_text("a,b\n1,2\n")
        self.before = self.snapshot()

    def snapshot(self) -> dict[str, bytes]:
        """Every file but the inputs and the outputs recipsim may write into ``out``."""
        files = {}
        for path in sorted(self.root.rglob("*")):
            if not path.is_file() or path.is_relative_to(self.inputs):
                continue
            if path.is_relative_to(self.out) and not path.is_relative_to(self.out / "other_report"):
                continue
            files[str(path.relative_to(self.root))] = path.read_bytes()
        return files

    def unchanged(self) -> bool:
        """Nothing outside ``out`` (and nothing of another report inside it) changed."""
        return self.snapshot() == self.before

    def case(self, text: str, name: str = "case.toml") -> Path:
        """Write an input file (a case, by default) into the inputs directory."""
        path = self.inputs / name
        path.write_text(text)
        return path


def one_line_error(capsys: pytest.CaptureFixture[str]) -> str:
    err = capsys.readouterr().err.strip()
    assert "Traceback" not in err
    assert err.count("\n") == 0, err
    assert err.startswith("recipsim:"), err
    return err


def stored_points(points: Path) -> dict[str, bytes]:
    """The records in a sweep's ``points/`` directory by point id, each the line its
    segment holds (of a point saved twice the later, by ``saved_ns``; a line cut short
    is left out)."""
    import json

    found: dict[str, tuple[int, bytes]] = {}
    for segment in sorted(points.glob("*.jsonl")):
        for line in segment.read_bytes().splitlines():
            try:
                record = json.loads(line)
            except ValueError:
                continue
            saved = record["saved_ns"]
            if record["point_id"] not in found or found[record["point_id"]][0] <= saved:
                found[record["point_id"]] = (saved, line)
    return {pid: line for pid, (_, line) in found.items()}
