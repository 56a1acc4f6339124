"""Tabulated cylinder pressure vs crank angle (the paper's pressure source).

CSV contract: a header row with the columns ``crank_angle [deg]`` (origin at TDC,
strictly increasing, within one revolution) and ``cylinder_pressure [Pa]`` (> 0);
other columns are ignored. A last row at exactly first angle + 360 deg closes the
curve and is dropped if its pressure equals the first one. The curve is periodic:
:func:`tabulated_pressure` interpolates linearly, wrapping from the last point to the
first one shifted by one revolution.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from recipsim.errors import CaseError
from recipsim.physics.kinematics import piston_displacement_array

ANGLE_COLUMN = "crank_angle [deg]"
PRESSURE_COLUMN = "cylinder_pressure [Pa]"
TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class PressureCurve:
    """A validated periodic pressure curve.

    Attributes
    ----------
    crank_angle : numpy.ndarray
        Strictly increasing, spanning less than one revolution [rad].
    pressure : numpy.ndarray
        [Pa], > 0.
    """

    crank_angle: np.ndarray
    pressure: np.ndarray

    def __call__(self, theta: np.ndarray | float) -> np.ndarray:
        """Pressure at crank angles ``theta`` [rad] (vectorised, periodic) [Pa]."""
        th = np.atleast_1d(np.asarray(theta, dtype=float))
        return np.array([tabulated_pressure(t, self.crank_angle, self.pressure) for t in th])


@njit(cache=True)
def periodic_linear_interpolation(theta: float, angles: np.ndarray, values: np.ndarray) -> float:
    """Linear interpolation of a 2 pi-periodic table.

    Parameters
    ----------
    theta : float
        Angle [rad], any value.
    angles : numpy.ndarray
        Strictly increasing angles spanning less than 2 pi [rad].
    values : numpy.ndarray
        Values at ``angles``.

    Returns
    -------
    float
        Interpolated value; between the last angle and the first + 2 pi the table wraps.
    """
    n = angles.shape[0]
    a0 = angles[0]
    t = a0 + (theta - a0) % TWO_PI
    last = angles[n - 1]
    if t >= last:
        span = a0 + TWO_PI - last
        w = (t - last) / span
        return values[n - 1] + w * (values[0] - values[n - 1])
    lo = 0
    hi = n - 1  # angles[lo] <= t < angles[hi]
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if angles[mid] <= t:
            lo = mid
        else:
            hi = mid
    w = (t - angles[lo]) / (angles[hi] - angles[lo])
    return values[lo] + w * (values[hi] - values[lo])


@njit(cache=True)
def tabulated_pressure(theta: float, angles: np.ndarray, pressures: np.ndarray) -> float:
    """Cylinder pressure at crank angle ``theta`` [rad] from a periodic table [Pa]."""
    return periodic_linear_interpolation(theta, angles, pressures)


def tabulated_pressure_curve_from_arrays(
    angles_deg: np.ndarray, pressures: np.ndarray, file: str = "<arrays>"
) -> PressureCurve:
    """Validate a pressure table given as arrays.

    Parameters
    ----------
    angles_deg : array_like
        Crank angles from TDC [deg], strictly increasing within one revolution.
    pressures : array_like
        Cylinder pressures [Pa], > 0.
    file : str
        Source name for error messages.

    Returns
    -------
    PressureCurve

    Raises
    ------
    CaseError
        With the offending row (1-based data row) and what is allowed.
    """
    a = np.asarray(angles_deg, dtype=float).ravel()
    p = np.asarray(pressures, dtype=float).ravel()
    if a.shape != p.shape:
        raise CaseError(file, PRESSURE_COLUMN, f"{p.size} pressures for {a.size} angles")
    if a.size < 3:
        raise CaseError(file, ANGLE_COLUMN, f"{a.size} rows; allowed: at least 3")
    for name, arr in ((ANGLE_COLUMN, a), (PRESSURE_COLUMN, p)):
        bad = np.flatnonzero(~np.isfinite(arr))
        if bad.size:
            raise CaseError(file, f"{name}, row {bad[0] + 1}", "not a finite number")
    steps = np.diff(a)
    bad = np.flatnonzero(steps <= 0.0)
    if bad.size:
        i = bad[0] + 1
        raise CaseError(
            file,
            f"{ANGLE_COLUMN}, row {i + 1}",
            f"{a[i]!r} deg after {a[i - 1]!r} deg; allowed: strictly increasing angles",
        )
    span = a[-1] - a[0]
    if span >= 360.0:
        closes = math.isclose(span, 360.0, rel_tol=0.0, abs_tol=1e-9) and math.isclose(
            p[-1], p[0], rel_tol=1e-9
        )
        if not closes:
            raise CaseError(
                file,
                ANGLE_COLUMN,
                f"angles span {span!r} deg; allowed: less than one revolution (360 deg), or "
                "exactly 360 deg with the last pressure equal to the first",
            )
        a, p = a[:-1], p[:-1]
    bad = np.flatnonzero(p <= 0.0)
    if bad.size:
        raise CaseError(
            file, f"{PRESSURE_COLUMN}, row {bad[0] + 1}", f"{p[bad[0]]!r} Pa; allowed: > 0"
        )
    return PressureCurve(np.radians(a), p.copy())


def ideal_cycle_pressure_curve(
    crank_radius: float,
    rod_length: float,
    *,
    clearance_fraction: float = 0.02,
    suction_pressure: float = 1.15e5,
    discharge_pressure: float = 15.0e5,
    polytropic_exponent: float = 1.1,
    n_points: int = 720,
    smoothing: float = 0.0,
) -> PressureCurve:
    """Pressure of an ideal compressor cycle with polytropic compression and re-expansion.

    From TDC: re-expansion ``p = p_d (V_c / V)^n`` down to ``p_s``, suction at ``p_s``
    to BDC, compression ``p = p_s (V_BDC / V)^n`` up to ``p_d``, discharge at ``p_d`` to
    TDC. Lossless valves, no heat transfer, so the indicated work has a closed form
    (:func:`ideal_cycle_indicated_work`). Defaults: R134a-like LBP (1.15 bar, 15 bar),
    clearance 2 % of the swept volume, n = 1.1.

    Parameters
    ----------
    crank_radius, rod_length : float
        [m].
    clearance_fraction : float
        Clearance volume over swept volume [-].
    suction_pressure, discharge_pressure : float
        [Pa].
    polytropic_exponent : float
        [-].
    n_points : int
        Number of equally spaced samples over one revolution.
    smoothing : float
        Standard deviation of a periodic Gaussian smoothing in crank angle [rad]
        (0: the sharp ideal cycle). A few degrees stand in for the finite opening and
        closing of real valves and remove the corners' high harmonics; it keeps the
        mean pressure but changes the indicated work slightly.

    Returns
    -------
    PressureCurve
    """
    theta = np.linspace(0.0, TWO_PI, n_points, endpoint=False)
    # volumes per unit piston area [m]
    x = piston_displacement_array(theta, crank_radius, rod_length)
    vc = clearance_fraction * 2.0 * crank_radius
    v = vc + x
    v_bdc = vc + 2.0 * crank_radius
    n = polytropic_exponent
    ps, pd = suction_pressure, discharge_pressure
    expanding = theta <= math.pi
    p = np.where(
        expanding,
        np.maximum(pd * (vc / v) ** n, ps),
        np.minimum(ps * (v_bdc / v) ** n, pd),
    )
    if smoothing > 0.0:
        d = np.minimum(theta, TWO_PI - theta)
        kernel = np.exp(-0.5 * (d / smoothing) ** 2)
        kernel /= kernel.sum()
        p = np.real(np.fft.ifft(np.fft.fft(p) * np.fft.fft(kernel)))
    return PressureCurve(theta, p)


def ideal_cycle_indicated_work(
    crank_radius: float,
    piston_area: float,
    *,
    clearance_fraction: float = 0.02,
    suction_pressure: float = 1.15e5,
    discharge_pressure: float = 15.0e5,
    polytropic_exponent: float = 1.1,
) -> float:
    """Work done on the gas per cycle, ``-closed integral p dV``, of the ideal cycle [J].

    Closed form for the cycle of :func:`ideal_cycle_pressure_curve` (its exact
    continuous curve, not the sampled one).
    """
    n = polytropic_exponent
    ps, pd = suction_pressure, discharge_pressure
    vc = clearance_fraction * 2.0 * crank_radius * piston_area
    v1 = vc + 2.0 * crank_radius * piston_area  # BDC
    v2 = v1 * (ps / pd) ** (1.0 / n)  # discharge opens
    v3 = vc * (pd / ps) ** (1.0 / n)  # suction opens
    compression = (pd * v2 - ps * v1) / (n - 1.0)
    discharge = pd * (v2 - vc)
    re_expansion = -(pd * vc - ps * v3) / (n - 1.0)
    suction = -ps * (v1 - v3)
    return compression + discharge + re_expansion + suction
