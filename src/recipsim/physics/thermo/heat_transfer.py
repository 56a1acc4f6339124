"""In-cylinder heat-transfer correlations, Nu = a Re^b Pr^c (quasi-steady).

``Qdot = h A_w (T_w - T)`` into the gas, with the wall area of the instantaneous
cylinder: head + piston crown + liner ``2 A_p + pi D x_wall`` (Roskosch et al.).

- ``annand`` (1963): Nu = 0.575 Re^0.7 on the bore with the mean piston speed
  ``c_m = 2 S N``; ThermoCycle ``Annand1963``.
- ``adair`` (Adair, Qvale & Pearson 1972): Nu = 0.053 Re^0.8 Pr^0.6 on the
  equivalent diameter ``D_e = 6 V / A_w`` with the swirl velocity ``D_e omega_g / 2``,
  ``omega_g = 2 omega (1.04 + cos 2 theta)``, halved in the half revolution around
  top dead centre (ThermoCycle's compressor convention; the original's angle origin
  is not verified).
"""

from __future__ import annotations

import math

from numba import njit

HT_ADIABATIC = 0
HT_ANNAND = 1
HT_ADAIR = 2

DEFAULT_COEFFICIENT = {HT_ADIABATIC: 0.0, HT_ANNAND: 0.575, HT_ADAIR: 0.053}


@njit(cache=True)
def heat_transfer_coefficient(
    model: int,
    coefficient: float,
    theta: float,
    omega: float,
    volume: float,
    wall_area: float,
    bore: float,
    stroke: float,
    rho: float,
    viscosity: float,
    conductivity: float,
    cp: float,
) -> float:
    """Convective coefficient h [W/(m2 K)] of the chosen correlation (0 if adiabatic)."""
    if model == HT_ANNAND:
        c_m = stroke * abs(omega) / math.pi
        re = rho * c_m * bore / viscosity
        return coefficient * re**0.7 * conductivity / bore
    if model == HT_ADAIR:
        d_e = 6.0 * volume / wall_area
        c2 = math.cos(2.0 * theta)
        omega_g = 2.0 * abs(omega) * (1.04 + c2)
        if math.cos(theta) > 0.0:
            omega_g *= 0.5
        re = rho * 0.5 * d_e * omega_g * d_e / viscosity
        pr = cp * viscosity / conductivity
        return coefficient * re**0.8 * pr**0.6 * conductivity / d_e
    return 0.0
