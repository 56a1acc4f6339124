"""Interpolated CoolProp properties for the compiled right-hand side (``properties = "table"``).

A table replaces the CoolProp callback of :mod:`recipsim.thermo.properties` (about
2 us a call from compiled code) by a compiled evaluation (about 0.07 us) that fills
the same buffer slots with the same conventions. It is built once per fluid from
CoolProp's HEOS backend (1-6 s) and cached on disk (:func:`load_property_table`).

Single phase (vapour and supercritical): piecewise bicubic Hermite interpolation on a
uniform grid in (T, ln rho) of ``p/rho``, ``h``, ``c_v``, ``(dp/dT)_rho / rho``,
``(dp/drho)_T``, viscosity and conductivity, each with node derivatives from fourth-order
finite differences of the node values (C1 interpolant, O(h^4) error). ``kappa`` and
``c_p`` follow from the interpolated values by the identities behind the HEOS callback
(``rho c^2 = rho (dp/drho)_T + T (dp/dT)_rho^2 / (rho c_v)``,
``c_p = c_v + T (dp/dT)_rho^2 / (rho^2 (dp/drho)_T)``); ``k0`` is a 1-D table in T.
Nodes up to a few grid lines inside the saturation dome carry the single-phase equation
of state's metastable values (CoolProp with the gas phase imposed), which are smooth, so
the interpolant stays accurate up to the dew line; nodes deeper in the dome or in the
liquid are not computed and the finite-difference windows shift away from them.

Inside the dome: 1-D cubic Hermite tables in T of what the HEOS callback's
``_fill_two_phase`` uses (saturated states from ``QT`` inputs and their saturation
derivatives), plus the dome pressure and the end points of ``h`` and quality, which are
linear in ``v = 1/rho`` at fixed T. For the pseudo-pure R410A CoolProp's ``DmassT``
dome pressure lies between its ``QT`` bubble and dew pressures and it has no saturation
derivatives, so the HEOS callback fails inside R410A's dome; the table hands those
states to it rather than invent values.

Self-check: at build time every cell is compared with CoolProp at its centre (and at
eight more points when the centre error is above a twentieth of the tolerance: near the
critical point the error is not largest at the centre), and the saturation table at
every interval's midpoint. The tolerance is 1e-5 on the thermodynamic quantities and
1e-4 on transport. States in failing cells (near the critical point, the metastable
dome), in the liquid, below the lowest or above the highest tabulated density make
:func:`table_props` return :data:`STATUS_FALLBACK`: the caller then evaluates the HEOS
callback. Outside the temperature range it returns ``STATUS_DOMAIN`` like the callback.
:func:`measure_error` compares the table with HEOS at random states; a table carries
the errors measured when it was built.

Data layout: one float64 array (header ``H_*``, grid with derivatives, cell mask, k0
table, saturation table) that the model appends to the property buffer after its
``N_PROPS`` outputs, so the compiled integrator's signature does not change.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import time
import zipfile
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import CoolProp
import CoolProp.CoolProp as CP
import numpy as np
from numba import njit

from ..atomic import atomic_write
from .properties import (
    N_PROPS,
    PROP_CONDUCTIVITY,
    PROP_CP,
    PROP_CV,
    PROP_DPDRHO,
    PROP_DPDT,
    PROP_ENTHALPY,
    PROP_K0,
    PROP_KAPPA,
    PROP_PRESSURE,
    PROP_QUALITY,
    PROP_VISCOSITY,
    STATUS_DOMAIN,
    STATUS_OK,
    HeosProperties,
)

#: the state is inside the temperature range but not covered by the table (liquid,
#: near-critical, below the lowest or above the highest density): evaluate HEOS instead
STATUS_FALLBACK = 2

#: bump when the build or the layout changes (part of the cache key)
TABLE_FORMAT = 2

# ---- header (offsets after N_PROPS) ------------------------------------------------------
H_FORMAT = 0
H_TMIN = 1  # temperature range of the table = domain of the callback [K]
H_TMAX = 2
H_NT = 3  # grid: temperature nodes, first node [K], spacing [K]
H_T0 = 4
H_DT = 5
H_NX = 6  # grid: ln(rho) nodes, first node, spacing
H_X0 = 7
H_DX = 8
H_NS = 9  # saturation table: nodes, first node [K], spacing [K]
H_TS0 = 10
H_DTS = 11
H_TSAT_MAX = 12  # the dome is tabulated below this temperature [K]
H_TCRIT = 13
H_LNRHOV_BAND = 14  # ln of the dew density at H_TSAT_MAX
H_OFF_GRID = 15  # absolute offsets in the buffer
H_OFF_MASK = 16
H_OFF_K0 = 17
H_OFF_SAT = 18
H_TRANSPORT = 19  # 1: fill viscosity, conductivity and c_p
N_HEADER = 24

# ---- grid quantities (single phase, functions of T and ln rho) ----------------------------
G_PRHO = 0  # p / rho [Pa m3/kg]
G_H = 1  # h [J/kg]
G_CV = 2  # c_v [J/(kg K)]
G_DPDT_RHO = 3  # (dp/dT)_rho / rho [Pa m3/(kg K)]
G_DPDRHO = 4  # (dp/drho)_T [Pa m3/kg]
G_VISCOSITY = 5  # [Pa s]
G_CONDUCTIVITY = 6  # [W/(m K)]
N_GRID = 7
#: cell mask bits: the thermodynamic quantities, the transport quantities meet the tolerance
MASK_THERMO = 1
MASK_TRANSPORT = 2

# ---- saturation quantities (functions of T) -----------------------------------------------
S_P = 0  # pressure inside the dome (DmassT) [Pa]
S_LNRHOV = 1  # ln of the dew density of the DmassT dome
S_VL_DOME = 2  # bubble specific volume of the DmassT dome [m3/kg]
S_HL_DOME = 3  # h at quality 0 and 1 of the DmassT dome [J/kg]
S_HV_DOME = 4
S_VL = 5  # QT saturated liquid and vapour: v [m3/kg], dv/dT, u [J/kg], du/dT
S_VV = 6
S_DVL = 7
S_DVV = 8
S_UL = 9
S_UV = 10
S_DUL = 11
S_DUV = 12
S_DPSAT = 13  # dp_sat/dT [Pa/K]
S_MUV = 14  # saturated vapour viscosity, conductivity, c_p
S_KV = 15
S_CPV = 16
N_SAT = 17

#: buffer slots compared with HEOS by :func:`measure_error`, and their names
CHECKED_SLOTS = {
    "p": PROP_PRESSURE,
    "h": PROP_ENTHALPY,
    "c_v": PROP_CV,
    "dp/dT": PROP_DPDT,
    "kappa": PROP_KAPPA,
    "k0": PROP_K0,
    "viscosity": PROP_VISCOSITY,
    "conductivity": PROP_CONDUCTIVITY,
    "c_p": PROP_CP,
    "quality": PROP_QUALITY,
    "dp/drho": PROP_DPDRHO,
}
#: the slots the accuracy target applies to (thermodynamic state and its derivatives)
THERMO_SLOTS = ("p", "h", "c_v", "dp/dT", "kappa", "dp/drho")
#: slots filled only with transport
TRANSPORT_SLOTS = ("viscosity", "conductivity", "c_p")


@dataclass(frozen=True)
class TableResolution:
    """Resolution, extent and self-check tolerance of a property table.

    Attributes
    ----------
    dt : float
        Target grid spacing in temperature [K].
    dx : float
        Grid spacing in ln(rho) [-].
    dt_sat : float
        Spacing of the saturation table [K].
    rho_min_ratio, rho_max_ratio : float
        Lowest and highest tabulated density as fractions of the critical density [-].
    dome_margin : int
        Grid lines computed inside the dome beyond the dew line (metastable values).
    tolerance : float
        Largest relative error of the thermodynamic quantities at a cell's check points
        before the cell is handed to HEOS [-]; transport quantities get ten times this.
    """

    dt: float = 1.0
    dx: float = 0.04
    dt_sat: float = 0.25
    rho_min_ratio: float = 1e-3
    rho_max_ratio: float = 2.0
    dome_margin: int = 6
    tolerance: float = 1e-5


@dataclass
class PropertyTable:
    """A built or loaded property table of one fluid.

    Attributes
    ----------
    coolprop_name : str
        CoolProp fluid name.
    data : ndarray
        Header, grid with derivatives, cell mask, k0 and saturation tables: what goes
        after the ``N_PROPS`` outputs of the property buffer.
    error : dict
        Errors measured against HEOS when the table was built (:func:`measure_error`).
    path : Path or None
        Cache file.
    from_cache : bool
        Loaded from the cache (else built now).
    build_time : float
        Seconds it took to build and measure the table (when it was built) [s].
    load_time : float
        Seconds it took to read the cache file (0 when built now) [s].
    """

    coolprop_name: str
    data: np.ndarray
    error: dict[str, Any] = field(default_factory=dict)
    path: Path | None = None
    from_cache: bool = False
    build_time: float = 0.0
    load_time: float = 0.0

    def header(self, slot: int) -> float:
        """A header value (``H_*``)."""
        return float(self.data[slot])

    @property
    def max_error(self) -> float:
        """Largest relative error of p, h and the derivatives at the random test states [-]."""
        return float(self.error.get("max_thermo", math.nan))

    def provenance(self) -> dict[str, Any]:
        """Entries for a run's provenance: measured error, cache file, build and load times."""
        return {
            "property_table_max_error [-]": self.max_error,
            "property_table_file": str(self.path) if self.path else "",
            "property_table_from_cache": self.from_cache,
            "property_table_build_time [s]": self.build_time,
            "property_table_load_time [s]": self.load_time,
        }

    def buffer_tail(self, transport: bool) -> np.ndarray:
        """A copy of :attr:`data` to append to a property buffer.

        Parameters
        ----------
        transport : bool
            Fill viscosity, conductivity and c_p (else those slots are left alone).
        """
        tail = self.data.copy()
        tail[H_TRANSPORT] = 1.0 if transport else 0.0
        return tail


