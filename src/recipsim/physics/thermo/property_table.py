"""Interpolated CoolProp properties for the compiled right-hand side (``properties = "table"``).

A table replaces the CoolProp callback of :mod:`recipsim.physics.thermo.properties` (a
call out of compiled code into CoolProp) by a compiled evaluation that fills the same
buffer slots with the same conventions. It is built once per fluid from CoolProp's
HEOS backend (:mod:`.property_table_build`) and cached on disk
(:func:`.property_table_cache.load_property_table`). This module holds the layout and
the compiled evaluation and does not import CoolProp.

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

Size (over the project's 400 lines): the layout constants and the compiled
evaluation that reads them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numba import njit

from recipsim.physics.layout_table import Layout
from recipsim.physics.thermo.buffer_pool import reusable_buffer
from recipsim.physics.thermo.property_slots import (
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
)

#: the state is inside the temperature range but not covered by the table (liquid,
#: near-critical, below the lowest or above the highest density): evaluate HEOS instead
STATUS_FALLBACK = 2

#: bump when the build or the layout changes (part of the cache key)
TABLE_FORMAT = 5

# ---- header (offsets after N_PROPS) ------------------------------------------------------
HEADER = Layout("property table header")
_h = HEADER.add
H_FORMAT = _h("format", "code", "TABLE_FORMAT the table was built with")
H_TMIN = _h("t_min", "K", "lowest temperature of the table (= domain of the callback)")
H_TMAX = _h("t_max", "K", "highest temperature of the table")
H_NT = _h("grid_t_nodes", "count", "grid: temperature nodes")
H_T0 = _h("grid_t_first", "K", "grid: first temperature node")
H_DT = _h("grid_t_step", "K", "grid: temperature spacing")
H_NX = _h("grid_x_nodes", "count", "grid: ln(rho) nodes")
H_X0 = _h("grid_x_first", "-", "grid: first ln(rho) node (rho in kg/m3)")
H_DX = _h("grid_x_step", "-", "grid: ln(rho) spacing")
H_NS = _h("sat_nodes", "count", "saturation table: nodes")
H_TS0 = _h("sat_t_first", "K", "saturation table: first node")
H_DTS = _h("sat_t_step", "K", "saturation table: spacing")
H_TSAT_MAX = _h("sat_t_max", "K", "the dome is tabulated below this temperature")
H_TCRIT = _h("t_crit", "K", "critical temperature")
H_LNRHOV_BAND = _h("ln_dew_density_at_sat_t_max", "-", "ln of the dew density at sat_t_max")
H_OFF_GRID = _h("grid_offset", "index", "absolute offset of the grid in the buffer")
H_OFF_MASK = _h("mask_offset", "index", "absolute offset of the cell mask in the buffer")
H_OFF_K0 = _h("k0_offset", "index", "absolute offset of the k0 table in the buffer")
H_OFF_SAT = _h("sat_offset", "index", "absolute offset of the saturation table in the buffer")
H_TRANSPORT = _h("transport", "code", "1: fill viscosity, conductivity and c_p")
H_S_T = _h("entropy_anchor_t", "K", "entropy anchor: temperature")
H_S_X = _h("entropy_anchor_x", "-", "entropy anchor: ln(rho)")
H_S_VALUE = _h("entropy_anchor_value", "J/(kg K)", "entropy anchor: HEOS entropy there")
H_RESERVED = _h("reserved", "-", "spare slot: nothing is stored there")
N_HEADER = HEADER.size

# ---- grid quantities (single phase, functions of T and ln rho) ----------------------------
GRID = Layout("property table grid quantities")
_g = GRID.add
G_PRHO = _g("p_over_rho", "Pa m3/kg", "p / rho")
G_H = _g("enthalpy", "J/kg", "specific enthalpy")
G_CV = _g("cv", "J/(kg K)", "isochoric specific heat")
G_DPDT_RHO = _g("dpdt_over_rho", "Pa m3/(kg K)", "(dp/dT)_rho / rho")
G_DPDRHO = _g("dpdrho", "Pa m3/kg", "(dp/drho)_T")
G_VISCOSITY = _g("viscosity", "Pa s", "dynamic viscosity")
G_CONDUCTIVITY = _g("conductivity", "W/(m K)", "thermal conductivity")
N_GRID = GRID.size
#: cell mask bits: the thermodynamic quantities, the transport quantities meet the tolerance
MASK_THERMO = 1
MASK_TRANSPORT = 2

# ---- saturation quantities (functions of T) -----------------------------------------------
SAT = Layout("property table saturation quantities")
_s = SAT.add
S_P = _s("pressure", "Pa", "pressure inside the dome (DmassT)")
S_LNRHOV = _s("ln_dew_density", "-", "ln of the dew density of the DmassT dome")
S_VL_DOME = _s("dome_liquid_volume", "m3/kg", "bubble specific volume of the DmassT dome")
S_HL_DOME = _s("dome_liquid_enthalpy", "J/kg", "h at quality 0 of the DmassT dome")
S_HV_DOME = _s("dome_vapour_enthalpy", "J/kg", "h at quality 1 of the DmassT dome")
S_VL = _s("liquid_volume", "m3/kg", "QT saturated liquid: specific volume")
S_VV = _s("vapour_volume", "m3/kg", "QT saturated vapour: specific volume")
S_DVL = _s("liquid_volume_slope", "m3/(kg K)", "QT saturated liquid: dv/dT")
S_DVV = _s("vapour_volume_slope", "m3/(kg K)", "QT saturated vapour: dv/dT")
S_UL = _s("liquid_energy", "J/kg", "QT saturated liquid: specific internal energy")
S_UV = _s("vapour_energy", "J/kg", "QT saturated vapour: specific internal energy")
S_DUL = _s("liquid_energy_slope", "J/(kg K)", "QT saturated liquid: du/dT")
S_DUV = _s("vapour_energy_slope", "J/(kg K)", "QT saturated vapour: du/dT")
S_DPSAT = _s("pressure_slope", "Pa/K", "dp_sat/dT")
S_MUV = _s("vapour_viscosity", "Pa s", "saturated vapour dynamic viscosity")
S_KV = _s("vapour_conductivity", "W/(m K)", "saturated vapour thermal conductivity")
S_CPV = _s("vapour_cp", "J/(kg K)", "saturated vapour isobaric specific heat")
#: the liquid line's enthalpy by expansion in p (table_states.liquid_enthalpy)
S_DHDP_L = _s("liquid_dhdp", "m3/kg", "saturated liquid (dh/dp)_T")
S_D2HDP2_L = _s("liquid_d2hdp2", "m3/(kg Pa)", "saturated liquid (d2h/dp2)_T")
S_D3HDP3_L = _s("liquid_d3hdp3", "m3/(kg Pa2)", "saturated liquid (d3h/dp3)_T")
N_SAT = SAT.size

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
    #: The entropy sums of the table (:func:`.table_entropy.entropy_tables`), cached with
    #: it; None: computed where needed.
    entropy: np.ndarray | None = field(default=None, repr=False, compare=False)
    #: Buffers handed out by :meth:`property_buffer`, reused once nothing else holds them.
    _buffers: list[np.ndarray] = field(default_factory=list, repr=False, compare=False)
    #: ``id`` of the kept buffers whose tail already holds :attr:`data` (a kept buffer
    #: lives as long as the table, so its ``id`` names it)
    _filled: set[int] = field(default_factory=set, repr=False, compare=False)

    def __getstate__(self) -> dict[str, Any]:
        """Pickled (to sweep workers) without the reusable buffers."""
        state = dict(self.__dict__)
        state["_buffers"] = []
        state["_filled"] = set()
        return state

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

    def property_buffer(self, transport: bool) -> np.ndarray:
        """A whole property buffer: ``N_PROPS`` zeroed outputs, then :attr:`data` with
        the transport flag set, as ``np.concatenate([np.zeros(N_PROPS),
        self.buffer_tail(transport)])`` gives, in one copy.

        The memory of an earlier buffer that nothing but this table holds any more is
        reused (a model build otherwise allocates, page-faults and frees 11 MB twice).
        A reused buffer's tail already holds :attr:`data`: the compiled code and the
        property callback write only the outputs, so only the outputs and the
        transport flag are written again (a sweep builds a model per point). A reused
        buffer equals a new one.

        Parameters
        ----------
        transport : bool
            Fill viscosity, conductivity and c_p.
        """
        buf = reusable_buffer(self._buffers, N_PROPS + self.data.size)
        buf[:N_PROPS] = 0.0
        if id(buf) not in self._filled:
            buf[N_PROPS:] = self.data
            if any(kept is buf for kept in self._buffers):
                self._filled.add(id(buf))
        buf[N_PROPS + H_TRANSPORT] = 1.0 if transport else 0.0
        return buf


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
    :class:`recipsim.physics.thermo.properties.HeosProperties` (mixture values in the dome).

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


#: random states per region for the error measured when a table is built
ERROR_SAMPLES = 200
