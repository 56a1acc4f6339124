"""The mean friction's terms beside the journals and the skirt: the thrust bearing, the
oil pump and the small-end pin against their closed forms; the films at the thermal
network's oil temperature through the oil's law; refrigerant dilution by its mixing
rule; a zero film refused; and the energy bookkeeping (friction is the sum of its
terms, and the electrical power of a lossless motor rises by exactly the friction
added)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from helpers import REFERENCE
from recipsim.api import load_case, simulate
from recipsim.errors import CaseError
from recipsim.physics.lubricant import DEFAULT_OIL, diluted_viscosity
from recipsim.physics.mean_friction import (
    oil_pump_power,
    thrust_ball_torque,
    thrust_collar_torque,
)
from recipsim.results.electrical import mean_friction_columns

_TERMS = ("friction_power_", "piston_friction_power")


def test_collar_torque_is_the_annulus_shear_integral() -> None:
    """T = pi mu w (R_o^4 - R_i^4) / (2 h) against the shear mu w r / h integrated over
    the annulus by quadrature (an independent evaluation: 1e-10 relative); the torque
    doubles when the film halves."""
    mu, w, h, d_i, d_o = 4.6e-3, 300.0, 10e-6, 0.016, 0.026
    shear, _ = quad(lambda r: mu * w * r / h * r * 2.0 * math.pi * r, d_i / 2, d_o / 2)
    torque = float(thrust_collar_torque(mu, d_i, d_o, h, np.array([w]))[0])
    assert torque == pytest.approx(shear, rel=1e-10)
    half = float(thrust_collar_torque(mu, d_i, d_o, h / 2, np.array([w]))[0])
    assert half == pytest.approx(2.0 * torque, rel=1e-14)


@pytest.mark.parametrize("film", [0.0, -1e-6])
def test_a_collar_without_a_film_is_refused(film: float) -> None:
    with pytest.raises(ValueError, match="film thickness"):
        thrust_collar_torque(4.6e-3, 0.016, 0.026, film, np.array([300.0]))
    with pytest.raises(CaseError, match=r"friction\.thrust_film_thickness"):
        load_case("tles5.7kk3_r600a", {"friction.thrust_film_thickness": film})


def test_thrust_outer_diameter_must_exceed_the_inner() -> None:
    with pytest.raises(CaseError, match=r"friction\.thrust_outer_diameter"):
        load_case("tles5.7kk3_r600a", {"friction.thrust_outer_diameter": "15 mm"})


def test_ball_thrust_and_oil_pump_by_hand() -> None:
    """SKF's M = mu F d / 2 and Euler's rho Q (w^2 r^2 + g H), evaluated by hand."""
    assert thrust_ball_torque(0.0013, 8.83, 0.021) == pytest.approx(
        0.5 * 0.0013 * 8.83 * 0.021, rel=1e-15
    )
    power = oil_pump_power(860.0, 1e-6, np.array([300.0]), 0.005, 0.06)
    assert float(power[0]) == pytest.approx(860e-6 * (300.0**2 * 0.005**2 + 9.80665 * 0.06))


def test_dilution_follows_the_logarithmic_rule_in_mole_fractions() -> None:
    """No refrigerant: the oil; 5 % R600a (58.12 g/mol) in a 0.30 kg/mol oil is a mole
    fraction 0.214 by hand, and the mixture's viscosity mu_o^(1-x) mu_r^x; more
    refrigerant, thinner oil."""
    mu_o, mu_r = 3.7e-3, 0.1e-3
    assert diluted_viscosity(mu_o, mu_r, 0.0, 0.30, 0.05812) == mu_o
    x = (0.05 / 0.05812) / (0.05 / 0.05812 + 0.95 / 0.30)
    assert x == pytest.approx(0.2137, abs=1e-4)
    expected = mu_o ** (1.0 - x) * mu_r**x
    assert diluted_viscosity(mu_o, mu_r, 0.05, 0.30, 0.05812) == pytest.approx(expected)
    assert diluted_viscosity(mu_o, mu_r, 0.10, 0.30, 0.05812) < expected
    with pytest.raises(ValueError, match="mass fraction"):
        diluted_viscosity(mu_o, mu_r, 1.0, 0.30, 0.05812)


@pytest.fixture(scope="module")
def reference_mean():
    """The reference cycle (rigid crank, constant speed, no network) with mean friction
    and the pin's film; and its cycle table."""
    case = load_case(
        REFERENCE,
        {
            "options.friction": "mean",
            "bearings.pin.diameter": "6 mm",
            "bearings.pin.length": "9 mm",
            "bearings.pin.radial_clearance": "5 um",
        },
    )
    result = simulate(case)
    return case, result