# ======================================================================================
# compiled evaluation
# ======================================================================================


@njit(cache=True)
def _hermite(t):
    """Cubic Hermite basis on [0, 1]: weights of f0, f0', f1, f1' (derivatives per cell)."""
    t2 = t * t
    t3 = t2 * t
    return 2.0 * t3 - 3.0 * t2 + 1.0, t3 - 2.0 * t2 + t, 3.0 * t2 - 2.0 * t3, t3 - t2


@njit(cache=True)
def _line(buf, r0, r1, h00, h10, h01, h11):
    """1-D Hermite value from node rows ``r0``, ``r1`` holding (f, f' per interval)."""
    return h00 * buf[r0] + h10 * buf[r0 + 1] + h01 * buf[r1] + h11 * buf[r1 + 1]


@njit(cache=True)
def _corner(buf, n, a, c, b, d):
    """One corner's share of a bicubic Hermite value: (f, f_t, f_u, f_tu) at ``n``."""
    return a * b * buf[n] + c * b * buf[n + 1] + a * d * buf[n + 2] + c * d * buf[n + 3]


@njit(cache=True)
def _patch(buf, n00, n01, n10, n11, a0, c0, a1, c1, b0, d0, b1, d1):
    return (
        _corner(buf, n00, a0, c0, b0, d0)
        + _corner(buf, n01, a0, c0, b1, d1)
        + _corner(buf, n10, a1, c1, b0, d0)
        + _corner(buf, n11, a1, c1, b1, d1)
    )


