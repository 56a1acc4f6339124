"""Point states from a property table: the set-up and post-processing of a run
without CoolProp.

With ``properties = "table"`` the integration reads a cached table
(:mod:`.property_table`); this module answers the few point-state questions around it
(suction and plenum states, the isentropic discharge, saturation, the liquid line,
the discharge temperature) from the same table, so that a run need not import CoolProp
(about 2 s). :class:`TableFluid` has the interface of :class:`recipsim.physics.thermo.fluid.Fluid`
and hands every question the table cannot answer (liquid and two-phase states other
than the ones below, near-critical or out-of-table states, pseudo-pure mixtures'
saturation) to a HEOS :class:`~recipsim.physics.thermo.fluid.Fluid` created on first need.

How each answer is obtained:

* ``(T, rho)``: the table directly; ``c_p`` and the speed of sound from the identities
  of :func:`.property_table.table_props`.
* entropy: integrated from an anchor state whose HEOS entropy the table stores
  (hottest node, low density): along the anchor isotherm
  ``ds = -(dp/dT)_rho / rho d(ln rho)``, then along the state's isochore
  ``ds = c_v / T dT``. Every vapour state is reached without crossing the dome. The
  integrands are the table's own piecewise cubics, integrated cell by cell with
  three-point Gauss-Legendre (exact for the cubic isotherm integrand).
* ``(p, T)``, ``(p, h)``, ``(p, s)``, ``(rho, s)``: Newton on ``(T, ln rho)`` with the
  table's derivatives, to a relative residual of 1e-12.
* saturation: the 1-D saturation table (pure fluids; for pseudo-pure mixtures it has no
  ``QT`` data and the question goes to HEOS).
* subcooled liquid enthalpy (the liquid line): the expansion in pressure at constant T
  from the saturated liquid, ``h = h_l + t1 + t2`` with ``t1 = (dh/dp)_T dp``,
  ``t2 = (d2h/dp2)_T dp^2 / 2``, ``dp = p - p_sat(T)`` and both derivatives tabulated
  along saturation. The neglected third-order term is about ``t2^2 / t1`` (measured:
  within a factor 0.8-4 of the true error for R134a, R290 and R744 from 4 to 20 K of
  subcooling up to 6 K below the critical point); where that estimate exceeds
  :data:`LIQUID_EXPANSION_LIMIT` (near-critical liquid, large subcooling close to it)
  the question goes to HEOS. Accepted answers are within about 3 J/kg of HEOS
  (1.5e-5 of a 200 kJ/kg refrigerating effect); at the shipped rating points 0.3 J/kg.

Accuracy: the table's (1e-5); :mod:`tests.test_table_states` measures every answer
against HEOS.

Size (over the project's 400 lines): one class answering every post-processing
state from the table with its HEOS fallback; splitting the saturation and liquid-line
answers out is listed on issue 13.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np
from numba import njit

from recipsim.physics.thermo.properties import (
    N_PROPS,
    PROP_CONDUCTIVITY,
    PROP_CV,
    PROP_DPDRHO,
    PROP_DPDT,
    PROP_ENTHALPY,
    PROP_K0,
    PROP_KAPPA,
    PROP_PRESSURE,
    PROP_QUALITY,
    PROP_VISCOSITY,
    STATUS_OK,
)
from recipsim.physics.thermo.property_table import (
    H_DT,
    H_DTS,
    H_DX,
    H_NS,
    H_NT,
    H_OFF_K0,
    H_OFF_SAT,
    H_S_T,
    H_S_VALUE,
    H_S_X,
    H_T0,
    H_TS0,
    H_TSAT_MAX,
    H_X0,
    N_SAT,
    S_D2HDP2_L,
    S_DHDP_L,
    S_DPSAT,
    S_HV_DOME,
    S_MUV,
    S_P,
    S_UL,
    S_VL,
    S_VV,
    PropertyTable,
    _hermite,
    _line,
    table_props,
)

if TYPE_CHECKING:
    from recipsim.physics.thermo.fluid import Fluid

# three-point Gauss-Legendre on [0, 1]
_GL_X = np.array([0.5 - math.sqrt(0.15), 0.5, 0.5 + math.sqrt(0.15)])
_GL_W = np.array([5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0])

#: largest estimated third-order term of the liquid-line expansion [J/kg]
LIQUID_EXPANSION_LIMIT = 2.5

_NEWTON_TOL = 1e-12
_NEWTON_ITERATIONS = 60


class TableMiss(Exception):
    """The table cannot answer this question (the caller asks HEOS)."""


@njit(cache=True)
def _segment_isotherm(temperature, x0, x1, buf) -> float:
    """Integral of ``(dp/dT)_rho / rho`` over ln(rho) from x0 to x1 at ``temperature``."""
    total = 0.0
    for q in range(3):
        x = x0 + _GL_X[q] * (x1 - x0)
        if table_props(temperature, math.exp(x), buf) != STATUS_OK or buf[PROP_QUALITY] >= 0.0:
            return math.nan
        total += _GL_W[q] * buf[PROP_DPDT] / math.exp(x)
    return total * (x1 - x0)


@njit(cache=True)
def _segment_isochore(density, t0, t1, buf) -> float:
    """Integral of ``c_v / T`` over T from t0 to t1 at ``density``."""
    total = 0.0
    for q in range(3):
        t = t0 + _GL_X[q] * (t1 - t0)
        if table_props(t, density, buf) != STATUS_OK or buf[PROP_QUALITY] >= 0.0:
            return math.nan
        total += _GL_W[q] * buf[PROP_CV] / t
    return total * (t1 - t0)


@njit(cache=True)
def table_entropy(temperature, density, buf) -> float:
    """Specific entropy [J/(kg K)] of a single-phase state from the table in ``buf``.

    Integrated from the table's anchor (see the module docstring) in pieces that
    follow the grid lines, so each piece sees one cubic; NaN where the path leaves the
    table (the caller asks HEOS).
    """
    b = N_PROPS
    t_a, x_a = buf[b + H_S_T], buf[b + H_S_X]
    x = math.log(density)
    s = buf[b + H_S_VALUE]
    # anchor isotherm, x_a -> x: ds = -(dp/dT)_rho / rho dx
    x0, dx = buf[b + H_X0], buf[b + H_DX]
    lo, hi = min(x_a, x), max(x_a, x)
    sign = 1.0 if x >= x_a else -1.0
    k = int(math.floor((lo - x0) / dx))
    start = lo
    while start < hi:
        end = min(x0 + (k + 1) * dx, hi)
        if end > start:
            s -= sign * _segment_isotherm(t_a, start, end, buf)
        start = end
        k += 1
    # isochore at x, t_a -> T: ds = c_v / T dT
    t0, dt = buf[b + H_T0], buf[b + H_DT]
    lo, hi = min(temperature, t_a), max(temperature, t_a)
    sign = 1.0 if temperature >= t_a else -1.0
    k = int(math.floor((lo - t0) / dt))
    start = lo
    while start < hi:
        end = min(t0 + (k + 1) * dt, hi)
        if end > start:
            s += sign * _segment_isochore(density, start, end, buf)
        start = end
        k += 1
    return s


@njit(cache=True)
def saturation_row(temperature, slot, buf) -> float:
    """Saturation-table quantity ``slot`` (``S_*``) at ``temperature``; NaN outside it."""
    b = N_PROPS
    if not (buf[b + H_TS0] <= temperature <= buf[b + H_TSAT_MAX]):
        return math.nan
    ns = int(buf[b + H_NS])
    s = (temperature - buf[b + H_TS0]) / buf[b + H_DTS]
    k = min(max(int(s), 0), ns - 2)
    h00, h10, h01, h11 = _hermite(s - k)
    r0 = int(buf[b + H_OFF_SAT]) + k * 2 * N_SAT + 2 * slot
    return _line(buf, r0, r0 + 2 * N_SAT, h00, h10, h01, h11)


@njit(cache=True)
def ideal_gas_ratio(temperature, buf) -> float:
    """Ideal-gas ``c_p0 / c_v0`` at ``temperature`` from the table's 1-D k0 table."""
    b = N_PROPS
    nt = int(buf[b + H_NT])
    g = (temperature - buf[b + H_T0]) / buf[b + H_DT]
    i = min(max(int(g), 0), nt - 2)
    h00, h10, h01, h11 = _hermite(g - i)
    r0 = int(buf[b + H_OFF_K0]) + 2 * i
    return _line(buf, r0, r0 + 2, h00, h10, h01, h11)


