"""The rotor counterweight's case keys: a zero mass (a sweep's first point) is the rotor
without a counterweight; placement keys without a mass are refused, naming the key."""

from __future__ import annotations

import pytest

from recipsim.case.load import load_case
from recipsim.errors import CaseError

LUBRICATED = "reference_r134a_lbp_lubricated"


def test_zero_counterweight_mass_is_no_counterweight() -> None:
    shipped = load_case(LUBRICATED).mechanism.rotor
    assert shipped.counterweight_mass == pytest.approx(0.032)
    assert shipped.counterweight_radius == pytest.approx(0.012)
    zero = load_case(LUBRICATED, {"mechanism.rotor.counterweight_mass": "0 g"}).mechanism.rotor
    plain = load_case("reference_r134a_lbp_coupled").mechanism.rotor
    assert zero == plain  # the placement keys are checked, nothing is added


def test_counterweight_keys_are_validated_even_at_zero_mass() -> None:
    with pytest.raises(CaseError, match=r"mechanism\.rotor\.counterweight_radius.*> 0"):
        load_case(
            LUBRICATED,
            {
                "mechanism.rotor.counterweight_mass": "0 g",
                "mechanism.rotor.counterweight_radius": "-1 mm",
            },
        )


def test_placement_without_a_mass_is_refused() -> None:
    with pytest.raises(
        CaseError, match=r"mechanism\.rotor\.counterweight_angle: needs counterweight_mass"
    ):
        load_case("reference_r134a_lbp_coupled", {"mechanism.rotor.counterweight_angle": "90 deg"})