@njit(cache=True)
def table_props(temperature, density, buf) -> int:
    """Fill ``buf[:N_PROPS]`` from the table stored in ``buf[N_PROPS:]``.

    Same outputs and conventions as the HEOS callback of
    :class:`recipsim.thermo.properties.HeosProperties` (mixture values in the dome).

    Parameters
    ----------
    temperature : float
        [K]
    density : float
        [kg/m3]
    buf : ndarray
        Property buffer: outputs, then the table (:attr:`PropertyTable.data`).

    Returns
    -------
    int
        ``STATUS_OK``; ``STATUS_DOMAIN`` outside the temperature range or for a
        non-positive density; :data:`STATUS_FALLBACK` where the table does not answer
        (the caller evaluates HEOS).
    """
    b = N_PROPS
    if not (buf[b + H_TMIN] <= temperature <= buf[b + H_TMAX]) or not (density > 0.0):
        return STATUS_DOMAIN
    x = math.log(density)
    if temperature < buf[b + H_TSAT_MAX]:
        ns = int(buf[b + H_NS])
        s = (temperature - buf[b + H_TS0]) / buf[b + H_DTS]
        k = min(max(int(s), 0), ns - 2)
        s -= k
        h00, h10, h01, h11 = _hermite(s)
        r0 = int(buf[b + H_OFF_SAT]) + k * 2 * N_SAT
        r1 = r0 + 2 * N_SAT
        ln_rho_dew = _line(buf, r0 + 2 * S_LNRHOV, r1 + 2 * S_LNRHOV, h00, h10, h01, h11)
        if not (x < ln_rho_dew):  # inside the dome, liquid, or no saturation data
            v = 1.0 / density
            vl_dome = _line(buf, r0 + 2 * S_VL_DOME, r1 + 2 * S_VL_DOME, h00, h10, h01, h11)
            if not (v >= vl_dome):
                return STATUS_FALLBACK  # liquid
            return _two_phase(buf, v, r0, r1, h00, h10, h01, h11, vl_dome)
    elif temperature < buf[b + H_TCRIT] and x >= buf[b + H_LNRHOV_BAND]:
        return STATUS_FALLBACK  # possibly inside the dome near the critical point

    nx = int(buf[b + H_NX])
    gx = (x - buf[b + H_X0]) / buf[b + H_DX]
    if not (0.0 <= gx <= nx - 1):
        return STATUS_FALLBACK
    nt = int(buf[b + H_NT])
    gt = (temperature - buf[b + H_T0]) / buf[b + H_DT]
    i = min(max(int(gt), 0), nt - 2)
    j = min(int(gx), nx - 2)
    cell = buf[int(buf[b + H_OFF_MASK]) + i * (nx - 1) + j]
    transport = buf[b + H_TRANSPORT] != 0.0
    if cell == 0.0 or (transport and cell != MASK_THERMO + MASK_TRANSPORT):
        return STATUS_FALLBACK
    a0, c0, a1, c1 = _hermite(gt - i)
    b0, d0, b1, d1 = _hermite(gx - j)
    stride = 4 * N_GRID
    n00 = int(buf[b + H_OFF_GRID]) + (i * nx + j) * stride
    n01 = n00 + stride
    n10 = n00 + nx * stride
    n11 = n10 + stride

    prho = _patch(buf, n00, n01, n10, n11, a0, c0, a1, c1, b0, d0, b1, d1)
    h = _patch(buf, n00 + 4, n01 + 4, n10 + 4, n11 + 4, a0, c0, a1, c1, b0, d0, b1, d1)
    q = 4 * G_CV
    cv = _patch(buf, n00 + q, n01 + q, n10 + q, n11 + q, a0, c0, a1, c1, b0, d0, b1, d1)
    q = 4 * G_DPDT_RHO
    dpdt = density * _patch(buf, n00 + q, n01 + q, n10 + q, n11 + q, a0, c0, a1, c1, b0, d0, b1, d1)
    q = 4 * G_DPDRHO
    dpdrho = _patch(buf, n00 + q, n01 + q, n10 + q, n11 + q, a0, c0, a1, c1, b0, d0, b1, d1)
    p = prho * density
    extra = temperature * dpdt * dpdt / (density * density)
    buf[PROP_PRESSURE] = p
    buf[PROP_ENTHALPY] = h
    buf[PROP_CV] = cv
    buf[PROP_DPDT] = dpdt
    buf[PROP_KAPPA] = density * (dpdrho + extra / cv) / p
    buf[PROP_DPDRHO] = dpdrho
    buf[PROP_QUALITY] = -1.0
    r0 = int(buf[b + H_OFF_K0]) + 2 * i
    buf[PROP_K0] = _line(buf, r0, r0 + 2, a0, c0, a1, c1)
    if transport:
        q = 4 * G_VISCOSITY
        buf[PROP_VISCOSITY] = _patch(
            buf, n00 + q, n01 + q, n10 + q, n11 + q, a0, c0, a1, c1, b0, d0, b1, d1
        )
        q = 4 * G_CONDUCTIVITY
        buf[PROP_CONDUCTIVITY] = _patch(
            buf, n00 + q, n01 + q, n10 + q, n11 + q, a0, c0, a1, c1, b0, d0, b1, d1
        )
        buf[PROP_CP] = cv + extra / dpdrho
    return STATUS_OK


