"""Build a property table from CoolProp's HEOS backend and measure its error.

Imported only when a table is built or checked: it imports CoolProp.
Layout and evaluation: :mod:`.property_table`; cache: :mod:`.property_table_cache`.

Size (over the project's 400 lines): the grid, the CoolProp sampling, the dome
handling and the error check against HEOS run as one build.
"""

from __future__ import annotations

import math
import time
from typing import Any

import CoolProp.CoolProp as CP
import numpy as np

from recipsim.physics.thermo.properties import N_PROPS, HeosProperties
from recipsim.physics.thermo.property_table import (
    CHECKED_SLOTS,
    ERROR_SAMPLES,
    G_CONDUCTIVITY,
    G_CV,
    G_DPDRHO,
    G_DPDT_RHO,
    G_H,
    G_PRHO,
    G_VISCOSITY,
    H_DT,
    H_DTS,
    H_DX,
    H_FORMAT,
    H_LNRHOV_BAND,
    H_NS,
    H_NT,
    H_NX,
    H_OFF_GRID,
    H_OFF_K0,
    H_OFF_MASK,
    H_OFF_SAT,
    H_S_T,
    H_S_VALUE,
    H_S_X,
    H_T0,
    H_TCRIT,
    H_TMAX,
    H_TMIN,
    H_TRANSPORT,
    H_TS0,
    H_TSAT_MAX,
    H_X0,
    MASK_THERMO,
    MASK_TRANSPORT,
    N_GRID,
    N_HEADER,
    N_SAT,
    S_CPV,
    S_D2HDP2_L,
    S_D3HDP3_L,
    S_DHDP_L,
    S_DPSAT,
    S_DUL,
    S_DUV,
    S_DVL,
    S_DVV,
    S_HL_DOME,
    S_HV_DOME,
    S_KV,
    S_LNRHOV,
    S_MUV,
    S_P,
    S_UL,
    S_UV,
    S_VL,
    S_VL_DOME,
    S_VV,
    STATUS_FALLBACK,
    STATUS_OK,
    TABLE_FORMAT,
    THERMO_SLOTS,
    TRANSPORT_SLOTS,
    PropertyTable,
    TableResolution,
    _hermite,
    evaluate_many,
)

# ======================================================================================
# build
# ======================================================================================

# fourth-order five-point first derivatives at window position 0..4 (unit spacing)
_FD5 = (
    np.array(
        [
            [-25.0, 48.0, -36.0, 16.0, -3.0],
            [-3.0, -10.0, 18.0, -6.0, 1.0],
            [1.0, -8.0, 0.0, 8.0, -1.0],
            [-1.0, 6.0, -18.0, 10.0, 3.0],
            [3.0, -16.0, 36.0, -48.0, 25.0],
        ]
    )
    / 12.0
)


def _derivative(f: np.ndarray, axis: int) -> np.ndarray:
    """First derivative per node spacing along ``axis`` by five-point differences.

    The most central window whose five values are all finite is used (windows shift
    towards the computed side at the edges of the grid and of the computed region);
    NaN where no window fits.
    """
    n = f.shape[axis]
    out = np.full(f.shape, np.nan)
    if n < 5:
        return out

    def part(lo: int, hi: int) -> tuple[slice, ...]:
        index = [slice(None)] * f.ndim
        index[axis] = slice(lo, hi)
        return tuple(index)

    for pos in (2, 1, 3, 0, 4):
        acc = _FD5[pos, 0] * f[part(0, n - 4)]
        for q in range(1, 5):
            acc += _FD5[pos, q] * f[part(q, n - 4 + q)]
        target = out[part(pos, n - 4 + pos)]
        np.copyto(target, acc, where=np.isnan(target))
    return out


def _grid_axes(
    state: CP.AbstractState, t_min: float, t_max: float, res: TableResolution
) -> tuple[np.ndarray, np.ndarray]:
    """Node temperatures [K] and ln(rho) values of the grid (rho in kg/m3)."""
    nt = max(int(math.ceil((t_max - t_min) / res.dt)) + 1, 5)
    temps = np.linspace(t_min, t_max, nt)
    rho_c = state.rhomass_critical()
    x0 = math.log(res.rho_min_ratio * rho_c)
    nx = max(int(math.ceil((math.log(res.rho_max_ratio * rho_c) - x0) / res.dx)) + 1, 5)
    xs = x0 + res.dx * np.arange(nx)
    return temps, xs


