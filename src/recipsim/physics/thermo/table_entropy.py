"""Specific entropy of a single-phase state from a property table.

The table holds no entropy: it is integrated from an anchor state whose HEOS entropy the
table stores (hottest node, low density), along the anchor isotherm
``ds = -(dp/dT)_rho / rho d(ln rho)``, then down the state's isochore
``ds = c_v / T dT``. Every vapour state is reached without crossing the dome. The
integrands are the table's own piecewise cubics, integrated cell by cell with
three-point Gauss-Legendre (exact for the cubic isotherm integrand).
:func:`table_entropy_path` evaluates that definition directly (about 3 x 300 table
evaluations down a 300-node isochore).

:func:`table_entropy` gives the same value (to rounding, about 1e-15 relative) from the
sums of :func:`entropy_tables`, computed once per table and cached with it
(:func:`table_entropy_sums`):

* along the anchor isotherm, the integral from the anchor to every ln(rho) node; a state
  adds the integral within its cell;
* down the isochore, the Gauss-Legendre sum over a whole temperature row of a cell is
  linear in the node data of the cell's two ln(rho) edges: with the Hermite weights
  ``b0, d0, b1, d1`` of the state's ln(rho) in its cell,
  ``sum = b0 P[j] + d0 R[j] + b1 P[j+1] + d1 R[j+1]``, where ``P[q]`` is the sum over
  ``c_v / T`` of node line ``q`` and ``R[q]`` the same over its ln(rho) derivative. The
  table stores these sums accumulated from the anchor temperature down to every row;
  a state adds the partial row it lies in.

Where the definition's path leaves the table (a cell that is not tabulated, the dome, the
near-critical band) both return NaN: the table stores, for every row and ln(rho) cell,
the lowest dome limit in ln(rho) that the path from there up to the anchor meets
(``-inf`` for a cell that does not answer).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from recipsim.physics.layout_table import Layout
from recipsim.physics.thermo.property_slots import (
    N_PROPS,
    PROP_CV,
    PROP_DPDT,
    PROP_QUALITY,
    STATUS_OK,
)
from recipsim.physics.thermo.property_table import (
    G_CV,
    G_DPDT_RHO,
    H_DT,
    H_DTS,
    H_DX,
    H_LNRHOV_BAND,
    H_NS,
    H_NT,
    H_NX,
    H_OFF_GRID,
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
    N_SAT,
    S_LNRHOV,
    PropertyTable,
    _hermite,
    table_props,
)

# three-point Gauss-Legendre on [0, 1]
_GL_X = np.array([0.5 - math.sqrt(0.15), 0.5, 0.5 + math.sqrt(0.15)])
_GL_W = np.array([5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0])

# ---- layout of the entropy tables (:func:`entropy_tables`) ---------------------------------
ENTROPY = Layout("property table entropy sums")
_e = ENTROPY.add
E_ROWS = _e("rows", "count", "temperature rows: grid nodes + 1")
E_NX = _e("x_nodes", "count", "ln(rho) nodes")
E_OFF_ANCHOR = _e("anchor_offset", "index", "anchor isotherm integral to each ln(rho) node")
E_OFF_LIMIT = _e("limit_offset", "index", "per row and ln(rho) cell: dome limit in ln(rho)")
E_OFF_P = _e("p_offset", "index", "per row and node line: c_v / T summed up to the anchor")
E_OFF_R = _e("r_offset", "index", "per row and node line: the same of d(c_v)/d(ln rho)")
N_ENTROPY_HEADER = ENTROPY.size


@njit(cache=True, inline="always")
def single_phase(temperature, density, buf) -> bool:
    """The table's outputs at (T, rho) into ``buf``; False outside its single phase."""
    return table_props(temperature, density, buf) == STATUS_OK and buf[PROP_QUALITY] < 0.0