@njit(cache=True)
def _two_phase(buf, v, r0, r1, h00, h10, h01, h11, vl_dome) -> int:
    """Mixture values inside the dome (as ``properties._fill_two_phase``); the status is
    :data:`STATUS_FALLBACK` where the saturation table has no data (NaN)."""
    vv_dome = math.exp(-_line(buf, r0 + 2 * S_LNRHOV, r1 + 2 * S_LNRHOV, h00, h10, h01, h11))
    quality = (v - vl_dome) / (vv_dome - vl_dome)
    hl = _line(buf, r0 + 2 * S_HL_DOME, r1 + 2 * S_HL_DOME, h00, h10, h01, h11)
    hv = _line(buf, r0 + 2 * S_HV_DOME, r1 + 2 * S_HV_DOME, h00, h10, h01, h11)
    v_l = _line(buf, r0 + 2 * S_VL, r1 + 2 * S_VL, h00, h10, h01, h11)
    v_v = _line(buf, r0 + 2 * S_VV, r1 + 2 * S_VV, h00, h10, h01, h11)
    dv_l = _line(buf, r0 + 2 * S_DVL, r1 + 2 * S_DVL, h00, h10, h01, h11)
    dv_v = _line(buf, r0 + 2 * S_DVV, r1 + 2 * S_DVV, h00, h10, h01, h11)
    u_l = _line(buf, r0 + 2 * S_UL, r1 + 2 * S_UL, h00, h10, h01, h11)
    u_v = _line(buf, r0 + 2 * S_UV, r1 + 2 * S_UV, h00, h10, h01, h11)
    du_l = _line(buf, r0 + 2 * S_DUL, r1 + 2 * S_DUL, h00, h10, h01, h11)
    du_v = _line(buf, r0 + 2 * S_DUV, r1 + 2 * S_DUV, h00, h10, h01, h11)
    x = (v - v_l) / (v_v - v_l)
    dx = (-dv_l * (v_v - v_l) - (v - v_l) * (dv_v - dv_l)) / (v_v - v_l) ** 2
    buf[PROP_PRESSURE] = _line(buf, r0 + 2 * S_P, r1 + 2 * S_P, h00, h10, h01, h11)
    buf[PROP_ENTHALPY] = hl + quality * (hv - hl)
    buf[PROP_CV] = du_l + x * (du_v - du_l) + (u_v - u_l) * dx
    buf[PROP_DPDT] = _line(buf, r0 + 2 * S_DPSAT, r1 + 2 * S_DPSAT, h00, h10, h01, h11)
    buf[PROP_KAPPA] = 1.0
    buf[PROP_K0] = 1.0
    buf[PROP_QUALITY] = quality
    buf[PROP_DPDRHO] = 0.0
    if math.isnan(buf[PROP_CV] + buf[PROP_PRESSURE] + buf[PROP_ENTHALPY] + buf[PROP_DPDT]):
        return STATUS_FALLBACK
    if buf[N_PROPS + H_TRANSPORT] != 0.0:
        mu = _line(buf, r0 + 2 * S_MUV, r1 + 2 * S_MUV, h00, h10, h01, h11)
        k = _line(buf, r0 + 2 * S_KV, r1 + 2 * S_KV, h00, h10, h01, h11)
        cp = _line(buf, r0 + 2 * S_CPV, r1 + 2 * S_CPV, h00, h10, h01, h11)
        if math.isnan(mu + k + cp):
            return STATUS_FALLBACK
        buf[PROP_VISCOSITY] = mu
        buf[PROP_CONDUCTIVITY] = k
        buf[PROP_CP] = cp
    return STATUS_OK