def _dew_density(state: CP.AbstractState, temperature: float) -> float:
    """Saturated vapour density at ``temperature`` [kg/m3]."""
    state.update(CP.QT_INPUTS, 1.0, temperature)
    return state.rhomass()


def _single_phase_values(gas: CP.AbstractState, temperature: float, density: float) -> np.ndarray:
    """Grid quantities from the equation of state at (T, rho), gas phase imposed.

    Raises ``ValueError`` when the equation of state fails; transport quantities that
    CoolProp cannot give are NaN.
    """
    gas.update(CP.DmassT_INPUTS, density, temperature)
    out = np.full(N_GRID, np.nan)
    out[G_PRHO] = gas.p() / density
    out[G_H] = gas.hmass()
    out[G_CV] = gas.cvmass()
    out[G_DPDT_RHO] = gas.first_partial_deriv(CP.iP, CP.iT, CP.iDmass) / density
    out[G_DPDRHO] = gas.first_partial_deriv(CP.iP, CP.iDmass, CP.iT)
    try:
        out[G_VISCOSITY] = gas.viscosity()
        out[G_CONDUCTIVITY] = gas.conductivity()
    except ValueError:
        out[G_VISCOSITY] = out[G_CONDUCTIVITY] = np.nan
    return out


def _grid_values(
    coolprop_name: str, temps: np.ndarray, xs: np.ndarray, res: TableResolution
) -> np.ndarray:
    """Node values (NaN where not computed: deep in the dome, liquid, EOS failure)."""
    gas = CP.AbstractState("HEOS", coolprop_name)
    gas.specify_phase(CP.iphase_gas)
    sat = CP.AbstractState("HEOS", coolprop_name)
    t_crit = sat.T_critical()
    grid = np.full((temps.size, xs.size, N_GRID), np.nan)
    dx = xs[1] - xs[0]
    for i, temp in enumerate(temps):
        x_top = xs[-1]
        if temp < t_crit:
            try:
                x_top = min(x_top, math.log(_dew_density(sat, temp)) + res.dome_margin * dx)
            except ValueError:
                x_top = -math.inf
        for j, x in enumerate(xs):
            if x > x_top + 1e-12:
                break
            try:
                grid[i, j] = _single_phase_values(gas, float(temp), math.exp(x))
            except ValueError:
                continue
    grid[~np.all(np.isfinite(grid[..., :G_VISCOSITY]), axis=2)] = np.nan
    return grid


def _k0_values(coolprop_name: str, temps: np.ndarray) -> np.ndarray:
    """Ideal-gas c_p0 / c_v0 at the grid temperatures [-]."""
    st = CP.AbstractState("HEOS", coolprop_name)
    r_gas = st.gas_constant() / st.molar_mass()
    out = np.empty(temps.size)
    for i, temp in enumerate(temps):
        st.update(CP.DmassT_INPUTS, 1e-3, float(temp))
        cp0 = st.cp0mass()
        out[i] = cp0 / (cp0 - r_gas)
    return out


