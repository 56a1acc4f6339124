"""What the suction side costs, and the suction path as heat exchangers.

- Capacity lost to suction heating: for R600a vapour at 0.58 bar (compressibility within
  3 % of 1, changing by under 1 % between the two temperatures) the density goes as 1/T,
  so the capacity with and without heating are in the ratio ``T_cyl / T_in`` within 1 %.
- A loss's COP cost is exactly what removing it alone gives: the loss chain's own
  numbers (round-off).
- The suction passage as a film in series with the wall: with the gas-side area given,
  the heat the suction gas takes from the cylinder wall is the film's (Dittus-Boelter at
  the flow) in series with the fixed UA, so its conductance is below the fixed UA and
  rises with the mass flow.
- Under the induction-motor drive without a motor model, the rotor's copper loss is in
  the electrical power and the COP.
"""

from __future__ import annotations

import pytest

from recipsim.api import load_case, simulate
from recipsim.model.thermal import ThermalCoupling
from recipsim.physics.thermo.shell_network import LINK_NAMES, NetworkLoads


@pytest.fixture(scope="module")
def tles():
    return simulate(load_case("tles5.7kk3_r600a")).summary


def test_capacity_lost_to_suction_heating_goes_as_temperature(tles):
    q = tles["cooling_capacity [W]"]
    t_cyl, t_in = tles["cylinder_inlet_temperature [K]"], tles["suction_temperature [K]"]
    lost = tles["capacity_loss_suction_heating [W]"]
    # the capacity without heating over the capacity with it (at the line pressure) is
    # the density ratio, T_cyl / T_in for an ideal gas; the vapour's compressibility
    # changes by under 1 % between the two temperatures
    heated = q + tles["capacity_loss_mufflers [W]"]
    assert (heated + lost) / heated == pytest.approx(t_cyl / t_in, rel=1e-2)
    assert lost > 0.05 * q  # 30 K of heating costs about a tenth of the capacity


def test_cop_costs_are_the_losses_removed_one_at_a_time(tles):
    q, w = tles["cooling_capacity [W]"], tles["motor_electrical_power [W]"]
    motor = tles["loss_motor [W]"]
    assert tles["cop_loss_motor [-]"] == pytest.approx(q / (w - motor) - q / w, rel=1e-12)
    heating = tles["loss_suction_heating [W]"]
    gained = tles["capacity_loss_suction_heating [W]"]
    expected = (q + gained) / (w - heating) - q / w
    assert tles["cop_loss_suction_heating [-]"] == pytest.approx(expected, rel=1e-12)


def test_suction_passage_film_is_in_series_and_grows_with_flow():
    case = load_case("tles5.7kk3_r600a", {"thermal.suction_passage_gas_side_area": 1e-3})
    result = simulate(case)
    model = result.solution.model
    coupling = ThermalCoupling(case)
    link = LINK_NAMES.index("suction_muffler_cylinder_wall")
    fixed = coupling.parameters.conductances[link]

    def conductance(mdot: float) -> float:
        loads = NetworkLoads(mdot, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
        return coupling.network_parameters(model, loads).conductances[link]

    low, high = conductance(2e-4), conductance(4e-4)
    assert low < high < fixed
    film_low, film_high = (1.0 / (1.0 / g - 1.0 / fixed) for g in (low, high))
    assert film_high / film_low == pytest.approx(2.0**0.8, rel=1e-9)  # turbulent at both


def test_rotor_loss_is_in_the_electrical_cop():
    row = simulate(load_case("reference_r134a_lbp_lubricated")).summary
    assert row["drive"] == "induction_motor" and row["motor"] == "lossless"
    rotor = row["motor_rotor_loss_power [W]"]
    assert rotor > 0.0
    assert row["motor_electrical_power [W]"] == pytest.approx(
        row["shaft_power [W]"] + rotor, rel=1e-12
    )
    assert row["COP [-]"] == pytest.approx(
        row["cooling_capacity [W]"] / row["motor_electrical_power [W]"], rel=1e-12
    )