@njit(cache=True)
def table_vapour_pt(pressure, temperature, gas_constant, buf) -> tuple[float, float, float]:
    """Vapour ``(h [J/kg], c_p [J/(kg K)], rho [kg/m3])`` at (p [Pa], T [K]): Newton on
    ln rho from the ideal gas (steps limited to 0.2), to a relative pressure residual of
    1e-12; all NaN where the table has no single-phase answer. ``buf`` is left holding
    the table's outputs at the answer."""
    x = math.log(pressure / (gas_constant * temperature))
    for _ in range(_NEWTON_ITERATIONS):
        rho = math.exp(x)
        if table_props(temperature, rho, buf) != STATUS_OK or buf[PROP_QUALITY] >= 0.0:
            break
        f = buf[PROP_PRESSURE] / pressure - 1.0
        if abs(f) < _NEWTON_TOL:
            dpdt = buf[PROP_DPDT]
            cp = buf[PROP_CV] + temperature * dpdt * dpdt / (rho * rho * buf[PROP_DPDRHO])
            return buf[PROP_ENTHALPY], cp, rho
        x -= max(-0.2, min(0.2, f * pressure / (rho * buf[PROP_DPDRHO])))
    return math.nan, math.nan, math.nan


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
        self._buf = table.property_buffer(transport=False)
        self._buf_transport = table.property_buffer(transport=True)
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

    # ---- table primitives -----------------------------------------------------------------
    def _props(self, temperature: float, density: float) -> np.ndarray:
        """The table's outputs at (T, rho); TableMiss outside its single-phase region."""
        buf = self._buf
        if table_props(temperature, density, buf) != STATUS_OK or buf[PROP_QUALITY] >= 0.0:
            raise TableMiss
        return buf

    def _entropy(self, temperature: float, density: float) -> float:
        s = float(table_entropy(temperature, density, self._buf))
        if not math.isfinite(s):
            raise TableMiss
        return s

    def _snapshot(
        self, temperature: float, density: float, entropy: bool = True
    ) -> dict[str, float]:
        """Every property at (T, rho); the entropy (about 40 us, an integral) NaN unless
        ``entropy``."""
        s = self._entropy(temperature, density) if entropy else math.nan
        buf = self._props(temperature, density)
        p, h, cv = float(buf[PROP_PRESSURE]), float(buf[PROP_ENTHALPY]), float(buf[PROP_CV])
        dpdt, dpdrho, kappa = float(buf[PROP_DPDT]), float(buf[PROP_DPDRHO]), float(buf[PROP_KAPPA])
        k0 = float(buf[PROP_K0])
        cp = cv + temperature * dpdt * dpdt / (density * density * dpdrho)
        return {
            "p": p,
            "T": temperature,
            "rho": density,
            "h": h,
            "s": s,
            "u": h - p / density,
            "quality": -1.0,
            "cp": cp,
            "cv": cv,
            "speed_of_sound": math.sqrt(kappa * p / density),
            "kappa": kappa,
            "k0": k0,
        }

    def _newton(
        self, residual: Any, temperature: float, density: float, one_d: bool = False
    ) -> tuple[float, float]:
        """Newton on (T, ln rho) (or on T alone, ``one_d``) for ``residual(T, rho) ->
        (f, J)`` with relative residual ``f``; damped to 0.2 in ln rho and 10 % in T."""
        x = math.log(density)
        for _ in range(_NEWTON_ITERATIONS):
            f, jac = residual(temperature, math.exp(x))
            if max(abs(v) for v in f) < _NEWTON_TOL:
                return temperature, math.exp(x)
            if one_d:
                dt, dx = -f[0] / jac[0][0], 0.0
            else:
                (a, b), (c, d) = jac
                det = a * d - b * c
                if det == 0.0:
                    raise TableMiss
                dt = -(d * f[0] - b * f[1]) / det
                dx = -(-c * f[0] + a * f[1]) / det
            scale = min(1.0, 0.2 / max(abs(dx), 1e-300), 0.1 * temperature / max(abs(dt), 1e-300))
            temperature += scale * dt
            x += scale * dx
        raise TableMiss

    def _density_pt(self, pressure: float, temperature: float) -> float:
        """Vapour density at (p, T) [kg/m3] (:func:`table_vapour_pt`)."""
        rho = table_vapour_pt(pressure, temperature, self.gas_constant, self._buf)[2]
        if not math.isfinite(rho):
            raise TableMiss
        return float(rho)

    # ---- the Fluid interface --------------------------------------------------------------
    def state_trho(self, temperature: float, density: float) -> dict[str, float]:
        """State from temperature [K] and density [kg/m3]."""
        try:
            return self._snapshot(temperature, density)
        except TableMiss:
            return self.heos().state_trho(temperature, density)

    def state_pt(
        self, pressure: float, temperature: float, entropy: bool = True
    ) -> dict[str, float]:
        """Single-phase (vapour or supercritical) state from pressure [Pa] and T [K]
        (entropy NaN unless ``entropy``)."""
        try:
            density = self._density_pt(pressure, temperature)
            return self._snapshot(temperature, density, entropy)
        except TableMiss:
            return self.heos().state_pt(pressure, temperature)

    def enthalpy_pt(self, pressure: float, temperature: float) -> tuple[float, float, float]:
        """Vapour enthalpy [J/kg], c_p [J/(kg K)] and density [kg/m3] at (p [Pa], T [K]),
        from the table without the entropy (about 1 us); HEOS where it has no data."""
        h, cp, density = table_vapour_pt(pressure, temperature, self.gas_constant, self._buf)
        if not math.isfinite(density):
            return self.heos().enthalpy_pt(pressure, temperature)
        return float(h), float(cp), float(density)

    def _state_at_pressure(
        self, pressure: float, residual: Any, guess: float | None, entropy: bool = True
    ) -> dict[str, float]:
        """Newton on (T, ln rho) for ``residual`` from ``guess`` (T [K]; default: 20 K
        above the dew point) and the vapour density there."""
        t0 = guess if guess is not None else self._guess_temperature(pressure)
        t, rho = self._newton(residual, t0, self._density_pt(pressure, t0))
        return self._snapshot(t, rho, entropy)

    def state_ph(
        self, pressure: float, enthalpy: float, guess: float | None = None, entropy: bool = True
    ) -> dict[str, float]:
        """State from pressure [Pa] and specific enthalpy [J/kg] (``guess``: T [K];
        entropy NaN unless ``entropy``)."""
        h_scale = max(abs(enthalpy), 1e5)

        def residual(t: float, rho: float) -> Any:
            buf = self._props(t, rho)
            p, h = buf[PROP_PRESSURE], buf[PROP_ENTHALPY]
            dpdt, dpdrho = buf[PROP_DPDT], buf[PROP_DPDRHO]
            dh_dt = buf[PROP_CV] + dpdt / rho
            dh_dx = dpdrho - t * dpdt / rho
            f = (p / pressure - 1.0, (h - enthalpy) / h_scale)
            jac = ((dpdt / pressure, rho * dpdrho / pressure), (dh_dt / h_scale, dh_dx / h_scale))
            return f, jac

        try:
            return self._state_at_pressure(pressure, residual, guess, entropy)
        except TableMiss:
            return self.heos().state_ph(pressure, enthalpy)

    def state_ps(
        self, pressure: float, entropy: float, guess: float | None = None
    ) -> dict[str, float]:
        """State from pressure [Pa] and specific entropy [J/(kg K)] (``guess``: T [K])."""
        s_scale = max(abs(entropy), 1e3)

        def residual(t: float, rho: float) -> Any:
            buf = self._props(t, rho)
            p, cv, dpdt, dpdrho = buf[PROP_PRESSURE], buf[PROP_CV], buf[PROP_DPDT], buf[PROP_DPDRHO]
            s = self._entropy(t, rho)
            f = (p / pressure - 1.0, (s - entropy) / s_scale)
            jac = (
                (dpdt / pressure, rho * dpdrho / pressure),
                (cv / t / s_scale, -dpdt / rho / s_scale),
            )
            return f, jac

        try:
            return self._state_at_pressure(pressure, residual, guess)
        except TableMiss:
            return self.heos().state_ps(pressure, entropy)

    def state_rhos(
        self, density: float, entropy: float, guess: float | None = None
    ) -> dict[str, float]:
        """State from density [kg/m3] and specific entropy [J/(kg K)] (``guess``: T [K])."""
        s_scale = max(abs(entropy), 1e3)

        def residual(t: float, rho: float) -> Any:
            cv = float(self._props(t, rho)[PROP_CV])  # read before the entropy's quadrature
            f = (self._entropy(t, rho) - entropy) / s_scale  # reuses the buffer
            return (f,), ((cv / t / s_scale,),)

        try:
            t0 = guess if guess is not None else self.critical_temperature
            t, _ = self._newton(residual, t0, density, one_d=True)
            return self._snapshot(t, density)
        except TableMiss:
            return self.heos().state_rhos(density, entropy)

    def _guess_temperature(self, pressure: float) -> float:
        """A vapour temperature at ``pressure`` to start Newton from [K]: 20 K above the
        dew point (or the critical temperature above the critical pressure)."""
        if pressure < self.critical_pressure:
            try:
                return self._saturation_temperature(pressure) + 20.0
            except TableMiss:
                pass
        return 1.1 * self.critical_temperature

    def _saturation_temperature(self, pressure: float) -> float:
        buf = self._buf
        t = 0.9 * self.critical_temperature
        for _ in range(_NEWTON_ITERATIONS):
            p = saturation_row(t, S_P, buf)
            dp = saturation_row(t, S_DPSAT, buf)
            if not (math.isfinite(p) and math.isfinite(dp)) or dp <= 0.0:
                raise TableMiss
            step = (p - pressure) / dp
            t -= max(-0.1 * t, min(0.1 * t, step))
            if abs(p / pressure - 1.0) < _NEWTON_TOL:
                return t
        raise TableMiss

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
        buf = self._buf_transport
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
            density = self._density_pt(pressure, temperature)
            buf = self._buf_transport
            if table_props(temperature, density, buf) != STATUS_OK or buf[PROP_QUALITY] >= 0.0:
                raise TableMiss
            return {
                "viscosity": float(buf[PROP_VISCOSITY]),
                "conductivity": float(buf[PROP_CONDUCTIVITY]),
            }
        except TableMiss:
            return self.heos().transport(pressure, temperature)

    def liquid_enthalpy(self, pressure: float, temperature: float) -> float:
        """Specific enthalpy [J/kg] of liquid at ``pressure`` [Pa] and ``temperature`` [K]
        (the liquid line); HEOS above the critical temperature or below saturation."""
        try:
            self._pure_saturation()
            buf = self._buf
            p_sat, v_l, u_l, dhdp, d2hdp2 = (
                float(saturation_row(temperature, slot, buf))
                for slot in (S_P, S_VL, S_UL, S_DHDP_L, S_D2HDP2_L)
            )
            values = (p_sat, v_l, u_l, dhdp, d2hdp2)
            if not all(math.isfinite(v) for v in values) or pressure < p_sat:
                raise TableMiss
            dp = pressure - p_sat
            t1, t2 = dhdp * dp, 0.5 * d2hdp2 * dp * dp
            if t2 * t2 > LIQUID_EXPANSION_LIMIT * max(abs(t1), abs(t2)):
                raise TableMiss  # the expansion is not accurate enough here
            return u_l + p_sat * v_l + t1 + t2
        except TableMiss:
            return self.heos().liquid_enthalpy(pressure, temperature)
