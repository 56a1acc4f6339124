"""Impedance tables of the finite-length journal bearing: Reynolds solutions, built once
per length-to-diameter ratio and cached.

The film equation in the frame of the line of centres (mechanics-notes 2.1-2.2), with
``theta`` from the thickest film, ``H = 1 + eps cos theta``, ``zeta = z/L`` in
``[-1/2, 1/2]`` and the wedge/squeeze direction ``A sin theta - B cos theta = V sin(theta
- theta0)``, is, for the scaled pressure ``P = p c^2/(mu V L^2)``::

    4 (L/D)^2 d/dtheta(H^3 dP/dtheta) + d/dzeta(H^3 dP/dzeta) = -12 sin(theta - theta0)

with ``P = 0`` at the ends, periodic in theta, and Swift-Stieber (Reynolds) cavitation
``P >= 0`` solved as a complementarity problem by projected SOR. For fixed ``(eps,
theta0)`` the problem is linear in V, so the force is ``mu R L^3 V/c^2`` times the two
numbers ``f = (f_r, f_t) = integral of P (cos theta, sin theta)``; as ``L/D -> 0`` they tend
to the short-bearing ones (:func:`~recipsim.physics.mechanics.journal.short_film_unit_forces`).

Discretisation: conservative finite differences, node-centred, on a theta grid
``theta(xi) = pi + 2 atan(a tan((xi - pi)/2))`` (uniform in xi) that clusters nodes around
the thinnest film (density ``1/a`` there, ``a = max(0.2, sqrt(1 - eps))``), half the
length by symmetry, Simpson in zeta and the (spectrally accurate, periodic) trapezoid in
xi for the forces. With 128 x 12 nodes the forces are within about 0.2 % of the
grid-converged values at eps = 0.9 and 0.7 % at eps = 0.99 (L/D 1.25).

The table stores the complex ratio ``Q = (f_r + i f_t)_finite / (f_r + i f_t)_short`` on
a grid of ``u = -ln(1 - eps)`` (uniform, so eps clusters toward 1) times ``theta0``
(uniform, periodic), with its spline derivatives for a C1 bicubic Hermite interpolation
(:mod:`.journal_finite`). The short force never vanishes for V > 0 (its dissipation
``A F_t - B F_r`` is positive), so Q has no poles, is 1 in the short limit and smooth
where the force itself changes sharply with theta0 (at high eps the film's end crossing
the thinnest film). The mirror symmetry ``A -> -A`` gives ``Q(pi - theta0) =
conj(Q(theta0))``: only half the theta0 values are solved.

Flat table layout (float64, self-describing; ``offset`` is where it starts in a larger
array): the :data:`HEADER` (``H_*``), then for each eps node j and theta0 node m the
:data:`NODE` values (the :data:`QUANTITIES` ``Q_r, Q_i`` and the peak-pressure ratio,
then their d/du, d/dtheta0 and d2/du dtheta0) at ``N_HEADER + (j n_theta0 + m)
N_NODE_VALUES``. A table: 33 x 33 warm-started Reynolds solutions of 128 x 12 nodes.
"""

from __future__ import annotations

import hashlib
import json
import math
import warnings
import zipfile
from pathlib import Path
from typing import Any

import numpy as np
from numba import njit

from recipsim.atomic import atomic_write
from recipsim.cache_dirs import cache_dir, private_dir
from recipsim.physics.layout_table import Layout
from recipsim.physics.mechanics.journal import film_peak_shape, short_film_unit_forces
from recipsim.progress import timed_step

#: Table format identifier (``table[offset + H_FORMAT]``).
TABLE_FORMAT = 1.0
HEADER = Layout("journal table header")
_h = HEADER.add
H_FORMAT = _h("format", "code", "format identifier (TABLE_FORMAT)")
H_LENGTH = _h("length", "count", "total length of the table, header included")
H_LENGTH_OVER_DIAMETER = _h("length_over_diameter", "-", "L/D the table was built for")
H_N_EPS = _h("eps_nodes", "count", "number of eps nodes")
H_N_THETA0 = _h("theta0_nodes", "count", "number of theta0 nodes (over 2 pi)")
H_U_MAX = _h("u_max", "-", "last eps node in u = -ln(1 - eps)")
H_THETA0_START = _h("theta0_start", "rad", "first theta0 node")
H_RESERVED = _h("reserved", "-", "spare slot: nothing is stored there")
N_HEADER = HEADER.size
QUANTITIES = Layout("journal table quantities")
JQ_REAL = QUANTITIES.add("impedance_ratio_real", "-", "Q_r, real part of the force ratio")
JQ_IMAG = QUANTITIES.add("impedance_ratio_imag", "-", "Q_i, imaginary part of the force ratio")
JQ_PEAK = QUANTITIES.add("peak_pressure_ratio", "-", "peak film pressure ratio")
N_QUANTITIES = QUANTITIES.size
#: Values per node: the quantities, then their d/du, d/dtheta0 and d2/du dtheta0.
NODE = Layout("journal table node values")
NODE.add_rows(QUANTITIES, ("value", "d_du", "d_dtheta0", "d2_du_dtheta0"))
N_NODE_VALUES = NODE.size
#: Version of the cache file's layout (key, data, checksum).
CACHE_FORMAT = 1

