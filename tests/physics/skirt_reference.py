"""Test-only reference: 2-D finite-difference Reynolds solution of the piston-skirt film.

Independent of :mod:`recipsim.physics.mechanics.skirt` (its own grid, its own force and
friction integrals; it keeps the circumferential flow that the compiled model drops).

Domain: ``s`` in [0, L] from the crown end (s = 0) to the skirt end (s = L), ``theta``
in [0, 2 pi) from +Y, periodic. Film ``h = c - e(s) cos(theta)``, ``e`` linear between
``e_crown`` and ``e_skirt``. Reynolds, piston frame (the bore slides past the piston
towards +s at ``U`` when the piston moves towards the head at ``U``)::

    d/ds(h^3 dp/ds) + d/dtheta(h^3 dp/dtheta) / R^2 = 6 mu U dh/ds + 12 mu dh/dt

with ``dh/dt = -v(s) cos(theta)``, p = 0 at s = 0 and s = L, solved for the full film
and then clipped at 0 (Guembel / half-Sommerfeld). Conservative five-point scheme with
``h^3`` at the cell faces; second order.

Outputs, as in the compiled model: lateral forces at the crown and skirt ends that carry
the film's Y resultant and its moment (linear shape functions), and the axial force on
the piston: wall shear ``-(mu U / h - h/2 dp/ds)`` plus the axial component ``p dh/ds``
of the pressure on the inclined skirt.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import spsolve


def reference_film(
    e_crown: float,
    e_skirt: float,
    v_crown: float,
    v_skirt: float,
    sliding_speed: float,
    radius: float,
    length: float,
    clearance: float,
    viscosity: float,
    n_axial: int = 80,
    n_theta: int = 360,
    circumferential: bool = True,
) -> tuple[float, float, float, float]:
    """Film forces from the 2-D Reynolds equation (half-Sommerfeld).

    ``circumferential=False`` drops the theta-flow term: the short-film approximation,
    solved by the same finite differences (a check of the compiled closed form).

    Returns
    -------
    f_crown, f_skirt, friction, peak_pressure : float
        [N], [N], [N], [Pa]; signs as in :func:`recipsim.physics.mechanics.skirt.skirt_film`.
    """
    mu, u_s, r, big_l, c = viscosity, sliding_speed, radius, length, clearance
    ds = big_l / n_axial
    dt = 2.0 * np.pi / n_theta
    s = np.linspace(0.0, big_l, n_axial + 1)
    th = np.arange(n_theta) * dt
    cos_t = np.cos(th)
    slope = (e_skirt - e_crown) / big_l

    def film(si: np.ndarray, ti: np.ndarray) -> np.ndarray:
        return c - (e_crown + slope * si) * np.cos(ti)

    si_in = s[1:-1]
    ss, tt = np.meshgrid(si_in, th, indexing="ij")  # interior axial nodes x theta
    n_i = si_in.size
    idx = np.arange(n_i * n_theta).reshape(n_i, n_theta)
    h_sp = film(ss + 0.5 * ds, tt) ** 3
    h_sm = film(ss - 0.5 * ds, tt) ** 3
    flow = 1.0 if circumferential else 0.0
    h_tp = flow * film(ss, tt + 0.5 * dt) ** 3 / r**2
    h_tm = flow * film(ss, tt - 0.5 * dt) ** 3 / r**2
    diag = -(h_sp + h_sm) / ds**2 - (h_tp + h_tm) / dt**2
    rows = [idx.ravel()]
    cols = [idx.ravel()]
    vals = [diag.ravel()]
    # axial neighbours (the end rows' outer neighbours are the p = 0 boundaries)
    rows += [idx[:-1].ravel(), idx[1:].ravel()]
    cols += [idx[1:].ravel(), idx[:-1].ravel()]
    vals += [(h_sp[:-1] / ds**2).ravel(), (h_sm[1:] / ds**2).ravel()]
    rows += [idx.ravel(), idx.ravel()]
    cols += [np.roll(idx, -1, axis=1).ravel(), np.roll(idx, 1, axis=1).ravel()]
    vals += [(h_tp / dt**2).ravel(), (h_tm / dt**2).ravel()]
    matrix = sp.csr_matrix(
        (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
        shape=(idx.size, idx.size),
    )
    v = v_crown + (v_skirt - v_crown) * ss / big_l
    rhs = 6.0 * mu * u_s * (-slope * np.cos(tt)) + 12.0 * mu * (-v * np.cos(tt))
    p_in = spsolve(matrix.tocsc(), rhs.ravel()).reshape(n_i, n_theta)
    p = np.zeros((n_axial + 1, n_theta))
    p[1:-1] = np.maximum(p_in, 0.0)

    # trapezoid in s (p = 0 at both ends), periodic rectangle rule in theta
    w_s = np.full(n_axial + 1, ds)
    w_s[[0, -1]] = 0.5 * ds
    line_y = -(p * cos_t).sum(axis=1) * dt * r  # Y force per unit length [N/m]
    f_crown = float(np.sum(w_s * line_y * (1.0 - s / big_l)))
    f_skirt = float(np.sum(w_s * line_y * s / big_l))

    # friction: shear on the piston at cell centres in s, plus p dh/ds
    s_mid = 0.5 * (s[1:] + s[:-1])
    sm, tm = np.meshgrid(s_mid, th, indexing="ij")
    h_mid = film(sm, tm)
    dp_ds = np.diff(p, axis=0) / ds
    shear = mu * u_s / h_mid - 0.5 * h_mid * dp_ds
    p_mid = 0.5 * (p[1:] + p[:-1])
    dh_ds = -slope * np.cos(tm)
    axial = -shear + p_mid * dh_ds
    friction = float(axial.sum() * ds * dt * r)
    return f_crown, f_skirt, friction, float(p.max())