@njit(cache=True, inline="always")
def _segment_isotherm(temperature, x0, x1, buf) -> float:
    """Integral of ``(dp/dT)_rho / rho`` over ln(rho) from x0 to x1 at ``temperature``."""
    total = 0.0
    for q in range(3):
        x = x0 + _GL_X[q] * (x1 - x0)
        if not single_phase(temperature, math.exp(x), buf):
            return math.nan
        total += _GL_W[q] * buf[PROP_DPDT] / math.exp(x)
    return total * (x1 - x0)


@njit(cache=True, inline="always")
def _segment_isochore(density, t0, t1, buf) -> float:
    """Integral of ``c_v / T`` over T from t0 to t1 at ``density``."""
    total = 0.0
    for q in range(3):
        t = t0 + _GL_X[q] * (t1 - t0)
        if not single_phase(t, density, buf):
            return math.nan
        total += _GL_W[q] * buf[PROP_CV] / t
    return total * (t1 - t0)


@njit(cache=True)
def table_entropy_path(temperature, density, buf) -> float:
    """Specific entropy [J/(kg K)] by the path integral itself (the definition; slow).

    Integrated from the table's anchor (see the module docstring) in pieces that follow
    the grid lines, so each piece sees one cubic; NaN where the path leaves the table.
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


def _anchor_isotherm(buf: np.ndarray, nx: int) -> np.ndarray:
    """Integral of ``(dp/dT)_rho / rho`` along the anchor isotherm from the anchor's ln(rho)
    to every ln(rho) node (signed; NaN beyond a cell that does not answer).

    Cell by cell with the Gauss-Legendre nodes of :func:`_segment_isotherm` (exact: the
    integrand is the table's cubic in ln(rho)), in numpy.
    """
    b = N_PROPS
    nt = int(buf[b + H_NT])
    t0, dt, x0, dx = (float(buf[b + h]) for h in (H_T0, H_DT, H_X0, H_DX))
    t_a, x_a = float(buf[b + H_S_T]), float(buf[b + H_S_X])
    gt = (t_a - t0) / dt
    i = min(max(int(gt), 0), nt - 2)
    a0, c0, a1, c1 = _hermite_weights(np.array(gt - i))
    # the integrand's node values along the isotherm: (f, f_u) at every ln(rho) node
    stride = 4 * N_GRID
    grid = int(buf[b + H_OFF_GRID])
    g = buf[grid : grid + nt * nx * stride].reshape(nt, nx, N_GRID, 4)[:, :, G_DPDT_RHO, :]
    f = a0 * g[i, :, 0] + c0 * g[i, :, 1] + a1 * g[i + 1, :, 0] + c1 * g[i + 1, :, 1]
    fu = a0 * g[i, :, 2] + c0 * g[i, :, 3] + a1 * g[i + 1, :, 2] + c1 * g[i + 1, :, 3]
    b0, d0, b1, d1 = _hermite_weights(_GL_X)
    cells = (
        _GL_W @ (b0[:, None] * f[None, :-1] + d0[:, None] * fu[None, :-1])
        + _GL_W @ (b1[:, None] * f[None, 1:] + d1[:, None] * fu[None, 1:])
    ) * dx
    # a cell answers where table_props does at the anchor temperature
    mask_off = int(buf[b + H_OFF_MASK])
    mask = buf[mask_off + i * (nx - 1) : mask_off + (i + 1) * (nx - 1)]
    bad = mask == 0.0
    if buf[b + H_TRANSPORT] != 0.0:
        bad |= mask != MASK_THERMO + MASK_TRANSPORT
    x_top = x0 + (np.arange(nx - 1) + _GL_X[2]) * dx  # the highest node of each cell
    bad |= ~(x_top < _dome_limits(np.array([t_a]), buf)[0])
    cells[bad] = np.nan
    # signed sums from the anchor's node
    q_a = int(round((x_a - x0) / dx))
    anchor = np.zeros(nx)
    anchor[q_a + 1 :] = np.cumsum(cells[q_a:])
    anchor[:q_a] = -np.cumsum(cells[:q_a][::-1])[::-1]
    return anchor


def _hermite_weights(t: np.ndarray) -> tuple[np.ndarray, ...]:
    """:func:`.property_table._hermite` of an array (the same operations)."""
    t2 = t * t
    t3 = t2 * t
    return 2.0 * t3 - 3.0 * t2 + 1.0, t3 - 2.0 * t2 + t, 3.0 * t2 - 2.0 * t3, t3 - t2


def _dome_limits(temps: np.ndarray, buf: np.ndarray) -> np.ndarray:
    """Largest ln(rho) (exclusive) at which :func:`table_props` gives a single-phase
    answer at ``temps`` as far as the dome is concerned (its dew line below the
    saturation table's end, the near-critical band up to the critical temperature);
    ``-inf`` where it has no saturation data."""
    b = N_PROPS
    ns = int(buf[b + H_NS])
    s = (temps - buf[b + H_TS0]) / buf[b + H_DTS]
    k = np.clip(s.astype(np.int64), 0, ns - 2)
    h00, h10, h01, h11 = _hermite_weights(s - k)
    r0 = int(buf[b + H_OFF_SAT]) + k * 2 * N_SAT + 2 * S_LNRHOV
    r1 = r0 + 2 * N_SAT
    dew = h00 * buf[r0] + h10 * buf[r0 + 1] + h01 * buf[r1] + h11 * buf[r1 + 1]
    dew = np.where(np.isnan(dew), -np.inf, dew)
    band = np.where(temps < buf[b + H_TCRIT], buf[b + H_LNRHOV_BAND], np.inf)
    return np.where(temps < buf[b + H_TSAT_MAX], dew, band)


def table_entropy_sums(table: PropertyTable, buf: np.ndarray | None = None) -> np.ndarray:
    """The entropy sums of ``table`` (:func:`entropy_tables`): those it holds (read with
    it from the cache), else computed now, from ``buf`` if given (a property buffer of
    the table without transport), and kept on it."""
    if table.entropy is None:
        table.entropy = entropy_tables(
            table.property_buffer(transport=False) if buf is None else buf
        )
    return table.entropy


def entropy_tables(buf: np.ndarray) -> np.ndarray:
    """The sums :func:`table_entropy` reads (layout ``E_*``), for the table in ``buf``.

    Computed once per table (in numpy, so that no further compiled function is built
    on a first run); a cell answers as :func:`table_props` does for the transport
    flag ``buf`` has now.

    Parameters
    ----------
    buf : ndarray
        Property buffer with the table (its outputs are overwritten).

    Returns
    -------
    ndarray
        Header ``E_*``, then the anchor isotherm's integrals (one per ln(rho) node), the
        limits (rows x ln(rho) cells), the sums of ``c_v / T`` and of its ln(rho)
        derivative (rows x ln(rho) nodes) [J/(kg K)].
    """
    b = N_PROPS
    nt, nx = int(buf[b + H_NT]), int(buf[b + H_NX])
    t0, dt, t_a = float(buf[b + H_T0]), float(buf[b + H_DT]), float(buf[b + H_S_T])
    rows = nt + 1
    # row m of the path: [t0 + m dt, t0 + (m + 1) dt] clipped at the anchor, and the
    # cell row that table_props reads at each of its three Gauss-Legendre points
    m = np.arange(rows)
    lo, hi = np.minimum(t0 + m * dt, t_a), np.minimum(t0 + (m + 1) * dt, t_a)
    temps = lo[:, None] + _GL_X[None, :] * (hi - lo)[:, None]
    gt = (temps - t0) / dt
    i = np.clip(gt.astype(np.int64), 0, nt - 2)
    a0, c0, a1, c1 = _hermite_weights(gt - i)
    stride = 4 * N_GRID
    grid = int(buf[b + H_OFF_GRID])
    cv = buf[grid : grid + nt * nx * stride].reshape(nt, nx, N_GRID, 4)[:, :, G_CV, :]
    below, above = cv[i], cv[i + 1]  # (rows, 3, nx, 4): f, f_t, f_u, f_tu

    def row_sums(f: int, ft: int) -> np.ndarray:
        w = (_GL_W[None, :] / temps)[:, :, None]
        terms = (a0[:, :, None] * below[..., f] + c0[:, :, None] * below[..., ft]) + (
            a1[:, :, None] * above[..., f] + c1[:, :, None] * above[..., ft]
        )
        return (w * terms).sum(axis=1) * (hi - lo)[:, None]

    p_sum = np.cumsum(row_sums(0, 1)[::-1], axis=0)[::-1]
    r_sum = np.cumsum(row_sums(2, 3)[::-1], axis=0)[::-1]
    mask_off = int(buf[b + H_OFF_MASK])
    cells = buf[mask_off : mask_off + (nt - 1) * (nx - 1)].reshape(nt - 1, nx - 1)[i]
    bad = cells == 0.0
    if buf[b + H_TRANSPORT] != 0.0:
        bad |= cells != MASK_THERMO + MASK_TRANSPORT
    limits = np.where(bad, -np.inf, _dome_limits(temps, buf)[:, :, None]).min(axis=1)
    limits[hi <= lo] = np.inf
    limits = np.minimum.accumulate(limits[::-1], axis=0)[::-1]
    header = np.zeros(N_ENTROPY_HEADER)
    off_a = N_ENTROPY_HEADER
    header[E_ROWS], header[E_NX] = rows, nx
    header[E_OFF_ANCHOR], header[E_OFF_LIMIT] = off_a, off_a + nx
    header[E_OFF_P] = off_a + nx + limits.size
    header[E_OFF_R] = header[E_OFF_P] + p_sum.size
    return np.concatenate(
        [header, _anchor_isotherm(buf, nx), limits.ravel(), p_sum.ravel(), r_sum.ravel()]
    )


@njit(cache=True)
def table_entropy(temperature, density, buf, ent) -> float:
    """Specific entropy [J/(kg K)] of a single-phase state (the path integral of
    :func:`table_entropy_path`, to rounding) from the table in ``buf`` and its sums
    ``ent`` (:func:`entropy_tables`); NaN where the path leaves the table.

    Parameters
    ----------
    temperature : float
        [K]
    density : float
        [kg/m3]
    buf : ndarray
        Property buffer with the table (its outputs are overwritten).
    ent : ndarray
        :func:`entropy_tables` of the same table.
    """
    b = N_PROPS
    if not (density > 0.0) or not (buf[b + H_TMIN] <= temperature <= buf[b + H_TMAX]):
        return math.nan
    x = math.log(density)
    nx = int(buf[b + H_NX])
    x0, dx = buf[b + H_X0], buf[b + H_DX]
    gx = (x - x0) / dx
    if not (0.0 <= gx <= nx - 1):
        return math.nan
    j = min(int(gx), nx - 2)
    # anchor isotherm: the integral to node j, then within cell j
    t_a = buf[b + H_S_T]
    xj = x0 + j * dx
    iso = ent[int(ent[E_OFF_ANCHOR]) + j]
    if x > xj:
        iso += _segment_isotherm(t_a, xj, x, buf)
    elif x < xj:
        iso -= _segment_isotherm(t_a, x, xj, buf)
    # isochore: the partial row the state lies in, then the rows above (sums)
    t0, dt = buf[b + H_T0], buf[b + H_DT]
    k = int(math.floor((temperature - t0) / dt))
    end = min(t0 + (k + 1) * dt, t_a)
    down = _segment_isochore(density, temperature, end, buf) if end > temperature else 0.0
    rows = int(ent[E_ROWS])
    m = min(max(k + 1, 0), rows - 1)
    if not (x < ent[int(ent[E_OFF_LIMIT]) + m * (nx - 1) + j]):
        return math.nan
    b0, d0, b1, d1 = _hermite(gx - j)
    n = m * nx + j
    p_sum, r_sum = int(ent[E_OFF_P]) + n, int(ent[E_OFF_R]) + n
    down += b0 * ent[p_sum] + d0 * ent[r_sum] + b1 * ent[p_sum + 1] + d1 * ent[r_sum + 1]
    return buf[b + H_S_VALUE] - iso - down