#: Grid of the tables: eps nodes uniform in u = -ln(1 - eps) on [0, -ln(1 - EPS_MAX)], the
#: theta0 nodes uniform over a period starting at -pi/2; Reynolds grid per solution.
EPS_MAX = 0.99
N_EPS = 33
N_THETA0 = 64
N_GRID_THETA = 128
N_GRID_ZETA = 12
THETA0_START = -0.5 * math.pi
#: Projected SOR stops when a sweep changes P by less than this fraction of its peak.
SOR_TOLERANCE = 1e-8

#: Range of L/D that tables may be built for (the finite law is tested on 0.3-1.5).
LENGTH_OVER_DIAMETER_RANGE = (0.02, 3.0)


@njit(cache=True)
def _theta_map(xi: float, a: float) -> tuple[float, float]:
    """Clustered grid: theta(xi) [rad] and d theta/d xi [-]."""
    s = 0.5 * (xi - math.pi)
    sn = math.sin(s)
    cs = math.cos(s)
    return math.pi + 2.0 * math.atan2(a * sn, cs), a / (cs * cs + a * a * sn * sn)


@njit(cache=True)
def reynolds_unit_forces(
    eps: float,
    theta0: float,
    length_over_diameter: float,
    pressure: np.ndarray,
    tolerance: float,
    max_sweeps: int,
) -> tuple[float, float, float, int]:
    """Finite-length film forces per unit ``mu R L^3 V/c^2`` by projected SOR.

    Parameters
    ----------
    eps : float
        Eccentricity ratio, ``0 <= eps < 1`` [-].
    theta0 : float
        Film direction, ``atan2(B, A)`` [rad].
    length_over_diameter : float
        L/D [-].
    pressure : numpy.ndarray
        Scaled pressure P on the (n_theta, n_zeta) grid [-]: the start (warm start) and,
        on return, the solution. Node (i, k) is at ``xi = 2 pi i/n_theta``, ``zeta =
        k/(2 n_zeta)``; n_zeta must be even (Simpson).
    tolerance : float
        Stop when a sweep changes no node by more than ``tolerance`` times the largest P.
    max_sweeps : int
        Limit on the sweeps.

    Returns
    -------
    fr, ft : float
        Radial and tangential force on the journal [-].
    peak : float
        Largest P on the grid [-].
    sweeps : int
        Sweeps used (``max_sweeps`` if not converged).
    """
    n_theta, n_zeta = pressure.shape
    a = min(1.0, max(0.2, math.sqrt(1.0 - eps)))
    lam = 4.0 * length_over_diameter * length_over_diameter
    dxi = 2.0 * math.pi / n_theta
    dzeta = 0.5 / n_zeta
    west = np.empty(n_theta)
    east = np.empty(n_theta)
    axial = np.empty(n_theta)
    source = np.empty(n_theta)
    inv_diag = np.empty(n_theta)
    cos_t = np.empty(n_theta)
    sin_t = np.empty(n_theta)
    for i in range(n_theta):
        theta, slope = _theta_map(i * dxi, a)
        theta_w, slope_w = _theta_map((i - 0.5) * dxi, a)
        theta_e, slope_e = _theta_map((i + 0.5) * dxi, a)
        west[i] = lam * (1.0 + eps * math.cos(theta_w)) ** 3 / (slope_w * dxi)
        east[i] = lam * (1.0 + eps * math.cos(theta_e)) ** 3 / (slope_e * dxi)
        axial[i] = slope * dxi * (1.0 + eps * math.cos(theta)) ** 3 / (dzeta * dzeta)
        source[i] = -12.0 * slope * dxi * math.sin(theta - theta0)
        inv_diag[i] = 1.0 / (west[i] + east[i] + 2.0 * axial[i])
        cos_t[i] = math.cos(theta) * slope * dxi
        sin_t[i] = math.sin(theta) * slope * dxi
    relax = min(1.95, 2.0 / (1.0 + math.sin(math.pi / n_theta)))
    sweeps = max_sweeps
    last = n_zeta - 1
    for sweep in range(max_sweeps):
        change = 0.0
        largest = 0.0
        for i in range(n_theta):
            iw = i - 1 if i > 0 else n_theta - 1
            ie = i + 1 if i < n_theta - 1 else 0
            cw = west[i] * inv_diag[i]
            ce = east[i] * inv_diag[i]
            cz = axial[i] * inv_diag[i]
            cs = source[i] * inv_diag[i]
            row = pressure[i]
            row_w = pressure[iw]
            row_e = pressure[ie]
            below = row[1]  # symmetry plane: the node below zeta = 0 mirrors node 1
            for k in range(n_zeta):
                above = row[k + 1] if k < last else 0.0
                old = row[k]
                star = cw * row_w[k] + ce * row_e[k] + cz * (above + below) - cs
                new = old + relax * (star - old)
                if new < 0.0:
                    new = 0.0
                step = abs(new - old)
                if step > change:
                    change = step
                if new > largest:
                    largest = new
                row[k] = new
                below = new
        if change <= tolerance * largest:
            sweeps = sweep + 1
            break
    fr = 0.0
    ft = 0.0
    for i in range(n_theta):
        column = pressure[i, 0]
        for k in range(1, n_zeta):
            column += (4.0 if k % 2 == 1 else 2.0) * pressure[i, k]
        column *= 2.0 * dzeta / 3.0  # Simpson over [0, 1/2], both halves
        fr += column * cos_t[i]
        ft += column * sin_t[i]
    return fr, ft, largest, sweeps


