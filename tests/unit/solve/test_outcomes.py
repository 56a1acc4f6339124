"""Named outcomes of a run (issue 18): stall and period-n detection, the envelope's
refusal, zero delivery with honest closures, library errors turned into messages."""

import math

import numpy as np
import pytest

from recipsim.api import load_case, simulate
from recipsim.case.envelope import OutsideEnvelopeError, check_envelope, envelope_refusal
from recipsim.results.outcome import PropertyEvaluationError, explained, state_or_explain
from recipsim.solve.periodic import stalled, subharmonic_period


def test_a_residual_that_stops_halving_over_the_window_has_stalled():
    decaying = [0.5**k for k in range(20)]
    assert not stalled(decaying)
    flat = [0.5**k for k in range(6)] + [2e-3 * (1 + 0.3 * (-1) ** k) for k in range(10)]
    assert stalled(flat)
    assert not stalled(flat[:8])  # too short to tell


@pytest.mark.parametrize("n", [2, 3, 4])
def test_end_states_that_repeat_every_n_revolutions_give_period_n(n):
    """A state cycling through n values 10 % apart repeats after n revolutions exactly,
    never after fewer: the detector must return n (and 1 for a settled state)."""
    ref = np.array([1.0, 1.0, 0.0])  # the third entry is not judged
    ends = [np.array([1.0 + 0.1 * (k % n), 2.0, float(k)]) for k in range(12)]
    assert subharmonic_period(ends, ref, 1e-4) == n
    settled = [np.array([1.0, 2.0, float(k)]) for k in range(12)]
    assert subharmonic_period(settled, ref, 1e-4) == 1
    drifting = [np.array([1.0 + 0.01 * k, 2.0, 0.0]) for k in range(12)]
    assert subharmonic_period(drifting, ref, 1e-4) == 1


def test_a_point_beyond_the_envelope_is_refused_in_one_line():
    case = load_case("reference_r134a_lbp", {"operating_point.condensing_temperature": "75 degC"})
    message = envelope_refusal(case)
    assert message is not None and "\n" not in message
    assert "condensing temperature 75.0 C is above the maximum 70.0 C" in message
    with pytest.raises(OutsideEnvelopeError):
        simulate(case)
    check_envelope(case.with_("solver.envelope=ignore"))  # runs anyway: no refusal
    assert envelope_refusal(load_case("reference_r134a_lbp")) is None


def test_zero_delivery_is_named_with_consistent_closures():
    """R600a at ASHRAE LBP with 15 % clearance: the re-expanding gas fills the stroke, no
    valve opens. Before issue 18 this was 'converged' with mass residual NaN and energy
    residual 1.0; the cycle is a closed adiabatic one, so both closures must be ~0
    (1e-6 asserted: the integrator's error on the gross p dV work)."""
    result = simulate(load_case("r600a_lbp", {"geometry.clearance_ratio": 0.15}))
    s = result.summary
    assert s["status"] == "no_delivery" and "NaN by design" in s["status_message"]
    assert s["volumetric_efficiency [-]"] == 0.0
    assert math.isnan(s["discharge_temperature [K]"]) and math.isnan(s["COP [-]"])
    assert abs(s["mass_balance_residual [-]"]) < 1e-6
    assert abs(s["energy_balance_residual [-]"]) < 1e-6


def test_a_converged_ordinary_point_is_ok():
    s = simulate(load_case("reference_r134a_lbp")).summary
    assert s["status"] == "ok" and s["status_message"] == ""


def test_a_failed_property_evaluation_names_the_quantity_and_the_state():
    case = load_case("reference_r134a_lbp", {"options.properties": "heos"})
    from recipsim.case.refrigerant import case_fluid

    fluid = case_fluid(case.refrigerant, "heos")
    with pytest.raises(PropertyEvaluationError) as info:
        state_or_explain(fluid, "ph", 1.2e6, -5e6, "the discharge temperature")
    text = str(info.value)
    assert text.startswith("CoolProp: no state at p = 1.2 MPa, h = -5e+06 J/kg")
    assert "while computing the discharge temperature" in text
    with pytest.raises(PropertyEvaluationError, match="ZeroDivisionError while post-processing"):
        with explained("post-processing"):
            _ = 1.0 / 0.0
