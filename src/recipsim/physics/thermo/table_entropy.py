"""Specific entropy of a single-phase state from a property table.

The table holds no entropy: it is integrated from an anchor state whose HEOS entropy the
table stores (hottest node, low density), along the anchor isotherm
``ds = -(dp/dT)_rho / rho d(ln rho)``, then down the state's isochore
``ds = c_v / T dT``. Every vapour state is reached without crossing the dome. The
integrands are the table's own piecewise cubics, integrated cell by cell with
three-point Gauss-Legendre (exact for the cubic isotherm integrand).
:func:`table_entropy_path` evaluates that definition directly (40-80 us: about 3 x 300
table evaluations down a 300-node isochore).

:func:`table_entropy` gives the same value (to rounding, about 1e-15 relative) in about
1 us from :func:`entropy_tables`, computed once per table (about 1 ms):

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
    _hermite,
    _line,
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


@njit(cache=True)
def _dome_limit(temperature, buf) -> float:
    """Largest ln(rho) (exclusive) at which :func:`table_props` gives a single-phase
    answer at ``temperature`` as far as the dome is concerned (its dew line, the
    near-critical band); ``-inf`` where it has no saturation data."""
    b = N_PROPS
    if temperature < buf[b + H_TSAT_MAX]:
        ns = int(buf[b + H_NS])
        s = (temperature - buf[b + H_TS0]) / buf[b + H_DTS]
        k = min(max(int(s), 0), ns - 2)
        h00, h10, h01, h11 = _hermite(s - k)
        r0 = int(buf[b + H_OFF_SAT]) + k * 2 * N_SAT
        limit = _line(buf, r0 + 2 * S_LNRHOV, r0 + 2 * N_SAT + 2 * S_LNRHOV, h00, h10, h01, h11)
        return limit if limit == limit else -math.inf
    if temperature < buf[b + H_TCRIT]:
        return buf[b + H_LNRHOV_BAND]
    return math.inf


@njit(cache=True)
def _anchor_isotherm(buf, anchor) -> None:
    """``anchor[q]``: integral of ``(dp/dT)_rho / rho`` along the anchor isotherm from the
    anchor's ln(rho) to node ``q`` (signed; NaN beyond a cell that does not answer)."""
    b = N_PROPS
    nx = anchor.shape[0]
    t_a, x_a, x0, dx = buf[b + H_S_T], buf[b + H_S_X], buf[b + H_X0], buf[b + H_DX]
    acc, prev = 0.0, x_a
    for q in range(nx):
        xq = x0 + q * dx
        if xq >= x_a:
            if xq > prev:
                acc += _segment_isotherm(t_a, prev, xq, buf)
            anchor[q], prev = acc, xq
    acc, prev = 0.0, x_a
    for q in range(nx - 1, -1, -1):
        xq = x0 + q * dx
        if xq < x_a:
            acc -= _segment_isotherm(t_a, xq, prev, buf)
            anchor[q], prev = acc, xq


@njit(cache=True)
def entropy_tables(buf) -> np.ndarray:
    """The sums :func:`table_entropy` reads (layout ``E_*``), for the table in ``buf``.

    Computed once per table (about 1 ms); a cell answers as :func:`table_props` does for
    the transport flag ``buf`` has now.
    """
    b = N_PROPS
    nt, nx = int(buf[b + H_NT]), int(buf[b + H_NX])
    t0, dt, t_a = buf[b + H_T0], buf[b + H_DT], buf[b + H_S_T]
    rows = nt + 1
    off_a = N_ENTROPY_HEADER
    off_l = off_a + nx
    off_p = off_l + rows * (nx - 1)
    off_r = off_p + rows * nx
    ent = np.empty(off_r + rows * nx)
    ent[E_ROWS], ent[E_NX] = rows, nx
    ent[E_OFF_ANCHOR], ent[E_OFF_LIMIT], ent[E_OFF_P], ent[E_OFF_R] = off_a, off_l, off_p, off_r
    _anchor_isotherm(buf, ent[off_a : off_a + nx])
    limit = ent[off_l:off_p].reshape((rows, nx - 1))
    p_sum = ent[off_p:off_r].reshape((rows, nx))
    r_sum = ent[off_r:].reshape((rows, nx))
    stride = 4 * N_GRID
    grid, mask = int(buf[b + H_OFF_GRID]) + 4 * G_CV, int(buf[b + H_OFF_MASK])
    transport = buf[b + H_TRANSPORT] != 0.0
    p_row, r_row, l_row = np.zeros(nx), np.zeros(nx), np.full(nx - 1, math.inf)
    for m in range(rows - 1, -1, -1):
        # row m of the path: [t0 + m dt, t0 + (m + 1) dt], clipped at the anchor
        lo, hi = min(t0 + m * dt, t_a), min(t0 + (m + 1) * dt, t_a)
        p_row[:] = 0.0
        r_row[:] = 0.0
        for g in range(3 if hi > lo else 0):
            t = lo + _GL_X[g] * (hi - lo)
            gt = (t - t0) / dt
            i = min(max(int(gt), 0), nt - 2)
            a0, c0, a1, c1 = _hermite(gt - i)
            w = _GL_W[g] / t
            for q in range(nx):
                n0 = grid + (i * nx + q) * stride
                n1 = n0 + nx * stride
                p_row[q] += w * (a0 * buf[n0] + c0 * buf[n0 + 1] + a1 * buf[n1] + c1 * buf[n1 + 1])
                r_row[q] += w * (
                    a0 * buf[n0 + 2] + c0 * buf[n0 + 3] + a1 * buf[n1 + 2] + c1 * buf[n1 + 3]
                )
            dome = _dome_limit(t, buf)
            for j in range(nx - 1):
                cell = buf[mask + i * (nx - 1) + j]
                if cell == 0.0 or (transport and cell != MASK_THERMO + MASK_TRANSPORT):
                    l_row[j] = -math.inf
                else:
                    l_row[j] = min(l_row[j], dome)
        for q in range(nx):
            p_row[q] = p_row[q] * (hi - lo) + (p_sum[m + 1, q] if m + 1 < rows else 0.0)
            r_row[q] = r_row[q] * (hi - lo) + (r_sum[m + 1, q] if m + 1 < rows else 0.0)
        p_sum[m, :] = p_row
        r_sum[m, :] = r_row
        limit[m, :] = l_row  # l_row keeps the minimum over the rows above
    return ent


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
