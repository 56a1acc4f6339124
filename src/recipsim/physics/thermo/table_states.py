"""Point states from a property table: the set-up and post-processing of a run
without CoolProp.

With ``properties = "table"`` the integration reads a cached table
(:mod:`.property_table`); this module answers the few point-state questions around it
(suction and plenum states, the isentropic discharge, saturation, the liquid line,
the discharge temperature) from the same table, so that a run need not import CoolProp.
:class:`TableFluid` has the interface of :class:`recipsim.physics.thermo.fluid.Fluid`
and hands every question the table cannot answer (liquid and two-phase states other
than the ones below, near-critical or out-of-table states, pseudo-pure mixtures'
saturation) to a HEOS :class:`~recipsim.physics.thermo.fluid.Fluid` created on first need.

How each answer is obtained:

* ``(T, rho)``: the table directly; ``c_p`` and the speed of sound from the identities
  of :func:`.property_table.table_props`.
* entropy: integrated from an anchor state whose HEOS entropy the table stores, along
  the anchor isotherm and then the state's isochore (:mod:`.table_entropy`: sums
  computed once per table).
* ``(p, T)``, ``(p, h)``, ``(p, s)``, ``(rho, s)``: Newton on ``(T, ln rho)`` with the
  table's derivatives, to a relative residual of 1e-12, compiled
  (:mod:`.table_solves`): one compiled call a state.
* saturation: the 1-D saturation table (pure fluids; for pseudo-pure mixtures it has no
  ``QT`` data and the question goes to HEOS).
* subcooled liquid enthalpy (the liquid line): the expansion in pressure at constant T
  from the saturated liquid, ``h = h_l + t1 + t2 + t3`` with ``t_n = (d^n h/dp^n)_T
  dp^n / n!``, ``dp = p - p_sat(T)``, the three derivatives tabulated along saturation
  (the third by a difference of CoolProp's second). The neglected fourth-order term is
  about ``t3^2 / t2`` (measured: 0.87-1.18 times the true error for R134a, R290, R600a,
  R32 and R1234yf, 0.5-40 K of subcooling, condensing up to 1 K below the critical
  point); where that estimate exceeds :data:`LIQUID_EXPANSION_LIMIT` (near-critical
  liquid, large subcooling close to it) the question goes to HEOS. Accepted answers are
  within about 3 J/kg of HEOS (1.5e-5 of a 200 kJ/kg refrigerating effect); at the
  shipped rating points 0.0004-0.11 J/kg (ASHRAE LBP) and 0.5 J/kg (R32, AHRI).
* saturated liquid at a pressure (EN 12900's liquid): the saturation table at the
  table's saturation temperature.
* the dense supercritical states of a transcritical gas-cooler exit (R744 at 90 bar and
  35 C, 660 kg/m3) are outside the table: HEOS.

Accuracy: the table's (1e-5); ``tests/unit/physics/thermo/test_table_states.py``
measures every answer against HEOS.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from recipsim.physics.thermo.properties import (
    PROP_CONDUCTIVITY,
    PROP_QUALITY,
    PROP_VISCOSITY,
    STATUS_OK,
)
from recipsim.physics.thermo.property_slots import N_PROPS
from recipsim.physics.thermo.property_table import (
    H_TRANSPORT,
    H_TS0,
    H_TSAT_MAX,
    S_D2HDP2_L,
    S_D3HDP3_L,
    S_DHDP_L,
    S_HV_DOME,
    S_MUV,
    S_P,
    S_UL,
    S_VL,
    S_VV,
    PropertyTable,
    table_props,
)
from recipsim.physics.thermo.table_entropy import table_entropy_sums
from recipsim.physics.thermo.table_solves import (
    N_STATE,
    Q_T,
    SOLVE_PH,
    SOLVE_PS,
    SOLVE_PT,
    SOLVE_RHOS,
    SOLVE_TRHO,
    SOLVE_TSAT,
    ideal_gas_ratio,
    saturation_row,
    solve_state,
    table_vapour_pt,
)

if TYPE_CHECKING:
    from recipsim.physics.thermo.fluid import Fluid

#: largest estimated fourth-order term of the liquid-line expansion [J/kg]
LIQUID_EXPANSION_LIMIT = 2.5


class TableMiss(Exception):
    """The table cannot answer this question (the caller asks HEOS)."""


def _state(out: np.ndarray) -> dict[str, float]:
    """A state (the keys of :meth:`Fluid.state_trho`, in its order) from a filled ``out``."""
    p, t, rho, h, s, u, cp, cv, c, kappa, k0 = out.tolist()
    return {
        "p": p,
        "T": t,
        "rho": rho,
        "h": h,
        "s": s,
        "u": u,
        "quality": -1.0,
        "cp": cp,
        "cv": cv,
        "speed_of_sound": c,
        "kappa": kappa,
        "k0": k0,
    }


class TableFluid:
    """Point states of one fluid from its property table, HEOS where it has no answer.

    Same interface as :class:`recipsim.physics.thermo.fluid.Fluid`.

    Parameters
    ----------
    table : PropertyTable
        The fluid's table (:func:`.property_table_cache.load_property_table`).
    gas_constant : float
        Specific gas constant [J/(kg K)] (Newton's first guess).
    critical_temperature, critical_pressure : float
        [K], [Pa].
    """

    def __init__(
        self,
        table: PropertyTable,
        gas_constant: float,
        critical_temperature: float,
        critical_pressure: float,
    ) -> None:
        self.name = table.coolprop_name
        self.table = table
        self.gas_constant = gas_constant
        self.critical_temperature = critical_temperature
        self.critical_pressure = critical_pressure
        # one buffer, its transport flag set for the calls that ask for transport
        # properties only (:meth:`transport`) rather than a second copy of the table
        self._buf = table.property_buffer(transport=False)
        #: the entropy sums of the table (:func:`.table_entropy.table_entropy_sums`: read
        #: with a cached table, else computed)
        self._entropy_tables = table_entropy_sums(table, self._buf)
        #: a state filled by the compiled solves (:data:`.table_solves.STATE`)
        self._out = np.full(N_STATE, math.nan)
        self._heos: Fluid | None = None
        # pseudo-pure mixtures have no QT saturation data (NaN rows): their saturation
        # questions go to HEOS
        t_mid = 0.5 * (table.header(H_TS0) + table.header(H_TSAT_MAX))
        self._pure = math.isfinite(saturation_row(t_mid, S_VL, self._buf))
        #: questions answered by HEOS (the table had no answer)
        self.heos_calls = 0

    # ---- HEOS for what the table cannot answer ------------------------------------------
    def heos(self) -> Fluid:
        """The HEOS fluid (imports CoolProp on first use)."""
        self.heos_calls += 1
        if self._heos is None:
            from recipsim.physics.thermo.fluid import Fluid

            self._heos = Fluid(self.name)
        return self._heos

    def _solve(
        self, kind: int, a: float, b: float, guess: float = math.nan, entropy: bool = True
    ) -> bool:
        """:func:`.table_solves.solve_state` into ``self._out``; False on a table miss."""
        return bool(
            solve_state(
                kind,
                a,
                b,
                guess,
                entropy,
                self.gas_constant,
                self.critical_temperature,
                self.critical_pressure,
                self._buf,
                self._entropy_tables,
                self._out,
            )
        )

    # ---- the Fluid interface --------------------------------------------------------------
    def state_trho(self, temperature: float, density: float) -> dict[str, float]:
        """State from temperature [K] and density [kg/m3]."""
        if self._solve(SOLVE_TRHO, temperature, density):
            return _state(self._out)
        return self.heos().state_trho(temperature, density)

    def state_pt(
        self, pressure: float, temperature: float, entropy: bool = True
    ) -> dict[str, float]:
        """Single-phase (vapour or supercritical) state from pressure [Pa] and T [K]
        (entropy NaN unless ``entropy``)."""
        if self._solve(SOLVE_PT, pressure, temperature, entropy=entropy):
            return _state(self._out)
        return self.heos().state_pt(pressure, temperature)

    def enthalpy_pt(self, pressure: float, temperature: float) -> tuple[float, float, float]:
        """Vapour enthalpy [J/kg], c_p [J/(kg K)] and density [kg/m3] at (p [Pa], T [K]),
        from the table without the entropy; HEOS where it has no data."""
        h, cp, density = table_vapour_pt(pressure, temperature, self.gas_constant, self._buf)
        if not math.isfinite(density):
            return self.heos().enthalpy_pt(pressure, temperature)
        return float(h), float(cp), float(density)

    def state_ph(
        self, pressure: float, enthalpy: float, guess: float | None = None, entropy: bool = True
    ) -> dict[str, float]:
        """State from pressure [Pa] and specific enthalpy [J/kg] (``guess``: T [K], default
        20 K above the dew point; entropy NaN unless ``entropy``)."""
        start = math.nan if guess is None else guess
        if self._solve(SOLVE_PH, pressure, enthalpy, start, entropy):
            return _state(self._out)
        return self.heos().state_ph(pressure, enthalpy)

    def state_ps(
        self, pressure: float, entropy: float, guess: float | None = None
    ) -> dict[str, float]:
        """State from pressure [Pa] and specific entropy [J/(kg K)] (``guess``: T [K],
        default 20 K above the dew point)."""
        start = math.nan if guess is None else guess
        if self._solve(SOLVE_PS, pressure, entropy, start):
            return _state(self._out)
        return self.heos().state_ps(pressure, entropy)

    def state_rhos(
        self, density: float, entropy: float, guess: float | None = None
    ) -> dict[str, float]:
        """State from density [kg/m3] and specific entropy [J/(kg K)] (``guess``: T [K],
        default the critical temperature)."""
        start = guess if guess is not None else self.critical_temperature
        if self._solve(SOLVE_RHOS, density, entropy, start):
            return _state(self._out)
        return self.heos().state_rhos(density, entropy)

    def _saturation_temperature(self, pressure: float) -> float:
        if not self._solve(SOLVE_TSAT, pressure, math.nan):
            raise TableMiss
        return float(self._out[Q_T])

    def _pure_saturation(self) -> None:
        """TableMiss for a pseudo-pure mixture (no ``QT`` saturation data in the table)."""
        if not self._pure:
            raise TableMiss

    def saturation_pressure(self, temperature: float, quality: float = 1.0) -> float:
        """Saturation pressure at ``temperature`` [K] -> [Pa] (bubble = dew: pure fluids)."""
        try:
            self._pure_saturation()
            p = float(saturation_row(temperature, S_P, self._buf))
            if not math.isfinite(p):
                raise TableMiss
            return p
        except TableMiss:
            return self.heos().saturation_pressure(temperature, quality)

    def saturation_temperature(self, pressure: float, quality: float = 1.0) -> float:
        """Saturation temperature at ``pressure`` [Pa] -> [K]."""
        try:
            self._pure_saturation()
            return self._saturation_temperature(pressure)
        except TableMiss:
            return self.heos().saturation_temperature(pressure, quality)

    def saturated_vapour(self, temperature: float) -> dict[str, float]:
        """Saturated vapour at ``temperature`` [K]: properties and viscosity [Pa s]."""
        buf = self._buf  # saturation rows: the transport flag plays no part
        values = [saturation_row(temperature, slot, buf) for slot in (S_P, S_VV, S_HV_DOME, S_MUV)]
        p, v_v, h_v, mu = (float(v) for v in values)
        if not all(math.isfinite(v) for v in values):
            return self.heos().saturated_vapour(temperature)
        return {
            "p": p,
            "rho": 1.0 / v_v,
            "h": h_v,
            "k0": float(ideal_gas_ratio(temperature, buf)),
            "viscosity": mu,
        }

    def transport(self, pressure: float, temperature: float) -> dict[str, float]:
        """Viscosity [Pa s] and thermal conductivity [W/(m K)] of a single-phase state."""
        try:
            density = float(table_vapour_pt(pressure, temperature, self.gas_constant, self._buf)[2])
            if not math.isfinite(density):
                raise TableMiss
            buf = self._buf
            buf[N_PROPS + H_TRANSPORT] = 1.0
            try:
                status = table_props(temperature, density, buf)
            finally:
                buf[N_PROPS + H_TRANSPORT] = 0.0
            if status != STATUS_OK or buf[PROP_QUALITY] >= 0.0:
                raise TableMiss
            return {
                "viscosity": float(buf[PROP_VISCOSITY]),
                "conductivity": float(buf[PROP_CONDUCTIVITY]),
            }
        except TableMiss:
            return self.heos().transport(pressure, temperature)

    def _saturated_liquid(self, temperature: float) -> tuple[float, ...]:
        """Saturated liquid at ``temperature`` [K]: p_sat [Pa], v_l [m3/kg], u_l [J/kg] and
        (d^n h / dp^n)_T for n = 1, 2, 3; TableMiss where the table has none."""
        self._pure_saturation()
        values = tuple(
            float(saturation_row(temperature, slot, self._buf))
            for slot in (S_P, S_VL, S_UL, S_DHDP_L, S_D2HDP2_L, S_D3HDP3_L)
        )
        if not all(math.isfinite(v) for v in values):
            raise TableMiss
        return values

    def liquid_enthalpy(self, pressure: float, temperature: float) -> float:
        """Specific enthalpy [J/kg] of liquid at ``pressure`` [Pa] and ``temperature`` [K]
        (the liquid line); HEOS above the critical temperature, below saturation or where
        the expansion would not be accurate."""
        try:
            p_sat, v_l, u_l, d1, d2, d3 = self._saturated_liquid(temperature)
            if pressure < p_sat:
                raise TableMiss
            dp = pressure - p_sat
            t2, t3 = 0.5 * d2 * dp * dp, d3 * dp**3 / 6.0
            if t3 * t3 > LIQUID_EXPANSION_LIMIT * max(abs(t2), abs(t3)):
                raise TableMiss  # the expansion is not accurate enough here
            return u_l + p_sat * v_l + d1 * dp + t2 + t3
        except TableMiss:
            return self.heos().liquid_enthalpy(pressure, temperature)

    def saturated_liquid_enthalpy(self, pressure: float) -> float:
        """Specific enthalpy [J/kg] of saturated liquid (bubble point) at ``pressure`` [Pa]:
        the saturated liquid at the table's saturation temperature, moved to ``pressure``
        along its isotherm (the two differ by the inverse's round-off, about 1e-3 Pa);
        HEOS where the table has no saturation data."""
        try:
            p_sat, v_l, u_l, d1, _d2, _d3 = self._saturated_liquid(
                self._saturation_temperature(pressure)
            )
            return u_l + p_sat * v_l + d1 * (pressure - p_sat)
        except TableMiss:
            return self.heos().saturated_liquid_enthalpy(pressure)
