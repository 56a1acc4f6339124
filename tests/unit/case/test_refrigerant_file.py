"""A refrigerant file is read through the shared schema (its top level:
:data:`recipsim.case.refrigerant.REFRIGERANT_SPEC`; its tables ``[limits]``,
``[rating_points.<name>]``, ``[envelope]``): a bad one names the file, the key and what
is allowed."""

from __future__ import annotations

import re

import pytest

from recipsim.case.refrigerant import read_refrigerant_file
from recipsim.errors import CaseError

GOOD = 'name = "R134a_x"\ncoolprop_name = "R134a"\n'


@pytest.mark.parametrize(
    ("text", "key", "allowed"),
    [
        ('name = "R134a_x"\n', "coolprop_name", "missing required key"),
        (GOOD + "colour = 1\n", "colour", "allowed: coolprop_name, description, envelope"),
        (GOOD + "description = 3\n", "description", "expected a string"),
        ('name = "x"\ncoolprop_name = "NoSuchFluid"\n', "coolprop_name", "does not know"),
        (GOOD + "[limits]\nmax_temperature = -5\n", "limits.max_temperature", "(0, inf] K"),
        (GOOD + "[envelope]\npressure_ratio_max = 0.5\n", "envelope.pressure_ratio_max", "(1,"),
        (
            GOOD + "[rating_points.lbp]\nevaporating_temperature = 50\n",
            "rating_points.lbp.evaporating_temperature",
            "[100, 600] K",
        ),
        (GOOD + "rating_points = 3\n", "rating_points", "expected tables"),
    ],
)
def test_a_bad_refrigerant_file_names_file_key_and_what_is_allowed(tmp_path, text, key, allowed):
    path = tmp_path / "R134a_x.toml"
    path.write_text(text)
    with pytest.raises(CaseError) as err:
        read_refrigerant_file(path)
    message = str(err.value)
    assert str(path) in message
    assert re.search(rf"(^|\s){re.escape(key)}:", message), message
    assert allowed in message


def test_a_good_refrigerant_file_reads(tmp_path):
    path = tmp_path / "R134a_x.toml"
    path.write_text(GOOD + '[limits]\nmax_temperature = "100 degC"\n')
    spec = read_refrigerant_file(path)
    assert spec.name == "R134a_x" and spec.description == ""
    assert spec.max_temperature == pytest.approx(373.15)
