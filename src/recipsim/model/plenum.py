"""Constant boundary states of the cylinder: the suction and discharge plena and the shell
gas, as the compiled scene reads them.

The thermal network and the shooting solver move them between revolutions, on a solve's
working copy (:meth:`recipsim.model.scene_model.WorkingModel.set_suction_state` and its
siblings); the entropy is left for first use, since only the set-up (the isentropic
discharge, the initial state) asks for it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from recipsim.case.refrigerant import AnyFluid


@dataclass
class PlenumState:
    """A constant boundary state [SI]; the setters of the model replace it, never change it.

    Its entropy is computed on first use (``fluid`` and NaN ``known_entropy``): the
    thermal network's plena, moved after every revolution, never need it.
    """

    pressure: float
    temperature: float
    density: float
    enthalpy: float
    kappa: float
    k0: float
    viscosity: float
    known_entropy: float = math.nan
    fluid: AnyFluid | None = field(default=None, repr=False, compare=False)
    #: isentropic states of this gas at each pressure asked for [Pa -> state]
    isentropic: dict[float, dict[str, float]] = field(
        default_factory=dict, repr=False, compare=False
    )

    @property
    def entropy(self) -> float:
        """Specific entropy [J/(kg K)]."""
        if math.isnan(self.known_entropy):
            assert self.fluid is not None, "a plenum state without its entropy or fluid"
            self.known_entropy = float(self.fluid.state_trho(self.temperature, self.density)["s"])
        return self.known_entropy


def plenum_state(
    fluid: AnyFluid,
    pressure: float,
    temperature: float | None = None,
    enthalpy: float | None = None,
) -> PlenumState:
    """The plenum state at ``pressure`` [Pa] and ``temperature`` [K] or ``enthalpy``
    [J/kg] (the entropy left for first use)."""
    if temperature is not None:
        st = fluid.state_pt(pressure, temperature, entropy=False)
    else:
        assert enthalpy is not None
        st = fluid.state_ph(pressure, enthalpy, entropy=False)
    if st["quality"] >= 0.0:
        # a wet plenum (adiabatic compression of a dry fluid from near saturation ends in
        # the dome): same conventions as the property callback inside the dome
        vapour = fluid.saturated_vapour(st["T"])
        kappa, k0, mu = 1.0, vapour["k0"], vapour["viscosity"]
    else:
        kappa, k0 = st["kappa"], st["k0"]
        mu = fluid.transport(pressure, st["T"])["viscosity"]
    return PlenumState(
        pressure=pressure,
        temperature=st["T"],
        density=st["rho"],
        enthalpy=st["h"],
        kappa=kappa,
        k0=k0,
        viscosity=mu,
        known_entropy=st["s"],
        fluid=fluid,
    )


def write_plenum(
    par: np.ndarray, st: PlenumState, ip: int, irho: int, ih: int, ikappa: int, ik0: int, itemp: int
) -> None:
    """Write a plenum state into the compiled scene's parameters at the given slots."""
    par[ip] = st.pressure
    par[irho] = st.density
    par[ih] = st.enthalpy
    par[ikappa] = st.kappa
    par[ik0] = st.k0
    par[itemp] = st.temperature


def isentropic_state(fluid: AnyFluid, plenum: PlenumState, pressure: float) -> dict[str, float]:
    """The state of ``plenum``'s gas compressed (or expanded) isentropically to
    ``pressure`` [Pa], kept with the plenum (the set-up, the network's predictor and the
    summary ask for the same one); the table's Newton starts from the ideal gas's
    temperature with the plenum's isentropic exponent (a start, not the answer)."""
    state = plenum.isentropic.get(pressure)
    if state is None:
        exponent = (plenum.kappa - 1.0) / plenum.kappa if plenum.kappa > 1.0 else 0.0
        guess = plenum.temperature * (pressure / plenum.pressure) ** exponent
        state = plenum.isentropic[pressure] = fluid.state_ps(pressure, plenum.entropy, guess)
    return state