@njit(cache=True)
def impedance_ratios(
    length_over_diameter: float,
    eps_nodes: np.ndarray,
    theta0_nodes: np.ndarray,
    n_grid_theta: int,
    n_grid_zeta: int,
    tolerance: float,
    ratios: np.ndarray,
) -> int:
    """Fill ``ratios[j, m] = (Q_r, Q_i, peak ratio)`` at ``(eps_nodes[j], theta0_nodes[m])``.

    The peak ratio is the largest finite-bearing pressure over the short bearing's.
    ``theta0_nodes`` must be uniform over a period from -pi/2 with an even count, so that
    node ``n - m`` is the mirror ``pi - theta0`` of node m: nodes ``0 .. n/2`` are solved
    (each warm-started from the previous one), the others are their mirrors. Returns the
    total number of SOR sweeps.
    """
    n_theta0 = theta0_nodes.size
    pressure = np.zeros((n_grid_theta, n_grid_zeta))
    total = 0
    for j in range(eps_nodes.size):
        eps = eps_nodes[j]
        pressure[:, :] = 0.0
        for m in range(n_theta0 // 2 + 1):
            theta0 = theta0_nodes[m]
            fr, ft, peak, sweeps = reynolds_unit_forces(
                eps, theta0, length_over_diameter, pressure, tolerance, 100000
            )
            total += sweeps
            sr, st = short_film_unit_forces(eps, math.sin(theta0), math.cos(theta0))
            norm = sr * sr + st * st
            ratios[j, m, JQ_REAL] = (fr * sr + ft * st) / norm
            ratios[j, m, JQ_IMAG] = (ft * sr - fr * st) / norm
            ratios[j, m, JQ_PEAK] = peak / (1.5 * film_peak_shape(eps, theta0))
        for m in range(n_theta0 // 2 + 1, n_theta0):
            ratios[j, m, JQ_REAL] = ratios[j, n_theta0 - m, JQ_REAL]
            ratios[j, m, JQ_IMAG] = -ratios[j, n_theta0 - m, JQ_IMAG]
            ratios[j, m, JQ_PEAK] = ratios[j, n_theta0 - m, JQ_PEAK]
    return total


# ======================================================================================
# building and caching (not compiled)
# ======================================================================================


def build_journal_table(length_over_diameter: float) -> np.ndarray:
    """Solve the Reynolds problems of one L/D and return its flat table.

    Parameters
    ----------
    length_over_diameter : float
        L/D [-], within :data:`LENGTH_OVER_DIAMETER_RANGE`.

    Returns
    -------
    numpy.ndarray
        The flat float64 table (layout in the module docstring).
    """
    from scipy.interpolate import CubicSpline

    u_max = -math.log(1.0 - EPS_MAX)
    u_nodes = np.linspace(0.0, u_max, N_EPS)
    theta0_nodes = THETA0_START + np.arange(N_THETA0) * (2.0 * math.pi / N_THETA0)
    values = np.zeros((N_EPS, N_THETA0, N_QUANTITIES))
    impedance_ratios(
        float(length_over_diameter),
        -np.expm1(-u_nodes),
        theta0_nodes,
        N_GRID_THETA,
        N_GRID_ZETA,
        SOR_TOLERANCE,
        values,
    )
    closed = np.append(theta0_nodes, theta0_nodes[0] + 2.0 * math.pi)

    def d_theta0(y: np.ndarray) -> np.ndarray:
        periodic = np.concatenate([y, y[:, :1]], axis=1)
        spline = CubicSpline(closed, periodic, axis=1, bc_type="periodic")
        return np.asarray(spline(theta0_nodes, 1))

    d_u = np.asarray(CubicSpline(u_nodes, values, axis=0)(u_nodes, 1))
    blocks = np.stack([values, d_u, d_theta0(values), d_theta0(d_u)], axis=2)
    header = np.zeros(N_HEADER)
    header[H_FORMAT] = TABLE_FORMAT
    header[H_LENGTH] = N_HEADER + blocks.size
    header[H_LENGTH_OVER_DIAMETER] = length_over_diameter
    header[H_N_EPS] = N_EPS
    header[H_N_THETA0] = N_THETA0
    header[H_U_MAX] = u_max
    header[H_THETA0_START] = THETA0_START
    return np.concatenate([header, blocks.ravel()])


def cache_key(length_over_diameter: float) -> dict[str, Any]:
    """What a cached table depends on: L/D, grids, tolerance and formats."""
    return {
        "cache_format": CACHE_FORMAT,
        "table_format": TABLE_FORMAT,
        "length_over_diameter": float(length_over_diameter),
        "eps_max": EPS_MAX,
        "grid": [N_EPS, N_THETA0, N_GRID_THETA, N_GRID_ZETA],
        "sor_tolerance": SOR_TOLERANCE,
    }


def table_checksum(key_text: str, data: np.ndarray) -> str:
    """SHA-256 of a cached table's key and data."""
    digest = hashlib.sha256(key_text.encode())
    digest.update(np.ascontiguousarray(data, dtype="<f8").tobytes())
    return digest.hexdigest()


def cache_path(length_over_diameter: float, directory: Path | None = None) -> Path:
    """File of the cached table of one L/D."""
    key = json.dumps(cache_key(length_over_diameter), sort_keys=True)
    digest = hashlib.sha256(key.encode()).hexdigest()[:16]
    return (directory or cache_dir()) / "journal_tables" / f"journal-{digest}.npz"


def _read_cached(path: Path, key_text: str) -> np.ndarray | None:
    """The cached table, or None (with a warning if it is damaged or tampered with)."""
    try:
        with np.load(path, allow_pickle=False) as npz:
            if str(npz["key"]) != key_text:
                return None
            data = np.array(npz["data"], dtype=np.float64)
            checksum = str(npz["checksum"])
    except (OSError, ValueError, KeyError, EOFError, TypeError, zipfile.BadZipFile) as exc:
        why = f"unreadable ({type(exc).__name__})"
    else:
        if checksum == table_checksum(key_text, data):
            if data.ndim == 1 and data.size > N_HEADER and data[H_LENGTH] == data.size:
                return data
            why = "not shaped as a journal table"
        else:
            why = "its checksum does not match its content"
    warnings.warn(f"journal table cache {path}: {why}; rebuilding it", stacklevel=3)
    return None


def finite_journal_table(length_over_diameter: float, directory: Path | None = None) -> np.ndarray:
    """The flat impedance table of one L/D: from the cache, else built and cached.

    Parameters
    ----------
    length_over_diameter : float
        L/D [-], within :data:`LENGTH_OVER_DIAMETER_RANGE` (tested on 0.3-1.5).
    directory : Path, optional
        Cache directory (default :func:`recipsim.cache_dirs.cache_dir`); the table is
        in its ``journal_tables`` folder, written atomically with its inputs and a
        SHA-256 checksum. A missing, stale, unreadable or tampered file is rebuilt.

    Returns
    -------
    numpy.ndarray
        Flat float64 table for :func:`~recipsim.physics.mechanics.journal_finite.
        finite_journal_film` (layout in the module docstring).
    """
    low, high = LENGTH_OVER_DIAMETER_RANGE
    if not low <= length_over_diameter <= high:
        raise ValueError(f"L/D = {length_over_diameter} is outside {low}-{high}")
    key_text = json.dumps(cache_key(length_over_diameter), sort_keys=True)
    path = cache_path(length_over_diameter, directory)
    if path.is_file():
        cached = _read_cached(path, key_text)
        if cached is not None:
            return cached
    doing = f"building the finite journal-bearing table for L/D = {length_over_diameter:.4g}"
    with timed_step("journal-bearing table", doing, f"once; cached in {path.parent}"):
        data = build_journal_table(length_over_diameter)
    checksum = table_checksum(key_text, data)

    def write(tmp: Path) -> None:
        with open(tmp, "wb") as handle:
            np.savez(handle, key=np.asarray(key_text), data=data, checksum=np.asarray(checksum))

    private_dir(path.parent)
    atomic_write(path, write)
    return data