@njit(cache=True)
def evaluate_many(temperatures, densities, buf, out, status) -> None:
    """Evaluate the table at many states: ``out[k]`` is the buffer's outputs at state k."""
    for k in range(temperatures.shape[0]):
        status[k] = table_props(temperatures[k], densities[k], buf)
        for m in range(N_PROPS):
            out[k, m] = buf[m]


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
    return row


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
    tol[S_MUV:] = 10.0 * res.tolerance
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
        if np.any(bad):  # transport only: states that need it here go to HEOS
            rows[k : k + 2, S_MUV:] = np.nan
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


# ======================================================================================
# cache
# ======================================================================================

#: random states per region for the error measured when a table is built
ERROR_SAMPLES = 200


def cache_dir() -> Path:
    """Directory of the cached tables: ``$RECIPSIM_CACHE`` or ``~/.cache/recipsim``."""
    env = os.environ.get("RECIPSIM_CACHE")
    return Path(env) if env else Path.home() / ".cache" / "recipsim"


def cache_key(
    coolprop_name: str, t_min: float, t_max: float, res: TableResolution
) -> dict[str, Any]:
    """What a cached table depends on: fluid, CoolProp version, range, resolution, format."""
    return {
        "format": TABLE_FORMAT,
        "fluid": coolprop_name,
        "coolprop": CoolProp.__version__,
        "t_min": float(t_min),
        "t_max": float(t_max),
        "resolution": asdict(res),
        "error_samples": ERROR_SAMPLES,
    }


