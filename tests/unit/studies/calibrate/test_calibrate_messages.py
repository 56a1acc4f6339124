"""``recipsim calibrate`` names the real mistake before any fit: a unit in a header that
does not fit its values, kelvin in a degC column, a parameter key the case does not have,
an infinite bound, a target that no summary holds. (Without these checks every run of
the fit fails alike and the influence check blamed the parameter: "no influence".)"""

from __future__ import annotations

from pathlib import Path

import pytest

from helpers import REFERENCE
from recipsim.case.load import load_case
from recipsim.errors import CaseError, RecipsimError
from recipsim.studies.calibrate.fit import CalibrationError
from recipsim.studies.calibrate.run import calibrate_case

GOOD = (
    "evaporating_temperature [degC],condensing_temperature [degC],cooling_capacity [W]\n"
    "-25,55,68\n-20,55,89\n"
)
PARAMETER = ["valves.suction.preload=0 N:0.5 N"]


def _never(case: object) -> dict[str, float]:
    raise AssertionError("no simulation may run before the inputs are checked")


def _calibrate(tmp_path: Path, text: str, parameters=PARAMETER, targets=None):
    data = tmp_path / "data.csv"
    data.write_text(text)
    return calibrate_case(load_case(REFERENCE), data, parameters, targets=targets, simulate=_never)


@pytest.mark.parametrize(
    ("text", "words"),
    [
        (GOOD.replace("-25,55,68", "248.15,328.15,68"), r"row 1: .*evaporating_temperature"),
        (GOOD.replace("[degC],condensing", "[bar],condensing"), r"row 1: .*evaporating"),
    ],
)
def test_inputs_the_case_refuses_are_named_by_row_before_fitting(tmp_path, text, words) -> None:
    with pytest.raises(CaseError, match=words) as info:
        _calibrate(tmp_path, text)
    assert info.value.file.endswith("data.csv")


@pytest.mark.parametrize(
    ("parameters", "words"),
    [
        (["valves.suction.preloda=0 N:0.5 N"], "unknown key"),
        (["valves.suction.preload=0 N:inf N"], "finite"),
    ],
)
def test_a_parameter_key_typo_or_an_infinite_bound_is_named(tmp_path, parameters, words) -> None:
    with pytest.raises(CalibrationError, match=words):
        _calibrate(tmp_path, GOOD, parameters)


def test_a_target_no_summary_holds_is_named(tmp_path) -> None:
    text = GOOD.replace("cooling_capacity [W]", "cooling_capacity [kW]")
    with pytest.raises(CaseError, match="did you mean 'cooling_capacity \\[W\\]'"):
        _calibrate(tmp_path, text, targets=["cooling_capacity [kW]"])


def test_the_checks_pass_a_good_file_on_to_the_fit(tmp_path) -> None:
    with pytest.raises((AssertionError, RecipsimError), match="no simulation may run"):
        _calibrate(tmp_path, GOOD)


def test_a_parameter_the_data_cannot_determine_is_refused_after_the_fit(tmp_path) -> None:
    """The capacity moves by 0.15 % per e-fold of the parameter, under the catalogue's
    printed resolution (0.5 W of 68 W): one standard deviation would span 1.5 decades,
    so the fit is refused rather than reported with an interval over decades."""
    import math

    from recipsim.studies.calibrate.parameters import case_value

    def weak(case) -> dict[str, float]:
        preload = case_value(case, "valves.suction.preload")
        return {"cooling_capacity [W]": 68.0 * (1.0 + 0.0015 * math.log(preload / 0.1))}

    data = tmp_path / "data.csv"
    data.write_text(GOOD)
    case = load_case(REFERENCE)
    with pytest.raises(CalibrationError, match="do not determine valves.suction.preload"):
        calibrate_case(case, data, ["valves.suction.preload=0.01 N:1 N"], simulate=weak)