def test_pin_and_thrust_at_the_fixed_film_temperature(reference_mean) -> None:
    """Without the network every film is at oil.film_temperature (60 C): the thrust
    collar's power T w at the reference speed and the pin's Petroff at the rod's swing
    (rod angle by central finite differences of asin, 1e-6 rad) by hand: 1e-8
    relative."""
    case, result = reference_mean
    row = result.summary
    mu = DEFAULT_OIL.viscosity(333.15)
    w = case.operating_point.shaft_speed
    thrust = math.pi * mu * w**2 * (0.013**4 - 0.008**4) / (2.0 * 10e-6)
    assert row["friction_power_thrust [W]"] == pytest.approx(thrust, rel=1e-9)
    cycle = result.cycle
    theta = np.radians(cycle["crank_angle [deg]"].to_numpy())
    lam = case.geometry.crank_radius / case.geometry.connecting_rod_length
    h = 1e-6
    dphi = (-np.arcsin(lam * np.sin(theta + h)) + np.arcsin(lam * np.sin(theta - h))) / (2 * h)
    pin = 2 * math.pi * mu * 0.003**3 * 0.009 * w**2 / 5e-6 * np.mean(dphi**2)
    assert row["friction_power_pin [W]"] == pytest.approx(pin, rel=1e-8)
    assert row["friction_film_temperature [K]"] == 333.15
    assert row["friction_film_viscosity [Pa*s]"] == mu


def test_friction_is_the_sum_of_its_terms_and_reaches_the_socket(reference_mean) -> None:
    """friction_power is the sum of its terms (rounding); with a lossless motor and no
    network the gas cycle does not see the mean friction, so the electrical power rises
    by exactly the friction over the frictionless run, and by exactly the thrust
    bearing's power when the thrust bearing is added (1e-9 relative: the same cycle)."""
    case, result = reference_mean
    row = result.summary
    terms = [v for k, v in row.items() if k.startswith(_TERMS) and k != "friction_power [W]"]
    assert len(terms) == 7  # four journals, the skirt, the thrust bearing, the pump
    assert row["friction_power [W]"] == pytest.approx(sum(terms), rel=1e-15)
    off = simulate(case.with_({"options.friction": "off"})).summary
    rise = row["motor_electrical_power [W]"] - off["motor_electrical_power [W]"]
    assert rise == pytest.approx(row["friction_power [W]"], rel=1e-9)
    none = simulate(case.with_({"friction.thrust_bearing": "none"})).summary
    assert "friction_power_thrust [W]" not in none
    rise = row["motor_electrical_power [W]"] - none["motor_electrical_power [W]"]
    assert rise == pytest.approx(row["friction_power_thrust [W]"], rel=1e-9)


@pytest.fixture(scope="module")
def tles():
    result = simulate(load_case("tles5.7kk3_r600a"))
    return result


def test_films_at_the_network_oil_temperature(tles) -> None:
    """With the thermal network the films are at the oil node's temperature (the one of
    the network solution the last revolution ran with: within 0.05 K of the reported
    node, the cycle's convergence), at the oil's Walther viscosity there (exact), and
    every journal is Petroff at that viscosity (1e-12: the same formula); the friction
    the network took as a heat source is the summary's (exact: the same temperature)."""
    row = tles.summary
    t = row["friction_film_temperature [K]"]
    assert t == pytest.approx(row["node_temperature_oil [K]"], abs=0.05)
    assert t > 333.15 + 5.0  # the network's oil runs warmer than the fixed 60 C here
    mu = row["friction_film_viscosity [Pa*s]"]
    assert mu == DEFAULT_OIL.viscosity(t)
    case = tles.case
    fixed = mean_friction_columns(case, {k: tles.cycle[k].to_numpy() for k in tles.cycle})
    at_t = mean_friction_columns(
        case, {k: tles.cycle[k].to_numpy() for k in tles.cycle}, oil_temperature=t
    )
    ratio = mu / DEFAULT_OIL.viscosity(333.15)
    for name in ("primary", "secondary", "eccentric", "pin"):
        column = f"friction_power_{name} [W]"
        assert row[column] == pytest.approx(at_t[column], rel=1e-12)
        assert at_t[column] == pytest.approx(fixed[column] * ratio, rel=1e-12)
    loads = tles.solution.model.thermal.last_loads
    assert loads.friction_power == pytest.approx(row["friction_power [W]"], rel=1e-6)


def test_dilution_lowers_the_network_friction(tles) -> None:
    """5 % R600a dissolved: thinner films, less friction at the same oil temperature."""
    case = tles.case.with_({"oil.dissolved_refrigerant_fraction": 0.05})
    cycle = {k: tles.cycle[k].to_numpy() for k in tles.cycle}
    t = tles.summary["friction_film_temperature [K]"]
    diluted = mean_friction_columns(case, cycle, oil_temperature=t)
    pure = mean_friction_columns(tles.case, cycle, oil_temperature=t)
    assert diluted["friction_power_primary [W]"] < 0.8 * pure["friction_power_primary [W]"]
