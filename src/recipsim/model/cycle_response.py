"""How a revolution's flows would move with the suction plenum's temperature: the
first-order response of the cycle that the shell's thermal network is solved with
(:class:`recipsim.model.thermal.ThermalCoupling`)."""

from __future__ import annotations

from dataclasses import dataclass, replace

from recipsim.model.plenum import PlenumState
from recipsim.physics.thermo.shell_network import NetworkLoads


@dataclass(frozen=True)
class CycleResponse:
    """A revolution's flows and how they would move with the suction plenum temperature.

    Within a revolution (270 deg to 270 deg) the gas discharged was drawn in the
    revolution before: the discharge stream is paired with that plenum (``earlier``;
    the same as ``drawn`` when the start state follows the plenum, as in revolution
    iteration), the suction mass, its back-flow and the leakage with the plenum of this
    revolution (``drawn``). Moved to a plenum at T: the mass flows scale with the plenum density
    (same volumetric efficiency; the delivered flow is the suction net flow less the
    leakage, which it equals at the periodic state), and each stream's specific
    enthalpy rise over its plenum's enthalpy scales with T over that plenum's temperature
    (compression work at a fixed pressure ratio, ideal gas). Exact at the plenum the
    revolution ran with, so it does not change the converged state; it carries the
    cycle's first-order response into each network update so that the coupled iteration
    converges in about the cylinder's own revolutions.

    Attributes
    ----------
    loads : NetworkLoads
        As measured over the revolution.
    suction_mass_flow : float
        Net flow through the suction valve [kg/s].
    drawn, earlier : plenum states
        Suction plenum of this revolution and of the one before.
    """

    loads: NetworkLoads
    suction_mass_flow: float
    drawn: PlenumState
    earlier: PlenumState

    def at(self, temperature: float, state: tuple[float, ...]) -> NetworkLoads:
        """The loads at a suction plenum at ``temperature`` [K], ``state`` = its
        (h [J/kg], c_p, rho [kg/m3])."""
        h_new, _, rho_new = state[:3]
        loads = self.loads
        scale = rho_new / self.drawn.density

        def moved(mass: float, enthalpy_flow: float, plenum: PlenumState) -> tuple[float, float]:
            if mass == 0.0:
                return 0.0, enthalpy_flow * scale
            rise = enthalpy_flow / mass - plenum.enthalpy
            return mass * scale, mass * scale * (h_new + rise * temperature / plenum.temperature)

        m_leak, h_leak = moved(loads.leakage_mass_flow, loads.leakage_enthalpy_flow, self.drawn)
        m_back, h_back = moved(
            loads.suction_backflow_mass_flow, loads.suction_backflow_enthalpy_flow, self.drawn
        )
        delivered = (self.suction_mass_flow - loads.leakage_mass_flow) * scale
        back = loads.discharge_backflow_mass_flow * scale
        gross = loads.delivered_mass_flow + loads.discharge_backflow_mass_flow
        rise = loads.discharge_enthalpy_flow / gross - self.earlier.enthalpy
        h_dis = h_new + rise * temperature / self.earlier.temperature
        return replace(
            loads,
            delivered_mass_flow=delivered,
            discharge_backflow_mass_flow=back,
            discharge_enthalpy_flow=(delivered + back) * h_dis,
            suction_backflow_mass_flow=m_back,
            suction_backflow_enthalpy_flow=h_back,
            leakage_mass_flow=m_leak,
            leakage_enthalpy_flow=h_leak,
        )
