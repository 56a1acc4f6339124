"""Independent finite-length journal-bearing solver, for tests only (numpy/scipy).

It shares nothing with ``recipsim.physics.mechanics.journal_table``: it solves the
Reynolds equation in the inertial frame, for the physical state (no reduction to the
wedge/squeeze direction), on a uniform cell-centred finite-volume grid over the whole
length, and handles Swift-Stieber cavitation (p >= 0, and zero flow divergence where
p > 0) with a primal-dual active-set iteration on sparse direct solves:

    (1/R^2) d/dalpha(h^3 dp/dalpha) + d/dz(h^3 dp/dz)
        = 6 mu (omega_j + omega_b) dh/dalpha + 12 mu dh/dt,

with ``h = c - e.n(alpha)``, ``dh/dt = -v.n(alpha)``, ``n = (cos alpha, sin alpha)``,
``p = 0`` at ``z = +-L/2``, periodic in alpha. The force on the journal is ``-integral
of p n R dalpha dz`` (midpoint rule).
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu


def reference_film_force(
    e: np.ndarray,
    v: np.ndarray,
    omega_journal: float,
    omega_bushing: float,
    radius: float,
    length: float,
    clearance: float,
    viscosity: float,
    n_alpha: int = 720,
    n_z: int = 24,
) -> tuple[np.ndarray, float]:
    """Film force on the journal [N] and the largest cell pressure [Pa].

    The active set is first found on grids coarser in alpha (halving down to about 90
    cells), each starting from the previous one's, since the iteration moves the
    cavitation boundary by about one cell per step."""
    levels = [n_alpha]
    while levels[-1] % 2 == 0 and levels[-1] >= 180:
        levels.append(levels[-1] // 2)
    free = None
    args = (e, v, omega_journal, omega_bushing, radius, length, clearance, viscosity)
    for n in reversed(levels):
        stiffness, load, alpha = _assemble(*args, n, n_z)
        if free is not None:
            free = np.repeat(free.reshape(-1, n_z), 2, axis=0).ravel()
        pressure, free = active_set_solve(stiffness, load, free)
    pressure = pressure.reshape(n_alpha, n_z)
    per_angle = pressure.sum(axis=1) * (length / n_z)
    d_alpha = 2 * math.pi / n_alpha
    force = -radius * d_alpha * np.array([per_angle @ np.cos(alpha), per_angle @ np.sin(alpha)])
    return force, float(pressure.max())


def _assemble(
    e, v, omega_journal, omega_bushing, radius, length, clearance, viscosity, n_alpha, n_z
):
    """Stiffness K (SPD M-matrix), load f and cell angles of the finite-volume problem."""
    d_alpha = 2 * math.pi / n_alpha
    dz = length / n_z
    alpha = (np.arange(n_alpha) + 0.5) * d_alpha
    face = np.arange(n_alpha) * d_alpha  # west face of each cell
    gap = clearance - e[0] * np.cos(alpha) - e[1] * np.sin(alpha)
    gap_face = clearance - e[0] * np.cos(face) - e[1] * np.sin(face)
    dh_da = e[0] * np.sin(alpha) - e[1] * np.cos(alpha)
    dh_dt = -(v[0] * np.cos(alpha) + v[1] * np.sin(alpha))
    source = 6 * viscosity * (omega_journal + omega_bushing) * dh_da + 12 * viscosity * dh_dt
    # operator -div(h^3 grad p) times the cell area d_alpha dz, scaled by 1/c^3
    h3_face = (gap_face / clearance) ** 3
    h3 = (gap / clearance) ** 3
    c_alpha = h3_face / (radius**2 * d_alpha**2) * d_alpha * dz  # west face of cell i
    c_z = h3 / dz**2 * d_alpha * dz
    n = n_alpha * n_z
    index = np.arange(n).reshape(n_alpha, n_z)
    west = np.roll(index, 1, axis=0)
    rows, cols, vals = [], [], []
    diag = np.zeros((n_alpha, n_z))
    coupling_a = np.broadcast_to(c_alpha[:, None], (n_alpha, n_z))
    for r, c in ((index, west), (west, index)):
        rows.append(r.ravel())
        cols.append(c.ravel())
        vals.append(-coupling_a.ravel())
    diag += coupling_a + np.roll(coupling_a, -1, axis=0)
    coupling_z = np.broadcast_to(c_z[:, None], (n_alpha, n_z - 1))
    for r, c in ((index[:, :-1], index[:, 1:]), (index[:, 1:], index[:, :-1])):
        rows.append(r.ravel())
        cols.append(c.ravel())
        vals.append(-coupling_z.ravel())
    diag[:, :-1] += coupling_z
    diag[:, 1:] += coupling_z
    diag[:, 0] += 2 * c_z  # p = 0 half a cell away, at the ends
    diag[:, -1] += 2 * c_z
    rows.append(index.ravel())
    cols.append(index.ravel())
    vals.append(diag.ravel())
    stiffness = sp.csr_matrix(
        (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n)
    )
    load = np.repeat(-source / clearance**3 * d_alpha * dz, n_z)
    return stiffness, load, alpha


def active_set_solve(stiffness, load, free=None, iterations=200):
    """min 1/2 p'Kp - f'p subject to p >= 0 (K an M-matrix): primal-dual active set.

    Returns the solution and its free set (p > 0 there, Kp = f)."""
    n = load.size
    free = np.ones(n, dtype=bool) if free is None else free
    load_scale = np.abs(load).max()
    for _ in range(iterations):
        p = np.zeros(n)
        idx = np.flatnonzero(free)
        p[idx] = splu(stiffness[idx][:, idx].tocsc()).solve(load[idx])
        multiplier = stiffness @ p - load
        multiplier[idx] = 0.0
        tol = 1e-10
        if p.min() >= -tol * p.max() and multiplier.min() >= -tol * load_scale:
            return np.maximum(p, 0.0), free
        free = p - multiplier * (p.max() / load_scale) > 0  # min(p, Kp - f) = 0, scaled
    raise RuntimeError("active-set iteration did not settle")