def _saturation_values(
    sat: CP.AbstractState, dome: CP.AbstractState, temp: float, pseudo_pure: bool
) -> np.ndarray:
    """Saturation quantities at ``temp`` (layout ``S_*``).

    The dome end points (``S_P`` ... ``S_HV_DOME``) must succeed (else ``ValueError``);
    the saturated-state derivatives and the transport of the saturated vapour are NaN
    where CoolProp cannot give them (the HEOS callback fails there too: pseudo-pure
    fluids have no saturation derivatives, R32's conductivity fails below about 236 K),
    and a state that needs them is handed to HEOS.
    """
    row = np.full(N_SAT, np.nan)
    sat.update(CP.QT_INPUTS, 0.0, temp)
    v_l = 1.0 / sat.rhomass()
    sat.update(CP.QT_INPUTS, 1.0, temp)
    v_v = 1.0 / sat.rhomass()
    # the DmassT dome (what the HEOS callback sees): p constant, h and quality linear in v
    v_a = v_l + 0.25 * (v_v - v_l)
    v_b = v_l + 0.75 * (v_v - v_l)
    dome.update(CP.DmassT_INPUTS, 1.0 / v_a, temp)
    p_a, h_a, q_a = dome.p(), dome.hmass(), dome.Q()
    dome.update(CP.DmassT_INPUTS, 1.0 / v_b, temp)
    h_b, q_b = dome.hmass(), dome.Q()
    dvdq = (v_b - v_a) / (q_b - q_a)
    dhdq = (h_b - h_a) / (q_b - q_a)
    row[S_P] = p_a
    row[S_VL_DOME] = v_a - q_a * dvdq
    row[S_LNRHOV] = -math.log(v_a + (1.0 - q_a) * dvdq)
    row[S_HL_DOME] = h_a - q_a * dhdq
    row[S_HV_DOME] = h_a + (1.0 - q_a) * dhdq
    if not pseudo_pure:
        try:
            sat.update(CP.QT_INPUTS, 0.0, temp)
            rho_l = sat.rhomass()
            mixture = [
                1.0 / rho_l,
                sat.umass(),
                sat.first_saturation_deriv(CP.iUmass, CP.iT),
                -sat.first_saturation_deriv(CP.iDmass, CP.iT) / rho_l**2,
            ]
            sat.update(CP.QT_INPUTS, 1.0, temp)
            rho_v = sat.rhomass()
            mixture += [
                1.0 / rho_v,
                sat.umass(),
                sat.first_saturation_deriv(CP.iUmass, CP.iT),
                -sat.first_saturation_deriv(CP.iDmass, CP.iT) / rho_v**2,
                sat.first_saturation_deriv(CP.iP, CP.iT),
            ]
            row[[S_VL, S_UL, S_DUL, S_DVL, S_VV, S_UV, S_DUV, S_DVV, S_DPSAT]] = mixture
        except ValueError:
            pass
    try:
        sat.update(CP.QT_INPUTS, 1.0, temp)
        row[[S_MUV, S_KV, S_CPV]] = [sat.viscosity(), sat.conductivity(), sat.cpmass()]
    except ValueError:
        pass
    if not pseudo_pure:
        try:
            sat.update(CP.QT_INPUTS, 0.0, temp)
            liquid = CP.AbstractState("HEOS", sat.name())
            liquid.specify_phase(CP.iphase_liquid)
            liquid.update(CP.DmassT_INPUTS, sat.rhomass(), temp)
            row[S_DHDP_L] = liquid.first_partial_deriv(CP.iHmass, CP.iP, CP.iT)
            row[S_D2HDP2_L] = liquid.second_partial_deriv(CP.iHmass, CP.iP, CP.iT, CP.iP, CP.iT)
            row[S_D3HDP3_L] = _third_pressure_derivative(liquid, row[S_D2HDP2_L], temp)
        except ValueError:
            pass
    return row


def _third_pressure_derivative(liquid: CP.AbstractState, d2: float, temp: float) -> float:
    """(d3h/dp3)_T of the liquid at its state (the saturated liquid) [m3/(kg Pa2)].

    CoolProp has no third derivatives: a one-sided second-order difference of
    ``(d2h/dp2)_T`` into the compressed liquid, steps of 1e-3 of the pressure (its
    truncation error, about 1e-6 p^2 times the fifth derivative, is far below the
    1e-5 the table is checked to; the term it feeds is a correction of a few J/kg).
    """
    p0 = liquid.p()
    step = 1e-3 * p0
    slopes = []
    for k in (1, 2):
        liquid.update(CP.PT_INPUTS, p0 + k * step, temp)
        slopes.append(liquid.second_partial_deriv(CP.iHmass, CP.iP, CP.iT, CP.iP, CP.iT))
    return (-3.0 * d2 + 4.0 * slopes[0] - slopes[1]) / (2.0 * step)


