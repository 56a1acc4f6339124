"""Compiled inverse states of a property table: the Newton iterations behind
:class:`recipsim.physics.thermo.table_states.TableFluid`.

Each solve takes the property buffer with the table (``buf``, its outputs overwritten)
and the table's entropy sums (``ent``, :func:`.table_entropy.entropy_tables`), and writes
a state into ``out`` (layout ``Q_*``) or reports a table miss (``False``, NaN), on which
the caller asks HEOS. One call from Python replaces a Python loop of compiled calls:
:class:`TableFluid` calls the one entry :func:`solve_state`, into which the helpers
inline (``inline="always"``), so that a first run compiles them once.

``(p, h)``, ``(p, s)``: Newton on ``(T, ln rho)`` with the table's derivatives;
``(rho, s)``: on ``T``; each to a relative residual of 1e-12 within 60 iterations, steps
damped to 0.2 in ln rho and 10 % in T. ``(p, T)``: Newton on ln rho from the ideal gas.
Saturation temperature: Newton on the 1-D saturation table from 0.9 ``T_c``.
"""

from __future__ import annotations

import math

from numba import njit

from recipsim.physics.layout_table import Layout
from recipsim.physics.thermo.property_slots import (
    N_PROPS,
    PROP_CV,
    PROP_DPDRHO,
    PROP_DPDT,
    PROP_ENTHALPY,
    PROP_K0,
    PROP_KAPPA,
    PROP_PRESSURE,
)
from recipsim.physics.thermo.property_table import (
    H_DT,
    H_DTS,
    H_NS,
    H_NT,
    H_OFF_K0,
    H_OFF_SAT,
    H_T0,
    H_TS0,
    H_TSAT_MAX,
    N_SAT,
    S_DPSAT,
    S_P,
    _hermite,
    _line,
)
from recipsim.physics.thermo.table_entropy import single_phase, table_entropy

NEWTON_TOL = 1e-12
NEWTON_ITERATIONS = 60

#: the questions of :func:`solve_state` (its ``kind``)
SOLVE_PH = 0
SOLVE_PS = 1
SOLVE_RHOS = 2
SOLVE_TRHO = 3
SOLVE_PT = 4
SOLVE_TSAT = 5

# ---- a state written by :func:`fill_state` ---------------------------------------------
STATE = Layout("table state")
_q = STATE.add
Q_P = _q("p", "Pa", "pressure")
Q_T = _q("T", "K", "temperature")
Q_RHO = _q("rho", "kg/m3", "density")
Q_H = _q("h", "J/kg", "specific enthalpy")
Q_S = _q("s", "J/(kg K)", "specific entropy (NaN unless asked for)")
Q_U = _q("u", "J/kg", "specific internal energy")
Q_CP = _q("cp", "J/(kg K)", "isobaric specific heat")
Q_CV = _q("cv", "J/(kg K)", "isochoric specific heat")
Q_SOUND = _q("speed_of_sound", "m/s", "speed of sound")
Q_KAPPA = _q("kappa", "-", "isentropic exponent")
Q_K0 = _q("k0", "-", "ideal-gas c_p0 / c_v0")
N_STATE = STATE.size


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
    for _ in range(NEWTON_ITERATIONS):
        rho = math.exp(x)
        if not single_phase(temperature, rho, buf):
            break
        f = buf[PROP_PRESSURE] / pressure - 1.0
        if abs(f) < NEWTON_TOL:
            dpdt = buf[PROP_DPDT]
            cp = buf[PROP_CV] + temperature * dpdt * dpdt / (rho * rho * buf[PROP_DPDRHO])
            return buf[PROP_ENTHALPY], cp, rho
        x -= max(-0.2, min(0.2, f * pressure / (rho * buf[PROP_DPDRHO])))
    return math.nan, math.nan, math.nan


