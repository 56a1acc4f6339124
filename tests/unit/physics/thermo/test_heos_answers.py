"""HEOS's liquid-line answers kept on disk (recipsim.physics.thermo.heos_answers): kept bit
for bit, a damaged file ignored and replaced, and a warm R744 run that no longer imports
CoolProp for its gas-cooler exit."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from helpers import REFERENCE
from recipsim.physics.thermo.heos_answers import MOST_ANSWERS, HeosAnswers


@pytest.fixture
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("RECIPSIM_CACHE", str(tmp_path))
    return tmp_path


def _never() -> float:
    raise AssertionError("HEOS asked for a kept answer")


def test_an_answer_is_kept_bit_for_bit(cache):
    value = 0.1 + 0.2  # not the float nearest 0.3: the round trip must be exact
    assert HeosAnswers("CO2").answer("liquid_enthalpy", (9e6, 308.15), lambda: value) == value
    again = HeosAnswers("CO2")  # a new process reads the file
    assert again.remembered("liquid_enthalpy", (9e6, 308.15))
    assert again.answer("liquid_enthalpy", (9e6, 308.15), _never) == value
    # another question, other inputs or another fluid are other answers
    assert not again.remembered("saturated_liquid_enthalpy", (9e6, 308.15))
    assert not again.remembered("liquid_enthalpy", (9e6, 308.16))
    assert not HeosAnswers("R744x").remembered("liquid_enthalpy", (9e6, 308.15))


@pytest.mark.parametrize(
    "text", ["not json", "[1, 2]", '{"liquid_enthalpy(1.0)": "2"}', '{"q(1.0)": NaN}']
)
def test_a_damaged_file_is_ignored_and_replaced(cache, text):
    answers = HeosAnswers("CO2")
    answers.path.parent.mkdir(parents=True)
    answers.path.write_text(text)
    assert answers.answer("q", (1.0,), lambda: 2.5) == 2.5
    assert json.loads(answers.path.read_text()) == {"q(1.0)": 2.5}


def test_at_most_so_many_answers_are_kept(cache, monkeypatch):
    monkeypatch.setattr("recipsim.physics.thermo.heos_answers.MOST_ANSWERS", 3)
    answers = HeosAnswers("CO2")
    for k in range(5):
        assert answers.answer("q", (float(k),), lambda k=k: 10.0 + k) == 10.0 + k
    assert len(json.loads(answers.path.read_text())) == 3
    assert MOST_ANSWERS >= 1000  # a sweep over gas-cooler exits keeps its points


def test_an_unwritable_cache_only_costs_the_evaluation(tmp_path, monkeypatch):
    blocked = tmp_path / "file"
    blocked.write_text("")
    monkeypatch.setenv("RECIPSIM_CACHE", str(blocked))
    assert HeosAnswers("CO2").answer("q", (1.0,), lambda: 4.0) == 4.0


def test_a_warm_r744_run_does_not_import_coolprop():
    """The transcritical case's gas-cooler exit (the only question its run asks HEOS):
    answered from the disk on the second run, which then never imports CoolProp."""
    case = REFERENCE.parent / "r744_transcritical.toml"
    script = f"""
import json, sys
from recipsim.pipeline import simulate_case
from recipsim.case.load import load_case
run = simulate_case(load_case({str(case)!r}))
print(json.dumps(["CoolProp" in sys.modules, run.row["cooling_capacity [W]"]]))
"""
    runs = [
        json.loads(
            subprocess.run(
                [sys.executable, "-c", script], capture_output=True, text=True, check=True
            )
            .stdout.strip()
            .splitlines()[-1]
        )
        for _ in range(2)
    ]
    assert runs[1][0] is False
    assert runs[1][1] == runs[0][1]  # the same capacity, to the bit