def _is_pseudo_pure(state: CP.AbstractState) -> bool:
    """Whether bubble and dew pressures differ (CoolProp's pseudo-pure mixtures)."""
    temp = 0.9 * state.T_critical()
    state.update(CP.QT_INPUTS, 0.0, temp)
    p_bubble = state.p()
    state.update(CP.QT_INPUTS, 1.0, temp)
    return abs(p_bubble - state.p()) > 1e-9 * p_bubble


def _column_floor(values: np.ndarray) -> np.ndarray:
    """Per-quantity magnitude below which errors are taken as absolute: 1e-3 of the median."""
    flat = np.abs(values.reshape(-1, values.shape[-1]))
    out = np.zeros(flat.shape[1])
    for q in range(flat.shape[1]):
        col = flat[np.isfinite(flat[:, q]), q]
        out[q] = 1e-3 * float(np.median(col)) if col.size else 0.0
    return out


def _saturation_table(
    coolprop_name: str, t_min: float, res: TableResolution
) -> tuple[np.ndarray, np.ndarray]:
    """Saturation quantities on a uniform T grid from ``t_min`` up to near the critical point."""
    sat = CP.AbstractState("HEOS", coolprop_name)
    dome = CP.AbstractState("HEOS", coolprop_name)
    t_crit = sat.T_critical()
    t_end = t_crit - 2.0 * res.dt_sat
    ns = max(int(math.floor((t_end - t_min) / res.dt_sat)) + 1, 5)
    temps = t_min + res.dt_sat * np.arange(ns)
    pseudo_pure = _is_pseudo_pure(sat)
    rows = np.full((ns, N_SAT), np.nan)
    for k, temp in enumerate(temps):
        try:
            rows[k] = _saturation_values(sat, dome, float(temp), pseudo_pure)
        except ValueError:
            continue  # CoolProp's saturation solver gave up (near the critical point)
    return temps, rows


def _scaled_grid(grid: np.ndarray) -> np.ndarray:
    """Node values and per-cell derivatives, shape (nT, nx, N_GRID, 4)."""
    out = np.empty(grid.shape + (4,))
    out[..., 0] = grid
    out[..., 1] = _derivative(grid, 0)
    out[..., 2] = fx = _derivative(grid, 1)
    out[..., 3] = _derivative(fx, 0)
    return out


def _cell_values(g4: np.ndarray, t: float, u: float) -> np.ndarray:
    """Bicubic Hermite values of every cell at unit position (t, u), shape
    (nT-1, nx-1, N_GRID)."""
    a0, c0, a1, c1 = (float(w) for w in _hermite(t))
    b0, d0, b1, d1 = (float(w) for w in _hermite(u))
    out = np.zeros((g4.shape[0] - 1, g4.shape[1] - 1, g4.shape[2]))
    for f, a, c, b, d in (
        (g4[:-1, :-1], a0, c0, b0, d0),
        (g4[:-1, 1:], a0, c0, b1, d1),
        (g4[1:, :-1], a1, c1, b0, d0),
        (g4[1:, 1:], a1, c1, b1, d1),
    ):
        out += a * b * f[..., 0] + c * b * f[..., 1] + a * d * f[..., 2] + c * d * f[..., 3]
    return out


def _relative(err: np.ndarray, ref: np.ndarray, floor: np.ndarray) -> np.ndarray:
    return np.abs(err) / np.maximum(np.abs(ref), floor)


#: unit positions checked in a cell whose centre error is above a twentieth of the tolerance
_MARGINAL_POINTS = tuple(
    (t, u) for t in (0.2, 0.5, 0.8) for u in (0.2, 0.5, 0.8) if (t, u) != (0.5, 0.5)
)


