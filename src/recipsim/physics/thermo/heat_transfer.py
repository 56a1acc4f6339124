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

The ``options.heat_transfer`` slot: :data:`HEAT_TRANSFER` (its choices, a
:class:`HeatTransferModel` each, are declared beside their correlations here). Adding a
correlation: write it (in its own module if it is more than a few lines), declare its
entry with a new ``code`` and its default coefficient, list it in
:data:`HEAT_TRANSFER`, and add one ``if model == CODE`` branch to
:func:`heat_transfer_coefficient` (numba compiles the dispatch statically); test it
against a published value.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit

from recipsim.slots import ModelChoice, Slot

HT_ADIABATIC = 0
HT_ANNAND = 1
HT_ADAIR = 2


@dataclass(frozen=True)
class HeatTransferModel(ModelChoice):
    """An in-cylinder heat-transfer correlation.

    Attributes
    ----------
    default_coefficient : float
        The correlation's constant ``a`` where the case gives no
        ``heat_transfer.coefficient`` [-].
    exchanges_heat : bool
        Heat flows between wall and gas: the case needs a wall temperature, the
        property callback the transport properties.
    """

    default_coefficient: float = 0.0
    exchanges_heat: bool = True


ADIABATIC = HeatTransferModel(
    name="adiabatic",
    code=HT_ADIABATIC,
    summary="no heat between the cylinder wall and the gas",
    exchanges_heat=False,
)
ANNAND = HeatTransferModel(
    name="annand",
    code=HT_ANNAND,
    summary="Nu = a Re^0.7 on the bore and the mean piston speed",
    source="Annand (1963); ThermoCycle Annand1963",
    default_coefficient=0.575,
)
ADAIR = HeatTransferModel(
    name="adair",
    code=HT_ADAIR,
    summary="Nu = a Re^0.8 Pr^0.6 on the equivalent diameter and the swirl velocity",
    source="Adair, Qvale & Pearson (1972)",
    default_coefficient=0.053,
)

#: The ``options.heat_transfer`` slot.
HEAT_TRANSFER: Slot[HeatTransferModel] = Slot(
    option="options.heat_transfer",
    doc="in-cylinder heat",
    choices=(ADIABATIC, ANNAND, ADAIR),
    default=ADIABATIC.name,
)


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
