"""The suction path's tubes: pressure drop and gas-side film under a pulsating draw.

The cylinder draws its gas during about half a revolution, so the flow in the tube
between the suction muffler's chamber and the suction port is a pulse, not the mean
flow. Two closed forms of a half-sine draw over half a revolution (flow
``q(t) = pi q_mean sin(2 pi t / T)`` while positive, zero the other half) carry that
into the quasi-steady laws:

- the mean of ``v^2`` is ``pi^2 / 4 = 2.47`` times the square of the mean ``v``
  (:data:`HALF_SINE_VELOCITY_SQUARE_FACTOR`), the factor on a tube's quasi-steady
  pressure drop ``(K + f L / D) rho v^2 / 2``; a muffler chamber that smooths the flow
  brings it towards 1, which is the mean-flow limit;
- a film coefficient that goes as ``Re^0.8`` averages to
  ``G = mean(q^0.8) / q_mean^0.8 = pi^-0.2 Gamma(0.9) / (2 Gamma(1.4) / sqrt(pi))``
  ``= 0.85`` of its value at the mean flow (:func:`half_sine_film_factor`, from
  ``int_0^pi sin^p x dx = sqrt(pi) Gamma((p + 1)/2) / Gamma(p/2 + 1)``).

Laws (SI): Darcy friction factor ``64 / Re`` below ``Re = 2300`` and Blasius'
``0.316 Re^-0.25`` above (Incropera et al., *Fundamentals of Heat and Mass Transfer*,
6th ed., eqs. 8.19 and 8.20a); turbulent film ``Nu = 0.023 Re^0.8 Pr^0.4`` (Dittus-Boelter,
heated gas, eq. 8.60) with the laminar floor ``Nu = 3.66`` (eq. 8.55).
"""

from __future__ import annotations

import math
from typing import Any

#: Mean of v^2 over the square of the mean v for a half-sine draw over half a revolution.
HALF_SINE_VELOCITY_SQUARE_FACTOR = math.pi**2 / 4.0
_LAMINAR_RE = 2300.0
_LAMINAR_NUSSELT = 3.66


def half_sine_film_factor(exponent: float = 0.8) -> float:
    """Quasi-steady mean of a ``Re^exponent`` film law over a half-sine draw, relative to
    its value at the mean flow [-] (0.85 for 0.8)."""
    p = exponent
    integral = math.sqrt(math.pi) * math.gamma(0.5 * (p + 1.0)) / math.gamma(0.5 * p + 1.0)
    # mean(q^p) = 0.5 (pi q_mean)^p integral / pi
    return 0.5 * math.pi**p * integral / math.pi


def film_pulse_factor(pulsation_factor: float) -> float:
    """The film's quasi-steady pulse factor for a tube whose mean(v^2) / mean(v)^2 is
    ``pulsation_factor``: 1 for a smoothed flow, :func:`half_sine_film_factor` for a
    half-sine draw (``pi^2 / 4``), linear in between [-]."""
    share = (pulsation_factor - 1.0) / (HALF_SINE_VELOCITY_SQUARE_FACTOR - 1.0)
    return 1.0 + min(max(share, 0.0), 1.0) * (half_sine_film_factor() - 1.0)


def reynolds_number(mass_flow: float, diameter: float, viscosity: float) -> float:
    """``Re = 4 mdot / (pi D mu)`` of a round tube [-]."""
    return 4.0 * abs(mass_flow) / (math.pi * diameter * viscosity)


def darcy_friction_factor(reynolds: float) -> float:
    """Darcy friction factor of a smooth tube: laminar ``64/Re``, Blasius above 2300."""
    if reynolds <= 0.0:
        return 0.0
    if reynolds < _LAMINAR_RE:
        return 64.0 / reynolds
    return 0.316 * reynolds**-0.25


def tube_pressure_drop(
    mass_flow: float,
    density: float,
    viscosity: float,
    diameter: float,
    length: float,
    minor_loss: float,
    pulsation_factor: float,
) -> float:
    """Mean pressure drop of a tube carrying a pulsating flow [Pa].

    ``pulsation_factor (K + f L / D) mdot^2 / (2 rho A^2)`` with the mean flow
    ``mass_flow`` [kg/s], the gas ``density`` [kg/m3] and ``viscosity`` [Pa s], the tube's
    ``diameter`` and ``length`` [m], its entry and exit losses ``minor_loss`` K [-] and
    ``pulsation_factor`` = mean(v^2) / mean(v)^2 [-]; f at the mean flow's Reynolds number.
    """
    if mass_flow == 0.0 or (minor_loss == 0.0 and length == 0.0):
        return 0.0
    area = math.pi * diameter * diameter / 4.0
    f = darcy_friction_factor(reynolds_number(mass_flow, diameter, viscosity))
    k = minor_loss + f * length / diameter
    return pulsation_factor * k * mass_flow * mass_flow / (2.0 * density * area * area)


def tube_diameter(flow_area: float) -> float:
    """Diameter of the round tube of ``flow_area`` [m2] [m]."""
    return math.sqrt(4.0 * flow_area / math.pi)


def gas_tube_pressure_drop(
    fluid: Any,
    pressure: float,
    temperature: float,
    density: float,
    mass_flow: float,
    tube: tuple[float, float, float, float],
) -> float:
    """:func:`tube_pressure_drop` of a gas at ``pressure`` [Pa], ``temperature`` [K] and
    ``density`` [kg/m3], its viscosity from ``fluid.transport``; ``tube`` is (entry and
    exit losses K [-], flow area [m2], length [m], pulsation factor [-]). No tube (K and
    length 0): 0, without asking the fluid."""
    minor_loss, flow_area, length, pulsation_factor = tube
    if minor_loss == 0.0 and length == 0.0:
        return 0.0
    viscosity = fluid.transport(pressure, temperature)["viscosity"]
    return tube_pressure_drop(
        mass_flow, density, viscosity, tube_diameter(flow_area), length, minor_loss,
        pulsation_factor,
    )  # fmt: skip


def tube_film_coefficient(
    mass_flow: float,
    diameter: float,
    viscosity: float,
    conductivity: float,
    prandtl: float,
    film_factor: float,
) -> float:
    """Gas-side film coefficient of a tube [W/(m2 K)]: Dittus-Boelter at the mean flow
    times ``film_factor`` (:func:`half_sine_film_factor` for a pulsating draw), not below
    the laminar ``Nu = 3.66``."""
    re = reynolds_number(mass_flow, diameter, viscosity)
    nusselt = max(0.023 * re**0.8 * prandtl**0.4 * film_factor, _LAMINAR_NUSSELT)
    return nusselt * conductivity / diameter


def series_conductance(film: float, wall: float) -> float:
    """Two conductances in series [W/K] (a film and the wall and outer side behind it)."""
    if film <= 0.0 or wall <= 0.0:
        return 0.0
    return film * wall / (film + wall)