def _cell_mask(
    coolprop_name: str, temps: np.ndarray, xs: np.ndarray, grid: np.ndarray, res: TableResolution
) -> np.ndarray:
    """Cells within the tolerance of CoolProp: bit 1 (:data:`MASK_THERMO`) for the
    thermodynamic quantities, bit 2 (:data:`MASK_TRANSPORT`) for transport.

    Every cell is checked at its centre, where the error of a Hermite interpolant with
    a smooth fourth derivative peaks; cells whose centre error is above a twentieth of
    the tolerance (near the critical point, where the fourth derivative varies within a
    cell) are checked at eight more points.
    """
    g4 = _scaled_grid(grid)
    finite = np.isfinite(g4).all(axis=3)
    thermo = finite[..., :G_VISCOSITY].all(axis=2)
    transport = finite.all(axis=2)

    def corners(a: np.ndarray) -> np.ndarray:
        return a[:-1, :-1] & a[:-1, 1:] & a[1:, :-1] & a[1:, 1:]

    ok_thermo = corners(thermo)
    ok_transport = corners(transport)
    gas = CP.AbstractState("HEOS", coolprop_name)
    gas.specify_phase(CP.iphase_gas)
    floor = _column_floor(grid)
    floor[G_DPDRHO] = 0.0  # strictly relative: (dp/drho)_T -> 0 at the critical point
    tol = np.full(N_GRID, res.tolerance)
    tol[G_VISCOSITY] = tol[G_CONDUCTIVITY] = 10.0 * res.tolerance
    dt, dx = temps[1] - temps[0], xs[1] - xs[0]

    def error(i: int, j: int, t: float, u: float, value: np.ndarray) -> np.ndarray | None:
        """Relative error per quantity / tolerance at (t, u) of cell (i, j)."""
        try:
            ref = _single_phase_values(gas, float(temps[i] + t * dt), math.exp(xs[j] + u * dx))
        except ValueError:
            return None
        return _relative(value - ref, ref, floor) / tol

    centre = _cell_values(g4, 0.5, 0.5)
    extra: dict[tuple[float, float], np.ndarray] = {}
    mask = np.zeros(ok_thermo.shape, dtype=np.uint8)
    for i, j in zip(*np.nonzero(ok_thermo), strict=True):
        scaled = error(i, j, 0.5, 0.5, centre[i, j])
        if scaled is None:
            continue
        if np.nanmax(scaled[:G_VISCOSITY]) > 0.05:
            for t, u in _MARGINAL_POINTS:
                if (t, u) not in extra:
                    extra[t, u] = _cell_values(g4, t, u)
                more = error(i, j, t, u, extra[t, u][i, j])
                if more is None:
                    scaled[:] = np.inf
                    break
                scaled = np.fmax(scaled, more)
        good = scaled <= 1.0
        if good[:G_VISCOSITY].all():
            mask[i, j] = MASK_THERMO
            if ok_transport[i, j] and good[G_VISCOSITY:].all():
                mask[i, j] |= MASK_TRANSPORT
    return mask


def build_raw(
    coolprop_name: str, t_min: float, t_max: float, res: TableResolution
) -> dict[str, Any]:
    """Compute the node values, the saturation table and the cell mask of a table.

    Parameters
    ----------
    coolprop_name : str
        CoolProp fluid name.
    t_min, t_max : float
        Temperature range [K] (the refrigerant's model range).
    res : TableResolution
        Resolution and tolerance.

    Returns
    -------
    dict
        Arrays and scalars, what the cache file stores (see :func:`assemble`).
    """
    state = CP.AbstractState("HEOS", coolprop_name)
    temps, xs = _grid_axes(state, t_min, t_max, res)
    grid = _grid_values(coolprop_name, temps, xs, res)
    mask = _cell_mask(coolprop_name, temps, xs, grid, res)
    sat_t, sat_rows = _saturation_table(coolprop_name, t_min, res)
    raw: dict[str, Any] = {
        "grid": grid,
        "mask": mask,
        "k0": _k0_values(coolprop_name, temps),
        "sat": sat_rows,
        "t_min": t_min,
        "t_max": t_max,
        "t0": float(temps[0]),
        "dt": float(temps[1] - temps[0]),
        "x0": float(xs[0]),
        "dx": float(xs[1] - xs[0]),
        "ts0": float(sat_t[0]),
        "dts": float(sat_t[1] - sat_t[0]),
        "t_crit": state.T_critical(),
    }
    # entropy anchor (table_entropy integrates from it): hottest node, a density
    # two grid lines above the lowest, where every vapour state is reached by an
    # isotherm then an isochore without crossing the dome
    raw["s_t"] = float(temps[-1])
    raw["s_x"] = float(xs[2])
    state.update(CP.DmassT_INPUTS, math.exp(raw["s_x"]), raw["s_t"])
    raw["s_value"] = state.smass()
    raw["t_sat_max"] = _checked_saturation_end(coolprop_name, sat_t, sat_rows, res)
    return raw