@njit(cache=True, inline="always")
def saturation_temperature(pressure, critical_temperature, buf) -> float:
    """Saturation temperature [K] at ``pressure`` [Pa] by Newton on the saturation
    table from 0.9 ``critical_temperature`` (steps limited to 10 %); NaN on a miss."""
    t = 0.9 * critical_temperature
    for _ in range(NEWTON_ITERATIONS):
        p = saturation_row(t, S_P, buf)
        dp = saturation_row(t, S_DPSAT, buf)
        if not (math.isfinite(p) and math.isfinite(dp)) or dp <= 0.0:
            return math.nan
        step = (p - pressure) / dp
        t -= max(-0.1 * t, min(0.1 * t, step))
        if abs(p / pressure - 1.0) < NEWTON_TOL:
            return t
    return math.nan


@njit(cache=True, inline="always")
def guess_temperature(pressure, critical_temperature, critical_pressure, buf) -> float:
    """A vapour temperature at ``pressure`` to start Newton from [K]: 20 K above the dew
    point (or 1.1 ``critical_temperature`` above the critical pressure or on a miss)."""
    if pressure < critical_pressure:
        t_sat = saturation_temperature(pressure, critical_temperature, buf)
        if t_sat == t_sat:
            return t_sat + 20.0
    return 1.1 * critical_temperature


@njit(cache=True, inline="always")
def fill_state(temperature, density, with_entropy, buf, ent, out) -> bool:
    """Every property at (T, rho) into ``out`` (``Q_*``; the entropy NaN unless
    ``with_entropy``); False where the table has no single-phase answer."""
    s = math.nan
    if with_entropy:
        s = table_entropy(temperature, density, buf, ent)
        if not math.isfinite(s):
            return False
    if not single_phase(temperature, density, buf):
        return False
    p, h, cv = buf[PROP_PRESSURE], buf[PROP_ENTHALPY], buf[PROP_CV]
    dpdt, dpdrho, kappa = buf[PROP_DPDT], buf[PROP_DPDRHO], buf[PROP_KAPPA]
    out[Q_P], out[Q_T], out[Q_RHO], out[Q_H], out[Q_S] = p, temperature, density, h, s
    out[Q_U] = h - p / density
    out[Q_CP] = cv + temperature * dpdt * dpdt / (density * density * dpdrho)
    out[Q_CV] = cv
    out[Q_SOUND] = math.sqrt(kappa * p / density)
    out[Q_KAPPA] = kappa
    out[Q_K0] = buf[PROP_K0]
    return True


@njit(cache=True, inline="always")
def _newton_2d(kind, pressure, target, temperature, density, buf, ent) -> tuple[float, float]:
    """Newton on (T, ln rho) for p = ``pressure`` and h (``SOLVE_PH``) or s
    (``SOLVE_PS``) = ``target``, residuals relative to p and to ``max(|target|, 1e5)``
    (h) or ``max(|target|, 1e3)`` (s); damped to 0.2 in ln rho and 10 % in T.
    (T, rho), NaN on a miss."""
    scale_f = max(abs(target), 1e5 if kind == SOLVE_PH else 1e3)
    x = math.log(density)
    for _ in range(NEWTON_ITERATIONS):
        rho = math.exp(x)
        if not single_phase(temperature, rho, buf):
            break
        p, cv, dpdt, dpdrho = buf[PROP_PRESSURE], buf[PROP_CV], buf[PROP_DPDT], buf[PROP_DPDRHO]
        f0 = p / pressure - 1.0
        a, b = dpdt / pressure, rho * dpdrho / pressure
        if kind == SOLVE_PH:
            f1 = (buf[PROP_ENTHALPY] - target) / scale_f
            c = (cv + dpdt / rho) / scale_f
            d = (dpdrho - temperature * dpdt / rho) / scale_f
        else:
            s = table_entropy(temperature, rho, buf, ent)
            if not math.isfinite(s):
                break
            f1 = (s - target) / scale_f
            c, d = cv / temperature / scale_f, -dpdt / rho / scale_f
        if abs(f0) < NEWTON_TOL and abs(f1) < NEWTON_TOL:
            return temperature, rho
        det = a * d - b * c
        if det == 0.0:
            break
        dt = -(d * f0 - b * f1) / det
        dx = -(-c * f0 + a * f1) / det
        step = min(1.0, 0.2 / max(abs(dx), 1e-300), 0.1 * temperature / max(abs(dt), 1e-300))
        temperature += step * dt
        x += step * dx
    return math.nan, math.nan


