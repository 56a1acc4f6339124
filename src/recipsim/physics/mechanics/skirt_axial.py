"""One circumferential station of the piston-skirt film: the axial pressure problem
(:mod:`recipsim.physics.mechanics.skirt` states the film model and its signs)::

    d/ds(h^3 dp/ds) - (k^2/R^2) h^3 p = cos(theta) (q0 + q1 s)

with ``p = 0`` at both ends, ``h`` linear in ``s`` and the pressure clipped at 0.

Each axial problem is solved by shooting with RK4 in ``sigma = int ds / h`` (uniform
steps in sigma crowd the nodes where the film is thin); the pressure integrals use the
end values and slopes of each step (cubic Hermite; on a step where the film cavitates,
its root and Gauss-Legendre on the positive part).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

#: RK4 steps along each axial line (in sigma).
N_AXIAL_STEPS = 24
_GL_X, _GL_W = np.polynomial.legendre.leggauss(6)
#: Gauss-Legendre nodes and weights on [-1, 1] (constants, 6 per quarter circle).
GAUSS_NODES = tuple(float(x) for x in _GL_X)
GAUSS_WEIGHTS = tuple(float(w) for w in _GL_W)


@njit(cache=True)
def _expm1_over_x(x: float) -> float:
    """``(exp(x) - 1) / x`` without cancellation (1 at 0)."""
    if abs(x) < 1.0e-8:
        return 1.0 + 0.5 * x
    return math.expm1(x) / x


@njit(cache=True)
def _log1p_over_x(x: float) -> float:
    """``log(1 + x) / x`` without cancellation (1 at 0)."""
    if abs(x) < 1.0e-8:
        return 1.0 - 0.5 * x
    return math.log1p(x) / x


@njit(cache=True)
def _coefficients(
    h: float, s: float, q0: float, q1: float, c: float, r2: float
) -> tuple[float, float, float]:
    """``1/h^2``, ``k^2 h^4 / R^2`` and ``h (q0 + q1 s)``: d/dsigma (p, F) = (F/h^2, a p + b)."""
    k2 = 2.0 * c * c / (h * (c + h))
    if k2 < 1.0:
        k2 = 1.0
    h2 = h * h
    return 1.0 / h2, k2 * h2 * h2 / r2, h * (q0 + q1 * s)


@njit(cache=True)
def _rk4_step(
    p: float,
    f: float,
    ia: float,
    ca: float,
    ba: float,
    im: float,
    cm: float,
    bm: float,
    ie: float,
    ce: float,
    be: float,
    dsig: float,
) -> tuple[float, float]:
    """One RK4 step of d/dsigma (p, F) = (i F, c p + b) with the coefficients at the
    start (``a``), middle (``m``) and end (``e``) of the step."""
    half = 0.5 * dsig
    k1p = f * ia
    k1f = ca * p + ba
    k2p = (f + half * k1f) * im
    k2f = cm * (p + half * k1p) + bm
    k3p = (f + half * k2f) * im
    k3f = cm * (p + half * k2p) + bm
    k4p = (f + dsig * k3f) * ie
    k4f = ce * (p + dsig * k3p) + be
    pe = p + dsig / 6.0 * (k1p + 2.0 * k2p + 2.0 * k3p + k4p)
    fe = f + dsig / 6.0 * (k1f + 2.0 * k2f + 2.0 * k3f + k4f)
    return pe, fe


@njit(cache=True)
def _hermite_step(
    pa: float,
    fa: float,
    pe: float,
    fe: float,
    ha: float,
    he: float,
    sa: float,
    se: float,
    g: float,
    dsig: float,
) -> tuple[float, float]:
    """``int p ds`` and ``int p s ds`` over one sigma step (corrected trapezoid rule).

    Uses p and ``dp/dsigma = F/h^2`` at both ends (fourth order); ``ds = h dsigma``,
    ``dh/dsigma = g h``.
    """
    ga = pa * ha
    gb = pe * he
    dga = fa / ha + g * ga
    dgb = fe / he + g * gb
    w0 = 0.5 * dsig * (ga + gb) + dsig * dsig / 12.0 * (dga - dgb)
    dsa = dga * sa + ga * ha
    dsb = dgb * se + gb * he
    w1 = 0.5 * dsig * (ga * sa + gb * se) + dsig * dsig / 12.0 * (dsa - dsb)
    return w0, w1


@njit(cache=True)
def _hermite_pressure(t: float, pa: float, da: float, pe: float, de: float) -> float:
    """Cubic Hermite interpolant on [0, 1] from the end values and end slopes (per unit t)."""
    t2 = t * t
    t3 = t2 * t
    return (
        (2.0 * t3 - 3.0 * t2 + 1.0) * pa
        + (t3 - 2.0 * t2 + t) * da
        + (-2.0 * t3 + 3.0 * t2) * pe
        + (t3 - t2) * de
    )


@njit(cache=True)
def _cavitating_step(
    pa: float,
    ma: float,
    pe: float,
    me: float,
    ha: float,
    sa: float,
    g: float,
    dsig: float,
) -> tuple[float, float]:
    """``int max(p, 0) ds`` and ``int max(p, 0) s ds`` over a step where p changes sign.

    p is the cubic Hermite interpolant of the end values and slopes ``m = dp/dsigma``;
    its root is found by bisection and the positive part integrated by Gauss-Legendre.
    """
    da = ma * dsig
    de = me * dsig
    lo = 0.0
    hi = 1.0
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        if (_hermite_pressure(mid, pa, da, pe, de) > 0.0) == (pa > 0.0):
            lo = mid
        else:
            hi = mid
    root = 0.5 * (lo + hi)
    t0, t1 = (0.0, root) if pa > 0.0 else (root, 1.0)
    w0 = 0.0
    w1 = 0.0
    for j in range(len(GAUSS_NODES)):
        t = t0 + 0.5 * (t1 - t0) * (1.0 + GAUSS_NODES[j])
        x = g * dsig * t
        h = ha * math.exp(x)
        s = sa + ha * dsig * t * _expm1_over_x(x)
        value = max(_hermite_pressure(t, pa, da, pe, de), 0.0) * h
        weight = 0.5 * (t1 - t0) * GAUSS_WEIGHTS[j] * dsig
        w0 += weight * value
        w1 += weight * value * s
    return w0, w1


@njit(cache=True)
def _march(
    f_start: float,
    h0: float,
    g: float,
    q0: float,
    q1: float,
    c: float,
    r2: float,
    length: float,
) -> tuple[float, float, float, float]:
    """Integrate one axial line from the crown end (p = 0, F = f_start) to the skirt end,
    with ``int max(p, 0) ds``, ``int max(p, 0) s ds`` and the largest nodal pressure.

    Returns
    -------
    p_end, w0, w1, p_max : float
        Pressure at the skirt end [Pa], the two integrals [Pa m], [Pa m2], [Pa].
    """
    sig_total = length / h0 * _log1p_over_x(g * length / h0)
    dsig = sig_total / N_AXIAL_STEPS
    grow = math.exp(0.5 * g * dsig)  # h(sigma + dsig/2) / h(sigma)
    ds_half = 0.5 * dsig * _expm1_over_x(0.5 * g * dsig)  # s step over dsig/2, per h
    p = 0.0
    f = f_start
    h = h0
    s = 0.0
    w0 = 0.0
    w1 = 0.0
    p_max = 0.0
    for _ in range(N_AXIAL_STEPS):
        hm = h * grow
        sm = s + h * ds_half
        he = hm * grow
        se = sm + hm * ds_half
        ia, ca, ba = _coefficients(h, s, q0, q1, c, r2)
        im, cm, bm = _coefficients(hm, sm, q0, q1, c, r2)
        ie, ce, be = _coefficients(he, se, q0, q1, c, r2)
        pe, fe = _rk4_step(p, f, ia, ca, ba, im, cm, bm, ie, ce, be, dsig)
        if p >= 0.0 and pe >= 0.0:
            dw0, dw1 = _hermite_step(p, f, pe, fe, h, he, s, se, g, dsig)
            w0 += dw0
            w1 += dw1
        elif p > 0.0 or pe > 0.0:
            dw0, dw1 = _cavitating_step(p, f / (h * h), pe, fe / (he * he), h, s, g, dsig)
            w0 += dw0
            w1 += dw1
        p = pe
        f = fe
        h = he
        s = se
        if p > p_max:
            p_max = p
    return p, w0, w1, p_max


@njit(cache=True)
def _shoot(
    h0: float, g: float, q0: float, q1: float, c: float, r2: float, length: float
) -> tuple[float, float, float, float, float]:
    """March the forced (F(0) = 0) and free (F(0) = 1) solutions of one axial line together.

    RK4 is linear in the state, so the discrete solution with p = 0 at both ends is
    exactly ``forced + start * free`` on every node.

    Returns
    -------
    start, w0, w1, lowest, highest : float
        ``start``: F(0) of the solution with p = 0 at both ends [Pa m^2]; ``w0``,
        ``w1``: its ``int p ds`` [Pa m], ``int p s ds`` [Pa m2] without clipping;
        ``lowest``, ``highest``: the range of ``-p_forced/p_free`` over the inner nodes
        (that solution is >= 0 on every node when ``start >= highest`` and <= 0 when
        ``start <= lowest``).
    """
    sig_total = length / h0 * _log1p_over_x(g * length / h0)
    dsig = sig_total / N_AXIAL_STEPS
    grow = math.exp(0.5 * g * dsig)
    ds_half = 0.5 * dsig * _expm1_over_x(0.5 * g * dsig)
    pp = 0.0
    fp = 0.0
    ph = 0.0
    fh = 1.0
    h = h0
    s = 0.0
    w0p = 0.0
    w1p = 0.0
    w0h = 0.0
    w1h = 0.0
    lowest = math.inf
    highest = -math.inf
    for k in range(N_AXIAL_STEPS):
        hm = h * grow
        sm = s + h * ds_half
        he = hm * grow
        se = sm + hm * ds_half
        # coefficients of d/dsigma (p, F) = (F/h^2, a p + b) at the three stage points
        ia, ca, ba = _coefficients(h, s, q0, q1, c, r2)
        im, cm, bm = _coefficients(hm, sm, q0, q1, c, r2)
        ie, ce, be = _coefficients(he, se, q0, q1, c, r2)
        ppe, fpe = _rk4_step(pp, fp, ia, ca, ba, im, cm, bm, ie, ce, be, dsig)
        phe, fhe = _rk4_step(ph, fh, ia, ca, 0.0, im, cm, 0.0, ie, ce, 0.0, dsig)
        dw0, dw1 = _hermite_step(pp, fp, ppe, fpe, h, he, s, se, g, dsig)
        w0p += dw0
        w1p += dw1
        dw0, dw1 = _hermite_step(ph, fh, phe, fhe, h, he, s, se, g, dsig)
        w0h += dw0
        w1h += dw1
        pp = ppe
        fp = fpe
        ph = phe
        fh = fhe
        h = he
        s = se
        if k < N_AXIAL_STEPS - 1:
            ratio = -pp / ph
            lowest = min(lowest, ratio)
            highest = max(highest, ratio)
    start = -pp / ph
    return start, w0p + start * w0h, w1p + start * w1h, lowest, highest


@njit(cache=True)
def station_pressure_integrals(
    cos_t: float,
    e_crown: float,
    e_skirt: float,
    q0: float,
    q1: float,
    c: float,
    r2: float,
    length: float,
    peak: bool,
) -> tuple[float, float, float, float]:
    """Clipped pressure integrals at one circumferential station.

    Parameters
    ----------
    cos_t : float
        Cosine of the station's angle from +Y [-].
    e_crown, e_skirt : float
        Lateral offsets of the piston axis at the film's crown and skirt ends [m].
    q0, q1 : float
        Source ``6 mu U dh/ds + 12 mu dh/dt = cos(theta) (q0 + q1 s)`` [Pa m], [Pa].
    c : float
        Radial clearance [m].
    r2 : float
        Piston radius squared [m^2].
    length : float
        Film length [m].
    peak : bool
        Also find the largest pressure (a second march); otherwise ``p_max`` is 0
        unless the line cavitates part-way.

    Returns
    -------
    w0, w1, slope, p_max : float
        ``int p+ ds`` [Pa m], ``int p+ s ds`` [Pa m2], ``dh/ds`` [-], peak [Pa].
    """
    h0 = c - e_crown * cos_t
    g = -(e_skirt - e_crown) * cos_t / length
    a0 = q0 * cos_t
    a1 = q1 * cos_t
    start, w0, w1, lowest, highest = _shoot(h0, g, a0, a1, c, r2, length)
    p_max = 0.0
    if start >= highest and not peak:
        return w0, w1, g, p_max  # p >= 0 on every node: no cavitation on this line
    if start <= lowest and not peak:
        return 0.0, 0.0, g, p_max  # p <= 0 everywhere: all cavitated
    _, w0, w1, p_max = _march(start, h0, g, a0, a1, c, r2, length)
    return w0, w1, g, p_max