def _sat_hermite(rows: np.ndarray) -> np.ndarray:
    """Saturation rows with per-interval derivatives, shape (ns, N_SAT, 2)."""
    return np.stack([rows, _derivative(rows, 0)], axis=-1)


def _checked_saturation_end(
    coolprop_name: str, temps: np.ndarray, rows: np.ndarray, res: TableResolution
) -> float:
    """Temperature where the saturation table first misses the tolerance at an
    interval midpoint [K] (the dome above it goes to HEOS), else its last node.

    Quantities CoolProp cannot give (NaN) are not checked; the table hands the states
    that need them to HEOS. Intervals where only the transport quantities miss the
    tolerance get NaN transport in ``rows`` (changed in place).
    """
    s2 = _sat_hermite(rows)
    mid = 0.5 * (s2[:-1, :, 0] + s2[1:, :, 0]) + 0.125 * (s2[:-1, :, 1] - s2[1:, :, 1])
    sat = CP.AbstractState("HEOS", coolprop_name)
    dome = CP.AbstractState("HEOS", coolprop_name)
    pseudo_pure = _is_pseudo_pure(sat)
    floor = _column_floor(rows)
    tol = np.full(N_SAT, res.tolerance)
    tol[S_MUV:S_DHDP_L] = 10.0 * res.tolerance
    # the liquid line's third-order term is a correction of at most a few J/kg
    tol[S_D3HDP3_L] = 100.0 * res.tolerance
    for k in range(temps.size - 1):
        if not np.isfinite(mid[k, S_LNRHOV]):
            continue
        tm = float(0.5 * (temps[k] + temps[k + 1]))
        try:
            ref = _saturation_values(sat, dome, tm, pseudo_pure)
        except ValueError:
            return float(temps[k])
        bad = _relative(mid[k] - ref, ref, floor) > tol
        if np.any(bad[:S_MUV]):
            return float(temps[k])
        if np.any(bad[S_MUV:S_DHDP_L]):  # transport only: states that need it go to HEOS
            rows[k : k + 2, S_MUV:S_DHDP_L] = np.nan
        if np.any(bad[S_DHDP_L:]):  # liquid line near the critical point: HEOS
            rows[k : k + 2, S_DHDP_L:] = np.nan
    return float(temps[-1])


def assemble(raw: dict[str, Any]) -> np.ndarray:
    """The array that follows the ``N_PROPS`` outputs in the property buffer."""
    grid = np.asarray(raw["grid"], dtype=float)
    nt, nx = grid.shape[:2]
    g4 = _scaled_grid(grid)
    np.copyto(g4, 0.0, where=np.isnan(g4))  # cells touching NaN are masked out
    mask = np.asarray(raw["mask"], dtype=float)
    k0 = np.asarray(raw["k0"], dtype=float)
    k0_2 = np.stack([k0, _derivative(k0, 0)], axis=-1)
    s2 = _sat_hermite(np.asarray(raw["sat"], dtype=float))  # NaN: hand the state to HEOS
    ns = s2.shape[0]
    header = np.zeros(N_HEADER)
    off_grid = N_PROPS + N_HEADER
    off_mask = off_grid + g4.size
    off_k0 = off_mask + mask.size
    off_sat = off_k0 + k0_2.size
    t_sat_max = float(raw["t_sat_max"])
    sat_rows = np.asarray(raw["sat"], dtype=float)
    k_band = min(int(round((t_sat_max - raw["ts0"]) / raw["dts"])), ns - 1)
    header[H_FORMAT] = TABLE_FORMAT
    header[H_TMIN] = raw["t_min"]
    header[H_TMAX] = raw["t_max"]
    header[H_NT] = nt
    header[H_T0] = raw["t0"]
    header[H_DT] = raw["dt"]
    header[H_NX] = nx
    header[H_X0] = raw["x0"]
    header[H_DX] = raw["dx"]
    header[H_NS] = ns
    header[H_TS0] = raw["ts0"]
    header[H_DTS] = raw["dts"]
    header[H_TSAT_MAX] = t_sat_max
    header[H_TCRIT] = raw["t_crit"]
    band = sat_rows[k_band, S_LNRHOV] if k_band >= 0 else math.nan
    header[H_LNRHOV_BAND] = band if math.isfinite(band) else -math.inf
    header[H_OFF_GRID] = off_grid
    header[H_OFF_MASK] = off_mask
    header[H_OFF_K0] = off_k0
    header[H_OFF_SAT] = off_sat
    header[H_TRANSPORT] = 1.0
    header[H_S_T] = raw["s_t"]
    header[H_S_X] = raw["s_x"]
    header[H_S_VALUE] = raw["s_value"]
    return np.concatenate([header, g4.ravel(), mask.ravel(), k0_2.ravel(), s2.ravel()])