@njit(cache=True, inline="always")
def _state_at_pressure(
    kind, pressure, target, guess, with_entropy, gas_constant, t_crit, p_crit, buf, ent, out
) -> bool:
    """The vapour state at ``pressure`` [Pa] with h (``SOLVE_PH``, [J/kg]) or s
    (``SOLVE_PS``, [J/(kg K)]) = ``target`` into ``out`` (:func:`fill_state`).

    Newton starts from ``guess`` (T [K]; NaN: :func:`guess_temperature`) and the vapour
    density there (:func:`table_vapour_pt`). False on a table miss.
    """
    t0 = guess if guess == guess else guess_temperature(pressure, t_crit, p_crit, buf)
    rho0 = table_vapour_pt(pressure, t0, gas_constant, buf)[2]
    if not math.isfinite(rho0):
        return False
    t, rho = _newton_2d(kind, pressure, target, t0, rho0, buf, ent)
    if t != t:
        return False
    return fill_state(t, rho, with_entropy or kind == SOLVE_PS, buf, ent, out)


@njit(cache=True, inline="always")
def _state_rhos(density, entropy, guess, buf, ent, out) -> bool:
    """The state at ``density`` [kg/m3] and ``entropy`` [J/(kg K)] into ``out``: Newton on
    T from ``guess`` [K], residual relative to ``max(|entropy|, 1e3)``, steps limited to
    10 %. False on a table miss."""
    scale_f = max(abs(entropy), 1e3)
    temperature = guess
    rho = math.exp(math.log(density))
    for _ in range(NEWTON_ITERATIONS):
        if not single_phase(temperature, rho, buf):
            return False
        cv = buf[PROP_CV]
        s = table_entropy(temperature, rho, buf, ent)
        if not math.isfinite(s):
            return False
        f = (s - entropy) / scale_f
        if abs(f) < NEWTON_TOL:
            return fill_state(temperature, density, True, buf, ent, out)
        dt = -f / (cv / temperature / scale_f)
        step = min(1.0, 0.2 / 1e-300, 0.1 * temperature / max(abs(dt), 1e-300))
        temperature += step * dt
    return False


@njit(cache=True)
def solve_state(kind, a, b, guess, with_entropy, gas_constant, t_crit, p_crit, buf, ent, out):
    """One question to the table, the one compiled entry of :class:`TableFluid`'s states
    (one compilation on a first run); False on a table miss (the caller asks HEOS).

    Parameters
    ----------
    kind : int
        ``SOLVE_PH``: (p [Pa], h [J/kg]); ``SOLVE_PS``: (p, s [J/(kg K)]);
        ``SOLVE_RHOS``: (rho [kg/m3], s); ``SOLVE_TRHO``: (T [K], rho);
        ``SOLVE_PT``: (p, T) vapour; ``SOLVE_TSAT``: the saturation temperature at
        p = ``a`` into ``out[Q_T]``.
    a, b : float
        The two inputs, in that order.
    guess : float
        Newton's first temperature [K] (``SOLVE_PH``, ``SOLVE_PS``: NaN for 20 K above
        the dew point; ``SOLVE_RHOS``: required).
    with_entropy : bool
        Compute the entropy (``SOLVE_PH``, ``SOLVE_TRHO``, ``SOLVE_PT``; NaN otherwise).
    gas_constant, t_crit, p_crit : float
        [J/(kg K)], [K], [Pa].
    buf, ent, out : ndarray
        Property buffer with the table, its entropy sums, the state (``Q_*``).
    """
    if kind == SOLVE_PH or kind == SOLVE_PS:
        return _state_at_pressure(
            kind, a, b, guess, with_entropy, gas_constant, t_crit, p_crit, buf, ent, out
        )
    if kind == SOLVE_RHOS:
        return _state_rhos(a, b, guess, buf, ent, out)
    if kind == SOLVE_TRHO:
        return fill_state(a, b, with_entropy, buf, ent, out)
    if kind == SOLVE_PT:
        rho = table_vapour_pt(a, b, gas_constant, buf)[2]
        return math.isfinite(rho) and fill_state(b, rho, with_entropy, buf, ent, out)
    out[Q_T] = saturation_temperature(a, t_crit, buf)
    return math.isfinite(out[Q_T])
