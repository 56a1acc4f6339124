"""The rating grid: which evaporating and condensing temperatures, at which standard.

A grid point is the case with ``operating_point.standard`` set and its evaporating and
condensing temperatures given: a map point rated the standard's way
(:mod:`recipsim.case.rating`: the standard then sets the suction gas, the liquid and the
ambient, with the sources stated there). The temperatures are written in the standard's
unit (degC for EN 12900, degF for AHRI 540 and ASHRAE LBP).

Default grids, by the case's application (its evaporating temperature: below -15 C low
back pressure, LBP; below 0 C medium, MBP; else high, HBP and air conditioning), in round
numbers of the standard's unit. They are recipsim's choice, not the standards' text:

- LBP, degC: evaporating -35 to -10 C every 5 K (the range household makers print, e.g.
  the TLES5.7KK.3 brochure), condensing 35 to 65 C every 10 K;
- MBP, degC: -20 to 5 C every 5 K, condensing 35 to 65 C every 10 K;
- HBP, degC: -5 to 15 C every 5 K, condensing 35 to 65 C every 10 K;
- LBP, degF: -30 to 20 F every 10 F, condensing 100 to 145 F every 15 F (130 F, the
  ASHRAE and AHRI condensing temperature, among them);
- MBP, degF: -10 to 40 F every 10 F, condensing 100 to 145 F every 15 F;
- HBP, degF: 20 to 55 F every 5 F, condensing 100 to 145 F every 15 F.

The condensing axes lie inside every shipped refrigerant's envelope (35 to 65 C at least),
four values each: the fewest that determine a cubic in D.

Each default is cut to the refrigerant's envelope (``[envelope]`` of its file) where one
is documented; a grid given by the user is run as given, and its points outside the
envelope are reported as such (``outside_envelope``) and left out of the fit.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from recipsim.case.case import Case
from recipsim.case.rating import STANDARDS
from recipsim.errors import CaseError
from recipsim.studies.rate.polynomial import TEMPERATURE_UNITS, from_kelvin, to_kelvin

#: Applications and the evaporating temperature below which a case belongs to each [K].
APPLICATIONS = {"LBP": 273.15 - 15.0, "MBP": 273.15, "HBP": math.inf}

#: (start, stop, step) of the evaporating and condensing axes, by unit and application.
DEFAULT_GRIDS: dict[tuple[str, str], tuple[tuple[float, float, float], ...]] = {
    ("degC", "LBP"): ((-35, -10, 5), (35, 65, 10)),
    ("degC", "MBP"): ((-20, 5, 5), (35, 65, 10)),
    ("degC", "HBP"): ((-5, 15, 5), (35, 65, 10)),
    ("degF", "LBP"): ((-30, 20, 10), (100, 145, 15)),
    ("degF", "MBP"): ((-10, 40, 10), (100, 145, 15)),
    ("degF", "HBP"): ((20, 55, 5), (100, 145, 15)),
}
#: Most values on one axis.
MAX_AXIS = 60


@dataclass(frozen=True)
class RatingGrid:
    """The temperatures a rating runs at.

    Attributes
    ----------
    standard : str
        Rating standard (a key of :data:`recipsim.case.rating.STANDARDS`).
    temperature_unit : str
        ``degC`` or ``degF``: the unit of the axes as written and of the polynomial.
    evaporating, condensing : tuple of float
        The axes, in ``temperature_unit``.
    application : str
        LBP, MBP or HBP (what chose the default axes).
    """

    standard: str
    temperature_unit: str
    evaporating: tuple[float, ...]
    condensing: tuple[float, ...]
    application: str

    def points(self) -> list[tuple[float, float]]:
        """(evaporating, condensing) of every point, evaporating slowest; condensing at or
        below evaporating is left out."""
        return [(e, c) for e in self.evaporating for c in self.condensing if c > e]

    def overrides(self) -> list[tuple[tuple[str, object], ...]]:
        """Each point's case values: the standard and its two temperatures."""
        unit = self.temperature_unit
        return [
            (
                ("operating_point.standard", self.standard),
                ("operating_point.evaporating_temperature", f"{_text(e)} {unit}"),
                ("operating_point.condensing_temperature", f"{_text(c)} {unit}"),
            )
            for e, c in self.points()
        ]


def _text(value: float) -> str:
    return f"{value:.6g}"