# ======================================================================================
# error against HEOS
# ======================================================================================


def _sample_region(
    region: str, n: int, rng: np.random.Generator, table: PropertyTable, sat: CP.AbstractState
) -> tuple[np.ndarray, np.ndarray]:
    """Random (T, rho) states of one region [K], [kg/m3]."""
    t_min, t_max = table.header(H_TMIN), table.header(H_TMAX)
    t_crit = table.header(H_TCRIT)
    rho_c = sat.rhomass_critical()
    x_lo = table.header(H_X0)
    x_hi = x_lo + table.header(H_DX) * (table.header(H_NX) - 1)
    t_lo, t_hi = {
        "supercritical": (t_crit, t_max),
        "near_critical": (max(0.98 * t_crit, t_min), min(1.05 * t_crit, t_max)),
    }.get(region, (t_min, min(t_crit - 1e-3, t_max)))
    if not t_lo < t_hi:
        return np.zeros(0), np.zeros(0)  # the table's range does not reach the region
    temps = np.empty(n)
    rhos = np.empty(n)
    for k in range(n):
        if region == "supercritical":
            temp = rng.uniform(t_lo, t_hi)
            rho = math.exp(rng.uniform(x_lo, x_hi))
        elif region == "near_critical":
            temp = rng.uniform(t_lo, t_hi)
            rho = rng.uniform(0.5, 1.5) * rho_c
        else:
            temp = rng.uniform(t_lo, t_hi)
            sat.update(CP.QT_INPUTS, 1.0, temp)
            rho_v = sat.rhomass()
            if region == "vapour":
                # below the table's lowest density at very low T: sample at its edge
                rho = math.exp(rng.uniform(x_lo, max(math.log(rho_v), x_lo)))
            elif region == "near_dew":
                rho = rng.uniform(0.8, 1.0) * rho_v
            else:  # two_phase
                sat.update(CP.QT_INPUTS, 0.0, temp)
                v_l = 1.0 / sat.rhomass()
                rho = 1.0 / (v_l + rng.uniform(0.0, 1.0) * (1.0 / rho_v - v_l))
        temps[k] = temp
        rhos[k] = rho
    return temps, rhos


REGIONS = ("vapour", "near_dew", "supercritical", "near_critical", "two_phase")


def _compare(
    temps: np.ndarray, rhos: np.ndarray, buf: np.ndarray, heos: HeosProperties, slots: list[str]
) -> tuple[dict[str, dict[str, float]], float]:
    """Errors of the table against ``heos`` in ``slots`` at the states the table answers;
    also the fraction of states it hands to HEOS."""
    n = temps.size
    out = np.zeros((n, N_PROPS))
    status = np.zeros(n, dtype=np.int64)
    evaluate_many(temps, rhos, buf, out, status)
    ref = np.full((n, N_PROPS), np.nan)
    for k in range(n):
        if status[k] == STATUS_OK and heos(temps[k], rhos[k]) == STATUS_OK:
            ref[k] = heos.buffer
    used = (status == STATUS_OK) & np.isfinite(ref[:, 0])
    errs: dict[str, dict[str, float]] = {}
    for name in slots:
        slot = CHECKED_SLOTS[name]
        a, r = out[used, slot], ref[used, slot]
        if a.size == 0:
            continue
        e = np.abs(a - r)
        if name != "quality":
            e = np.where(r != 0.0, e / np.where(r != 0.0, np.abs(r), 1.0), e)
        errs[name] = {"max": float(e.max()), "rms": float(np.sqrt(np.mean(e**2)))}
    return errs, float(np.mean(status == STATUS_FALLBACK)) if n else 0.0