def cache_path(
    coolprop_name: str,
    t_min: float,
    t_max: float,
    res: TableResolution,
    directory: Path | None = None,
) -> Path:
    """File of the cached table for these inputs."""
    key = json.dumps(cache_key(coolprop_name, t_min, t_max, res), sort_keys=True)
    digest = hashlib.sha256(key.encode()).hexdigest()[:16]
    safe = "".join(c if c.isalnum() else "_" for c in coolprop_name)
    return (directory or cache_dir()) / "property_tables" / f"{safe}-{digest}.npz"


def _write(path: Path, table: PropertyTable, key: dict[str, Any]) -> None:
    def write(tmp: Path) -> None:
        with open(tmp, "wb") as handle:
            np.savez(
                handle,
                key=np.asarray(json.dumps(key, sort_keys=True)),
                error=np.asarray(json.dumps(table.error)),
                build_time=np.asarray(table.build_time),
                data=table.data,
            )

    atomic_write(path, write)


def _read(path: Path, key: dict[str, Any]) -> tuple[np.ndarray, dict[str, Any], float] | None:
    """Data, error and build time of a cached table; None if stale or unreadable."""
    try:
        with np.load(path, allow_pickle=False) as npz:
            if json.loads(str(npz["key"])) != json.loads(json.dumps(key, sort_keys=True)):
                return None
            data = np.array(npz["data"], dtype=np.float64)
            error = json.loads(str(npz["error"]))
            build_time = float(npz["build_time"])
    except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile):
        return None
    if data.ndim != 1 or data.size < N_HEADER or data[H_FORMAT] != TABLE_FORMAT:
        return None
    return data, error, build_time


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


def load_property_table(
    coolprop_name: str,
    t_min: float,
    t_max: float,
    res: TableResolution | None = None,
    directory: Path | None = None,
) -> PropertyTable:
    """The property table of a fluid: from the cache, else built, measured and cached.

    Parameters
    ----------
    coolprop_name : str
        CoolProp fluid name.
    t_min, t_max : float
        Temperature range [K] (the refrigerant's model range).
    res : TableResolution, optional
        Resolution and tolerance (default :class:`TableResolution`).
    directory : Path, optional
        Cache directory (default :func:`cache_dir`).

    Returns
    -------
    PropertyTable
        With :attr:`PropertyTable.error` measured against HEOS when it was built. A
        missing, stale (another key) or unreadable cache file is rebuilt and replaced
        atomically.
    """
    res = res or TableResolution()
    key = cache_key(coolprop_name, t_min, t_max, res)
    path = cache_path(coolprop_name, t_min, t_max, res, directory)
    start = time.perf_counter()
    cached = _read(path, key) if path.is_file() else None
    if cached is not None:
        data, error, build_time = cached
        return PropertyTable(
            coolprop_name,
            data,
            error=error,
            path=path,
            from_cache=True,
            build_time=build_time,
            load_time=time.perf_counter() - start,
        )
    table = build_table(coolprop_name, t_min, t_max, res)
    table.path = path
    _write(path, table, key)
    return table
