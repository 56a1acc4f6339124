"""Lubricating oil: density and a viscosity-temperature law fitted through data points.

Two laws, each fitted exactly through its data points (non-compiled fits, compiled
evaluation with :func:`oil_viscosity`):

- Vogel, ``mu = a exp(b / (T - c))`` through three (T, mu) points (dynamic viscosity);
- Walther / ASTM D341, ``log10 log10(nu + 0.7) = A - B log10 T`` through two (T, nu)
  points, ``nu`` kinematic in mm2/s (cSt) and ``T`` in K as in the standard. The
  standard's extra terms for ``nu < 2 mm2/s`` are left out: they change ``Z = nu + 0.7``
  by less than 1 % above 1.5 mm2/s, and the oils here stay above 1.5 mm2/s below 110 C.

Data points may be kinematic [m2/s] or dynamic [Pa s]; the oil's density [kg/m3]
converts between them and is taken independent of temperature (a light mineral oil's
density falls about 0.07 %/K, so ``mu`` from ``nu`` is off by about 4 % 60 K away from
the density's temperature; the fitted law is in the viscosity the data were given in,
so this only matters for the conversion).

Named oils:

- :func:`spindle_oil`: a light mineral (spindle) oil with three published dynamic
  viscosities, 18.6 / 6.3 / 2.4 mPa s at 30 / 60 / 100 C (Stachowiak & Batchelor,
  *Engineering Tribology*, Table 2.3, "spindle oil", adapted there from its ref. [12]).
  Its 6.3 mPa s at 60 C is the design's 0.006 Pa s; with the assumed density
  860 kg/m3 it has 14.4 mm2/s at 40 C, an ISO VG 15 oil, not VG 5-10.
- :data:`DEFAULT_OIL` (ISO VG 10): 10.0 mm2/s at 40 C, the ISO 3448 grade midpoint,
  and the spindle oil's Walther slope ``B`` (an assumption: the same
  viscosity-temperature slope as that light mineral oil), which puts it at
  2.30 mm2/s at 100 C and 4.64 mPa s at 60 C with 860 kg/m3.

Walther through the spindle oil's 30 C and 100 C points gives 6.11 mPa s at 60 C
against the published 6.3 (3 %), the size of the law's own uncertainty.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numba import njit

#: Law codes for :func:`oil_viscosity`.
LAW_VOGEL = 0
LAW_WALTHER = 1

#: Kelvin offset of the Celsius scale [K].
_ZERO_CELSIUS = 273.15
#: Walther's offset on the kinematic viscosity [mm2/s].
_WALTHER_OFFSET = 0.7


@dataclass(frozen=True)
class Oil:
    """A lubricant: density and a fitted viscosity-temperature law.

    Attributes
    ----------
    name : str
        Label for reports.
    density : float
        [kg/m3], constant.
    law_code : int
        :data:`LAW_VOGEL` or :data:`LAW_WALTHER`.
    coefficients : tuple[float, float, float]
        Vogel: ``(a [Pa s], b [K], c [K])``; Walther: ``(A [-], B [-], density [kg/m3])``.
    temperatures : tuple[float, ...]
        The data points' temperatures [K].
    viscosities : tuple[float, ...]
        The data points' dynamic viscosities [Pa s].
    source : str
        Where the data points come from.
    """

    name: str
    density: float
    law_code: int
    coefficients: tuple[float, float, float]
    temperatures: tuple[float, ...]
    viscosities: tuple[float, ...]
    source: str

    def viscosity(self, temperature: float) -> float:
        """Dynamic viscosity [Pa s] at ``temperature`` [K]."""
        c1, c2, c3 = self.coefficients
        return float(oil_viscosity(temperature, self.law_code, c1, c2, c3))


@njit(cache=True)
def oil_viscosity(temperature: float, law_code: int, c1: float, c2: float, c3: float) -> float:
    """Dynamic viscosity of an oil from its fitted law.

    Parameters
    ----------
    temperature : float
        Oil temperature [K].
    law_code : int
        :data:`LAW_VOGEL` (0) or :data:`LAW_WALTHER` (1).
    c1, c2, c3 : float
        Vogel: ``a`` [Pa s], ``b`` [K], ``c`` [K]; Walther: ``A`` [-], ``B`` [-] and the
        density [kg/m3].

    Returns
    -------
    float
        Dynamic viscosity [Pa s].
    """
    if law_code == LAW_VOGEL:
        return c1 * math.exp(c2 / (temperature - c3))
    z = 10.0 ** (10.0 ** (c1 - c2 * math.log10(temperature)))
    return c3 * (z - _WALTHER_OFFSET) * 1.0e-6


def _dynamic_points(
    temperatures: tuple[float, ...],
    viscosities: tuple[float, ...],
    density: float,
    kinematic: bool,
    count: int,
) -> tuple[np.ndarray, np.ndarray]:
    """Validate data points and return (T [K], mu [Pa s]) arrays."""
    t = np.asarray(temperatures, dtype=float)
    v = np.asarray(viscosities, dtype=float)
    if t.shape != (count,) or v.shape != (count,):
        raise ValueError(f"need exactly {count} temperatures and {count} viscosities")
    if not (np.all(np.isfinite(t)) and np.all(t > 0.0)):
        raise ValueError(f"temperatures must be finite and positive in K, got {temperatures}")
    if np.any(np.diff(t) <= 0.0):
        raise ValueError(f"temperatures must be strictly increasing, got {temperatures}")
    if not (np.all(np.isfinite(v)) and np.all(v > 0.0)):
        raise ValueError(f"viscosities must be finite and positive, got {viscosities}")
    if np.any(np.diff(v) >= 0.0):
        raise ValueError(f"viscosities must fall as the temperature rises, got {viscosities}")
    if not (math.isfinite(density) and density > 0.0):
        raise ValueError(f"density must be finite and positive [kg/m3], got {density}")
    return t, (v * density if kinematic else v)


def fit_vogel(
    name: str,
    temperatures: tuple[float, float, float],
    viscosities: tuple[float, float, float],
    density: float,
    kinematic: bool = False,
    source: str = "",
) -> Oil:
    """Vogel law ``mu = a exp(b / (T - c))`` through three points.

    Parameters
    ----------
    name : str
        Label.
    temperatures : tuple of 3 float
        Strictly increasing [K].
    viscosities : tuple of 3 float
        Dynamic [Pa s], or kinematic [m2/s] when ``kinematic``; strictly falling.
    density : float
        [kg/m3].
    kinematic : bool
        Whether ``viscosities`` are kinematic.
    source : str
        Where the points come from.

    Returns
    -------
    Oil

    Raises
    ------
    ValueError
        Bad points, or points that no Vogel curve passes through (``ln mu`` must be
        convex in T, i.e. the viscosity must fall more slowly as T rises).
    """
    t, mu = _dynamic_points(temperatures, viscosities, density, kinematic, 3)
    y = np.log(mu)
    # ln mu = ln a + b / (T - c): the slope ratio fixes c alone
    target = (y[0] - y[1]) / (y[1] - y[2])

    def mismatch(c: float) -> float:
        g = 1.0 / (t - c)
        return float((g[0] - g[1]) / (g[1] - g[2]) - target)

    # the ratio tends to (t2-t1)/(t3-t2) as c -> -inf and to +inf as c -> t1
    far = t[0] - 1.0e6
    near = t[0] - 1.0e-9 * t[0]
    if not mismatch(far) < 0.0 < mismatch(near):
        raise ValueError(
            f"no Vogel curve passes through {temperatures}, {viscosities}: ln(mu) must be "
            "convex in T (the viscosity must fall more slowly as the temperature rises)"
        )
    from scipy.optimize import brentq  # a heavy import, needed only to fit an oil

    c = brentq(mismatch, far, near, xtol=1e-12 * t[0], rtol=1e-15, maxiter=500)
    b = (y[0] - y[1]) / (1.0 / (t[0] - c) - 1.0 / (t[1] - c))
    a = math.exp(y[0] - b / (t[0] - c))
    return Oil(
        name,
        density,
        LAW_VOGEL,
        (a, float(b), float(c)),
        tuple(map(float, t)),
        tuple(map(float, mu)),
        source,
    )


def fit_walther(
    name: str,
    temperatures: tuple[float, float],
    viscosities: tuple[float, float],
    density: float,
    kinematic: bool = True,
    source: str = "",
) -> Oil:
    """Walther / ASTM D341 law ``log10 log10(nu + 0.7) = A - B log10 T`` through two points.

    Parameters
    ----------
    name : str
        Label.
    temperatures : tuple of 2 float
        Strictly increasing [K].
    viscosities : tuple of 2 float
        Kinematic [m2/s] when ``kinematic`` (default), else dynamic [Pa s]; falling.
    density : float
        [kg/m3].
    kinematic : bool
        Whether ``viscosities`` are kinematic.
    source : str
        Where the points come from.

    Returns
    -------
    Oil
    """
    t, mu = _dynamic_points(temperatures, viscosities, density, kinematic, 2)
    nu_cst = mu / density * 1.0e6
    w = np.log10(np.log10(nu_cst + _WALTHER_OFFSET))
    x = np.log10(t)
    slope = (w[0] - w[1]) / (x[1] - x[0])
    intercept = w[0] + slope * x[0]
    return Oil(
        name,
        density,
        LAW_WALTHER,
        (float(intercept), float(slope), density),
        tuple(map(float, t)),
        tuple(map(float, mu)),
        source,
    )


def celsius(t: float) -> float:
    """Kelvin from Celsius [K]."""
    return t + _ZERO_CELSIUS


#: Assumed density of the light mineral oils below [kg/m3] (typical 850-880 at 15-40 C).
MINERAL_OIL_DENSITY = 860.0


@lru_cache(maxsize=1)
def spindle_oil() -> Oil:
    """The light mineral spindle oil, a Vogel curve through three points (Stachowiak &
    Batchelor, Table 2.3), fitted when first asked for."""
    return fit_vogel(
        "spindle oil (light mineral)",
        (celsius(30.0), celsius(60.0), celsius(100.0)),
        (18.6e-3, 6.3e-3, 2.4e-3),
        MINERAL_OIL_DENSITY,
        source="Stachowiak & Batchelor, Engineering Tribology, Table 2.3 (spindle oil); "
        "density assumed",
    )


#: The spindle oil's Walther slope through its 30 C and 100 C points.
_SPINDLE_WALTHER = fit_walther(
    "spindle oil (Walther)",
    (celsius(30.0), celsius(100.0)),
    (18.6e-3, 2.4e-3),
    MINERAL_OIL_DENSITY,
    kinematic=False,
)


def _iso_vg10_at_100c() -> float:
    """Kinematic viscosity at 100 C [m2/s] of 10 mm2/s at 40 C with the spindle slope."""
    slope = _SPINDLE_WALTHER.coefficients[1]
    w40 = math.log10(math.log10(10.0 + _WALTHER_OFFSET))
    w100 = w40 - slope * (math.log10(celsius(100.0)) - math.log10(celsius(40.0)))
    return (10.0 ** (10.0**w100) - _WALTHER_OFFSET) * 1.0e-6


DEFAULT_OIL = fit_walther(
    "ISO VG 10 mineral refrigeration oil",
    (celsius(40.0), celsius(100.0)),
    (10.0e-6, _iso_vg10_at_100c()),
    MINERAL_OIL_DENSITY,
    source="ISO 3448 VG 10 midpoint at 40 C; Walther slope of the spindle oil "
    "(Stachowiak & Batchelor, Table 2.3), an assumption; density assumed",
)


#: Assumed mean molar mass of a light mineral refrigeration oil [kg/mol] (ISO VG 10-15
#: naphthenic or paraffinic base oils: about 0.25-0.35 kg/mol).
MINERAL_OIL_MOLAR_MASS = 0.30


def diluted_viscosity(
    oil_viscosity: float,
    refrigerant_viscosity: float,
    refrigerant_mass_fraction: float,
    oil_molar_mass: float,
    refrigerant_molar_mass: float,
) -> float:
    """Dynamic viscosity of oil with refrigerant dissolved in it [Pa s].

    The logarithmic mixing rule in mole fractions, ``ln mu = x_r ln mu_r + (1 - x_r)
    ln mu_o`` (Arrhenius's rule; Grunberg & Nissan, "Mixture law for viscosity", Nature
    164, 799, 1949, with their interaction term left out): a light refrigerant of
    small molar mass takes a large mole fraction at a small mass fraction, so a few per
    cent of R600a in a mineral oil lower its viscosity by a third or more, the order
    measured for R600a in light lubricants (Marcelino Neto & Barbosa, Fluid Phase
    Equilibria 292, 7-12, 2010). The interaction term, which these mixtures need for
    their measured values within a few per cent, needs the pair's data.

    Parameters
    ----------
    oil_viscosity, refrigerant_viscosity : float
        Pure oil's and the liquid refrigerant's at the same temperature [Pa s].
    refrigerant_mass_fraction : float
        Mass of dissolved refrigerant over the mixture's mass [-], in [0, 1).
    oil_molar_mass, refrigerant_molar_mass : float
        [kg/mol].

    Raises
    ------
    ValueError
        A mass fraction outside [0, 1).
    """
    w = refrigerant_mass_fraction
    if not 0.0 <= w < 1.0:
        raise ValueError(f"dissolved refrigerant mass fraction {w!r}: allowed 0 <= w < 1")
    if w == 0.0:
        return oil_viscosity
    moles_r = w / refrigerant_molar_mass
    x_r = moles_r / (moles_r + (1.0 - w) / oil_molar_mass)
    return math.exp(x_r * math.log(refrigerant_viscosity) + (1.0 - x_r) * math.log(oil_viscosity))


def refrigerant_liquid_viscosity(coolprop_name: str, temperature: float) -> tuple[float, float]:
    """The refrigerant's saturated-liquid viscosity at ``temperature`` [Pa s] and its
    molar mass [kg/mol] (CoolProp), for :func:`diluted_viscosity`. The dissolved
    refrigerant is taken as its own liquid at the oil's temperature, at most 0.98 of its
    critical temperature (a supercritical solute has no liquid of its own: there the
    value is the liquid's at 0.98 T_c).
    """
    import CoolProp.CoolProp as CP

    t = min(temperature, 0.98 * CP.PropsSI("Tcrit", coolprop_name))
    return float(CP.PropsSI("V", "T", t, "Q", 0.0, coolprop_name)), float(
        CP.PropsSI("M", coolprop_name)
    )