def measure_error(
    table: PropertyTable,
    n: int = 400,
    seed: int = 1,
    regions: tuple[str, ...] = REGIONS,
) -> dict[str, Any]:
    """Errors of the table against the HEOS callback at random states.

    Regions: ``vapour`` (T < T_crit, rho_min < rho < rho_dew, uniform in ln rho),
    ``near_dew`` (0.8 rho_dew < rho < rho_dew), ``supercritical`` (T > T_crit, over the
    tabulated densities), ``near_critical`` (0.98 < T/T_crit < 1.05, 0.5 < rho/rho_crit
    < 1.5) and ``two_phase`` (uniform quality by volume). States the table hands to
    HEOS (:data:`STATUS_FALLBACK`) are counted, not compared; so are states where HEOS
    itself fails.

    Parameters
    ----------
    table : PropertyTable
        The table.
    n : int
        States per region.
    seed : int
        Random seed.
    regions : tuple of str
        Regions to sample (default all).

    Returns
    -------
    dict
        Per region: ``n``; ``fallback`` and ``fallback_transport``, the fractions of
        states handed to HEOS without and with transport; ``errors``, the ``max`` and
        ``rms`` relative error of each buffer slot (absolute for the quality and where
        HEOS gives 0). ``max_thermo``: the largest relative error of p, h, c_v, dp/dT,
        kappa and dp/drho over all regions [-].
    """
    t_min, t_max = table.header(H_TMIN), table.header(H_TMAX)
    heos = HeosProperties(table.coolprop_name, transport=False, t_min=t_min, t_max=t_max)
    heos_t = HeosProperties(table.coolprop_name, transport=True, t_min=t_min, t_max=t_max)
    sat = CP.AbstractState("HEOS", table.coolprop_name)
    rng = np.random.default_rng(seed)
    buf = np.concatenate([np.zeros(N_PROPS), table.buffer_tail(False)])
    buf_t = np.concatenate([np.zeros(N_PROPS), table.buffer_tail(True)])
    thermo = [name for name in CHECKED_SLOTS if name not in TRANSPORT_SLOTS]
    result: dict[str, Any] = {}
    worst = 0.0
    for region in regions:
        temps, rhos = _sample_region(region, n, rng, table, sat)
        errs, fallback = _compare(temps, rhos, buf, heos, thermo)
        errs_t, fallback_t = _compare(temps, rhos, buf_t, heos_t, list(TRANSPORT_SLOTS))
        errs.update(errs_t)
        for name in THERMO_SLOTS:
            if name in errs:
                worst = max(worst, errs[name]["max"])
        result[region] = {
            "n": int(temps.size),
            "fallback": fallback,
            "fallback_transport": fallback_t,
            "errors": errs,
        }
    result["max_thermo"] = worst
    return result


def build_table(
    coolprop_name: str, t_min: float, t_max: float, res: TableResolution | None = None
) -> PropertyTable:
    """Build a table and measure its error against HEOS (no cache).

    Parameters
    ----------
    coolprop_name : str
        CoolProp fluid name.
    t_min, t_max : float
        Temperature range [K] (the refrigerant's model range).
    res : TableResolution, optional
        Resolution and tolerance (default :class:`TableResolution`).
    """
    start = time.perf_counter()
    raw = build_raw(coolprop_name, t_min, t_max, res or TableResolution())
    table = PropertyTable(coolprop_name, assemble(raw))
    table.error = measure_error(table, n=ERROR_SAMPLES)
    table.build_time = time.perf_counter() - start
    return table
