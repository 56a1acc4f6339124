"""The ten-coefficient compressor polynomial of EN 12900 and AHRI 540: evaluate and fit.

Every quantity X a maker rates (cooling capacity, power input, current, mass flow) is a
third-order polynomial in the suction dew-point temperature S and the discharge dew-point
temperature D, ten coefficients C1 .. C10 in this order::

    X = C1 + C2 S + C3 D + C4 S^2 + C5 S D + C6 D^2 + C7 S^3 + C8 D S^2 + C9 S D^2 + C10 D^3

S and D in degrees Celsius for EN 12900, in degrees Fahrenheit for AHRI 540 (and the
ASHRAE/AHRI LBP rating, which North American makers publish in AHRI 540's form).

Sources: the order of the terms and AHRI 540's Fahrenheit dew-point temperatures as the
ACHP documentation states the "10-coefficient ANSI/AHRI 540 compressor map" (ACHP,
Compressor component, "Mathematical Description", citing ANSI/AHRI 540-2004: mass flow in
lbm/h and power in W; ``M_8 T_d T_s^2`` and ``M_9 T_d^2 T_s``); the same order with
Celsius temperatures as TESPy's ``calc_EN12900`` evaluates the EN 12900 polynomial
(``tespy.components.displacementmachinery.polynomial_compressor``, after Cecchinato et al.
2010). The standards' own texts (EN 12900:2013, AHRI 540-2015) are sold and were not
read; both secondary sources agree on the form and order above.

The fit is linear least squares on the ten monomials, its columns scaled to unit norm
(S^3 in Fahrenheit reaches 10^6, the constant 1): the coefficients are those of the
unscaled monomials, as published. At least ten points, and a grid that determines all ten
coefficients (four distinct S and four distinct D at least), are required
(:class:`RatingError` otherwise).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from recipsim.errors import RecipsimError

#: Names of the coefficients, in the standards' order.
COEFFICIENTS = tuple(f"C{i}" for i in range(1, 11))
#: The monomial each coefficient multiplies (S suction, D discharge dew point).
TERMS = ("1", "S", "D", "S^2", "S*D", "D^2", "S^3", "D*S^2", "S*D^2", "D^3")
#: Fewest good points a fit of ten coefficients accepts.
MIN_POINTS = len(COEFFICIENTS)

#: Temperature unit of S and D for each rating standard.
TEMPERATURE_UNITS = {"EN12900": "degC", "AHRI_540": "degF", "ASHRAE_LBP": "degF"}
_OFFSET_K = 273.15


class RatingError(RecipsimError):
    """A rating that cannot be made: too few good points, a grid that leaves some of the
    ten coefficients undetermined, an unreadable coefficient file."""


def from_kelvin(temperature: np.ndarray | float, unit: str) -> np.ndarray:
    """Temperatures [K] in ``unit`` (``"degC"`` or ``"degF"``)."""
    celsius = np.asarray(temperature, dtype=float) - _OFFSET_K
    if unit == "degC":
        return celsius
    if unit == "degF":
        return celsius * 1.8 + 32.0
    raise ValueError(f"temperature unit {unit!r}: degC or degF")


def to_kelvin(temperature: np.ndarray | float, unit: str) -> np.ndarray:
    """Temperatures in ``unit`` (``"degC"`` or ``"degF"``) in K."""
    value = np.asarray(temperature, dtype=float)
    if unit == "degC":
        return value + _OFFSET_K
    if unit == "degF":
        return (value - 32.0) / 1.8 + _OFFSET_K
    raise ValueError(f"temperature unit {unit!r}: degC or degF")


def monomials(s: np.ndarray | float, d: np.ndarray | float) -> np.ndarray:
    """The ten monomials of :data:`TERMS` at each (S, D): shape ``(n, 10)``."""
    s = np.atleast_1d(np.asarray(s, dtype=float))
    d = np.atleast_1d(np.asarray(d, dtype=float))
    one = np.ones_like(s)
    return np.column_stack(
        [one, s, d, s**2, s * d, d**2, s**3, d * s**2, s * d**2, d**3]
    )  # fmt: skip


def evaluate(
    coefficients: Sequence[float] | np.ndarray, s: np.ndarray | float, d: np.ndarray | float
) -> np.ndarray:
    """X(S, D) of the polynomial with ``coefficients`` C1 .. C10 (S, D in its unit)."""
    c = np.asarray(coefficients, dtype=float)
    if c.shape != (MIN_POINTS,):
        raise ValueError(f"expected ten coefficients, got {c.shape}")
    return monomials(s, d) @ c


@dataclass(frozen=True)
class PolynomialFit:
    """A quantity's polynomial fitted to its good points.

    Attributes
    ----------
    coefficients : numpy.ndarray
        C1 .. C10 (the standard's order and units).
    fitted : numpy.ndarray
        The polynomial at each point fitted.
    residuals : numpy.ndarray
        Polynomial minus point, in the quantity's unit.
    relative : numpy.ndarray
        ``residuals`` over the point's value [-].
    """

    coefficients: np.ndarray
    fitted: np.ndarray
    residuals: np.ndarray
    relative: np.ndarray

    @property
    def max_abs(self) -> float:
        """Largest absolute residual, in the quantity's unit."""
        return float(np.max(np.abs(self.residuals)))

    @property
    def rms_abs(self) -> float:
        """Root mean square of the residuals, in the quantity's unit."""
        return float(np.sqrt(np.mean(self.residuals**2)))

    @property
    def max_rel(self) -> float:
        """Largest relative residual [-]."""
        return float(np.max(np.abs(self.relative)))

    @property
    def rms_rel(self) -> float:
        """Root mean square of the relative residuals [-]."""
        return float(np.sqrt(np.mean(self.relative**2)))


def fit(s: np.ndarray, d: np.ndarray, values: np.ndarray, quantity: str = "X") -> PolynomialFit:
    """Least-squares coefficients of the ten-term polynomial through the points.

    Parameters
    ----------
    s, d : numpy.ndarray
        Suction and discharge dew-point temperatures of the points, in the standard's unit.
    values : numpy.ndarray
        The quantity at each point (finite).
    quantity : str
        Its name, for messages.

    Raises
    ------
    RatingError
        Fewer than ten points, or points that do not determine the ten coefficients.
    """
    s, d, values = (np.asarray(a, dtype=float) for a in (s, d, values))
    if len(values) < MIN_POINTS:
        raise RatingError(
            f"{quantity}: {len(values)} good points; the polynomial's ten coefficients need "
            f"at least {MIN_POINTS} (widen the grid, or see why points failed)"
        )
    matrix = monomials(s, d)
    norms = np.linalg.norm(matrix, axis=0)
    scaled, _, rank, _ = np.linalg.lstsq(matrix / norms, values, rcond=None)
    if rank < MIN_POINTS:
        raise RatingError(
            f"{quantity}: the {len(values)} good points determine only {rank} of the ten "
            f"coefficients ({len(set(s))} distinct suction and {len(set(d))} distinct "
            "discharge temperatures; a cubic in each needs at least four of each)"
        )
    coefficients = scaled / norms
    fitted = evaluate(coefficients, s, d)
    residuals = fitted - values
    with np.errstate(divide="ignore", invalid="ignore"):
        relative = np.where(values != 0.0, residuals / values, math.nan)
    return PolynomialFit(coefficients, fitted, residuals, relative)
