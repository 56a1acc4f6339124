"""One reused CoolProp ``AbstractState`` for set-up and post-processing states.

Used when a case is loaded and when results are post-processed, never inside the
right-hand side (which goes through :mod:`recipsim.physics.thermo.properties`).
CoolProp is imported when the first :class:`Fluid` is made.
"""

from __future__ import annotations


class Fluid:
    """Convenience wrapper around one reused CoolProp ``AbstractState``.

    Parameters
    ----------
    coolprop_name : str
        CoolProp fluid name.
    backend : str
        CoolProp backend (``"HEOS"``).
    """

    def __init__(self, coolprop_name: str, backend: str = "HEOS") -> None:
        import CoolProp.CoolProp as CP

        self._cp = CP
        self.name = coolprop_name
        self.state = CP.AbstractState(backend, coolprop_name)
        self.molar_mass = self.state.molar_mass()
        self.gas_constant = self.state.gas_constant() / self.molar_mass
        self.critical_temperature = self.state.T_critical()
        self.critical_pressure = self.state.p_critical()

    def saturation_pressure(self, temperature: float, quality: float = 1.0) -> float:
        """Saturation pressure at ``temperature`` [K] -> [Pa]."""
        self.state.update(self._cp.QT_INPUTS, quality, temperature)
        return self.state.p()

    def saturation_temperature(self, pressure: float, quality: float = 1.0) -> float:
        """Saturation (dew for quality 1) temperature at ``pressure`` [Pa] -> [K]."""
        self.state.update(self._cp.PQ_INPUTS, pressure, quality)
        return self.state.T()

    def state_pt(
        self, pressure: float, temperature: float, entropy: bool = True
    ) -> dict[str, float]:
        """Single-phase state from pressure [Pa] and temperature [K] (``entropy``: the
        table fluid's option; HEOS has it at no cost)."""
        self.state.update(self._cp.PT_INPUTS, pressure, temperature)
        return self._snapshot()

    def enthalpy_pt(self, pressure: float, temperature: float) -> tuple[float, float, float]:
        """Vapour enthalpy [J/kg], c_p [J/(kg K)] and density [kg/m3] at (p [Pa], T [K])
        (the few properties the shell network needs, without a full state)."""
        self.state.update(self._cp.PT_INPUTS, pressure, temperature)
        s = self.state
        return float(s.hmass()), float(s.cpmass()), float(s.rhomass())

    def state_ph(
        self, pressure: float, enthalpy: float, guess: float | None = None, entropy: bool = True
    ) -> dict[str, float]:
        """State from pressure [Pa] and specific enthalpy [J/kg] (``guess`` and ``entropy``:
        the table fluid's options)."""
        self.state.update(self._cp.HmassP_INPUTS, enthalpy, pressure)
        return self._snapshot()

    def state_ps(
        self, pressure: float, entropy: float, guess: float | None = None
    ) -> dict[str, float]:
        """State from pressure [Pa] and specific entropy [J/(kg K)] (``guess``: the table
        fluid's option)."""
        self.state.update(self._cp.PSmass_INPUTS, pressure, entropy)
        return self._snapshot()

    def state_rhos(
        self, density: float, entropy: float, guess: float | None = None
    ) -> dict[str, float]:
        """State from density [kg/m3] and specific entropy [J/(kg K)] (``guess``: the
        table fluid's option)."""
        self.state.update(self._cp.DmassSmass_INPUTS, density, entropy)
        return self._snapshot()

    def state_trho(self, temperature: float, density: float) -> dict[str, float]:
        """State from temperature [K] and density [kg/m3]."""
        self.state.update(self._cp.DmassT_INPUTS, density, temperature)
        return self._snapshot()

    def _snapshot(self) -> dict[str, float]:
        s = self.state
        phase = s.phase()
        twophase = phase == self._cp.iphase_twophase
        snap = {
            "p": s.p(),
            "T": s.T(),
            "rho": s.rhomass(),
            "h": s.hmass(),
            "s": s.smass(),
            "u": s.umass(),
            "quality": s.Q() if twophase else -1.0,
        }
        if not twophase:
            snap["cp"] = s.cpmass()
            snap["cv"] = s.cvmass()
            snap["speed_of_sound"] = s.speed_sound()
            snap["kappa"] = snap["rho"] * snap["speed_of_sound"] ** 2 / snap["p"]
            cp0 = s.cp0mass()
            snap["k0"] = cp0 / (cp0 - self.gas_constant)
        return snap

    def saturated_vapour(self, temperature: float) -> dict[str, float]:
        """Saturated vapour at ``temperature`` [K]: properties and viscosity [Pa s]."""
        self.state.update(self._cp.QT_INPUTS, 1.0, temperature)
        cp0 = self.state.cp0mass()
        return {
            "p": self.state.p(),
            "rho": self.state.rhomass(),
            "h": self.state.hmass(),
            "k0": cp0 / (cp0 - self.gas_constant),
            "viscosity": self.state.viscosity(),
        }

    def liquid_enthalpy(self, pressure: float, temperature: float) -> float:
        """Specific enthalpy [J/kg] of liquid at ``pressure`` [Pa] and ``temperature`` [K]."""
        self.state.update(self._cp.PT_INPUTS, pressure, temperature)
        return float(self.state.hmass())

    def saturated_liquid_enthalpy(self, pressure: float) -> float:
        """Specific enthalpy [J/kg] of saturated liquid (bubble point) at ``pressure`` [Pa]."""
        self.state.update(self._cp.PQ_INPUTS, pressure, 0.0)
        return float(self.state.hmass())

    def transport(self, pressure: float, temperature: float) -> dict[str, float]:
        """Viscosity [Pa s] and thermal conductivity [W/(m K)] of a single-phase state."""
        self.state.update(self._cp.PT_INPUTS, pressure, temperature)
        return {"viscosity": self.state.viscosity(), "conductivity": self.state.conductivity()}