def parse_axis(text: str, where: str) -> tuple[float, ...]:
    """``"START:STOP:STEP"`` (both ends included) or ``"A,B,C"``, in the standard's unit.

    Raises
    ------
    CaseError
        Naming the option and what is expected.
    """
    try:
        if ":" in text:
            parts = [float(p) for p in text.split(":")]
            if len(parts) != 3 or parts[2] <= 0 or parts[1] < parts[0]:
                raise ValueError
            count = math.floor((parts[1] - parts[0]) / parts[2] + 1e-9) + 1
            values = [parts[0] + i * parts[2] for i in range(count)]
        else:
            values = [float(p) for p in text.split(",") if p.strip()]
    except ValueError:
        raise CaseError(
            where, text, "expected START:STOP:STEP (STOP >= START, STEP > 0) or A,B,C"
        ) from None
    if not values or not all(math.isfinite(v) for v in values) or len(values) > MAX_AXIS:
        raise CaseError(where, text, f"expected 1 to {MAX_AXIS} finite temperatures")
    return tuple(sorted({round(v, 9) for v in values}))


def application_of(case: Case) -> str:
    """LBP, MBP or HBP from the case's evaporating temperature."""
    t_evap = case.operating_point.evaporating_temperature
    return next(name for name, below in APPLICATIONS.items() if t_evap < below)


#: The standard a shipped refrigerant file's rating point stands for.
RATING_POINT_STANDARDS = {
    "ashrae_lbp": "ASHRAE_LBP",
    "en12900_lbp": "EN12900",
    "ahri_ac": "AHRI_540",
}


def standard_of(case: Case, standard: str | None) -> str:
    """The rating's standard: the one asked for, else the case's own
    (``operating_point.standard``), else that of its rating point, else EN 12900."""
    if standard is None:
        own = case.operating_point.standard
        point = (case.raw.get("operating_point") or {}).get("rating_point")
        return own if own in STANDARDS else RATING_POINT_STANDARDS.get(str(point), "EN12900")
    if standard not in TEMPERATURE_UNITS:
        raise CaseError("--standard", standard, f"one of {', '.join(TEMPERATURE_UNITS)}")
    return standard


def rating_grid(
    case: Case,
    standard: str | None = None,
    evaporating: Sequence[float] | str | None = None,
    condensing: Sequence[float] | str | None = None,
    application: str | None = None,
) -> RatingGrid:
    """The grid of a rating of ``case`` (defaults: the module docstring).

    Parameters
    ----------
    case : Case
        The compressor.
    standard : str, optional
        EN12900, AHRI_540 or ASHRAE_LBP; default: the case's own, else EN12900.
    evaporating, condensing : sequence of float or str, optional
        The axes in the standard's unit (a string as :func:`parse_axis` reads it).
    application : str, optional
        LBP, MBP or HBP for the default axes; default: :func:`application_of`.
    """
    name = standard_of(case, standard)
    unit = TEMPERATURE_UNITS[name]
    if application is not None and application not in APPLICATIONS:
        raise CaseError("--application", application, f"one of {', '.join(APPLICATIONS)}")
    app = application or application_of(case)
    (e_start, e_stop, e_step), (c_start, c_stop, c_step) = DEFAULT_GRIDS[(unit, app)]
    axes = []
    for given, (start, stop, step), kind in (
        (evaporating, (e_start, e_stop, e_step), "evaporating"),
        (condensing, (c_start, c_stop, c_step), "condensing"),
    ):
        if given is None:
            values = tuple(float(v) for v in np.arange(start, stop + step / 2, step))
            axes.append(_inside_envelope(case, values, kind, unit))
        elif isinstance(given, str):
            axes.append(parse_axis(given, f"--{kind}"))
        else:
            axes.append(parse_axis(",".join(str(float(v)) for v in given), kind))
    return RatingGrid(name, unit, axes[0], axes[1], app)


def _inside_envelope(
    case: Case, values: tuple[float, ...], kind: str, unit: str
) -> tuple[float, ...]:
    """The default axis values within the refrigerant's documented envelope."""
    bounds = case.refrigerant.envelope or {}
    lo = bounds.get(f"{kind}_temperature_min", -math.inf)
    hi = bounds.get(f"{kind}_temperature_max", math.inf)
    kelvin = to_kelvin(np.array(values), unit)
    kept = tuple(v for v, k in zip(values, kelvin, strict=True) if lo - 1e-6 <= k <= hi + 1e-6)
    return kept or values


def in_unit(temperature_k: float, unit: str) -> float:
    """A temperature [K] in ``unit``, as a float."""
    return float(from_kelvin(temperature_k, unit))
