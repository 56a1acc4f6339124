"""Rating standards and the suction-gas, liquid and ambient keys of the operating point.

``operating_point.standard`` names the rating conditions a compressor is rated at. A
standard sets the evaporating and condensing temperatures (unless the case gives the
suction or discharge side itself: a map point rated the standard's way), the suction-gas
and liquid temperatures as it defines them (absolute, or by superheat and subcooling) and
the ambient temperature. The cooling capacity is then ``m_dot [h(p_evap, T_suction gas)
- h(liquid)]`` with those temperatures, whatever the gas does inside the shell.
Explicit keys that contradict the standard are refused.

Standards (temperatures as manufacturers print them, rounded to 0.1 C):

- ``ASHRAE_LBP`` (ASHRAE 23 / AHRI 540 low back pressure, household refrigeration):
  evaporating -23.3 C (-10 F), condensing 54.4 C (130 F), suction gas and liquid 32.2 C
  (90 F), ambient 32.2 C. Source: the Danfoss/Secop brochure header "-23.3 C / 54.4 C"
  and thermo-notes section 3; the refrigerant files' ``ashrae_lbp`` point.
- ``EN12900`` (EN 12900 / CECOMAF, the low-back-pressure household point): evaporating
  -25 C, condensing 55 C, suction gas 32 C, no subcooling (liquid at the bubble point),
  ambient 32 C. Source: ``src/recipsim/data/catalogue/README.md`` and thermo-notes section 3
  (the standard's text was not read).
- ``AHRI_540``: the air-conditioning point only, evaporating 7.2 C (45 F), condensing
  54.4 C (130 F), superheat 11.1 K (20 F), subcooling 8.3 K (15 F), ambient 35 C (95 F),
  as the R32 and R410A files' ``ahri_ac`` point; AHRI 540's medium- and low-temperature
  points are not offered (their values could not be checked against the standard).

Without a standard (``"none"``) the suction gas is ``suction_temperature`` or
``superheat``, the liquid ``liquid_temperature`` or ``subcooling`` (exactly one of each,
or the rating point's), and the ambient ``ambient_temperature`` (default 32.2 C).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from recipsim.errors import CaseError
from recipsim.schema import Choice, Field, Spec
from recipsim.units import correctly_rounded

_PREFIX = "operating_point"
#: Default ambient temperature [K] (32.2 C, the ASHRAE LBP ambient).
DEFAULT_AMBIENT_TEMPERATURE = 305.35
#: Explicit keys within this of the standard's value agree with it [K].
_AGREEMENT = 1e-6
#: A liquid within this of the bubble point is saturated liquid [K].
SATURATED_LIQUID_BAND = 1e-6


@dataclass(frozen=True)
class RatingStandard:
    """Rating conditions of a standard (temperatures [K], differences [K]).

    Exactly one of ``suction_temperature`` / ``superheat`` and one of
    ``liquid_temperature`` / ``subcooling`` is set.
    """

    name: str
    evaporating_temperature: float
    condensing_temperature: float
    ambient_temperature: float
    suction_temperature: float | None = None
    superheat: float | None = None
    liquid_temperature: float | None = None
    subcooling: float | None = None


def _kelvin(celsius: float) -> float:
    """``celsius`` [C] in K, as a case file's ``"... degC"`` converts (no float noise)."""
    return correctly_rounded(celsius, 273.15, 274.15, celsius + 273.15)


STANDARDS: dict[str, RatingStandard] = {
    "ASHRAE_LBP": RatingStandard(
        "ASHRAE_LBP", _kelvin(-23.3), _kelvin(54.4), _kelvin(32.2),
        suction_temperature=_kelvin(32.2), liquid_temperature=_kelvin(32.2),
    ),
    "EN12900": RatingStandard(
        "EN12900", _kelvin(-25.0), _kelvin(55.0), _kelvin(32.0),
        suction_temperature=_kelvin(32.0), subcooling=0.0,
    ),
    "AHRI_540": RatingStandard(
        "AHRI_540", _kelvin(7.2), _kelvin(54.4), _kelvin(35.0), superheat=11.1, subcooling=8.3,
    ),
}  # fmt: skip

RATING_SPEC: Spec = {
    "standard": Choice(
        ("none", *STANDARDS),
        "none",
        "rating conditions: evaporating/condensing (unless given), suction gas, liquid, ambient",
    ),
    "superheat": Field(
        "K", None, lo=0.0, hi=100.0, doc="suction gas above the dew point; or suction_temperature"
    ),
    "subcooling": Field(
        "K", None, lo=0.0, hi=100.0, doc="liquid below the bubble point; or liquid_temperature"
    ),
    "ambient_temperature": Field(
        "K", DEFAULT_AMBIENT_TEMPERATURE, lo=200.0, hi=400.0, doc="air around the shell"
    ),
}


def rating_standard(
    values: dict[str, Any], raw: Mapping[str, Any], file: str
) -> RatingStandard | None:
    """The case's standard, its evaporating and condensing temperatures put into ``values``
    where the case gives neither the temperature nor the pressure of that side (a rating
    point's values are replaced: the standard defines the point)."""
    name = values["standard"]
    if name == "none":
        return None
    std = STANDARDS[name]
    for temperature, pressure, value in (
        ("evaporating_temperature", "suction_pressure", std.evaporating_temperature),
        ("condensing_temperature", "discharge_pressure", std.condensing_temperature),
    ):
        if temperature not in raw and pressure not in raw:
            values[temperature] = value
            values[pressure] = None
    return std


def _one_of(
    values: Mapping[str, Any], raw: Mapping[str, Any], absolute: str, relative: str, file: str
) -> str:
    """Which of the keys ``absolute`` / ``relative`` gives the temperature (an explicit
    key beats a rating point's value; both explicit, or none at all, is refused)."""
    if absolute in raw and relative in raw:
        raise CaseError(
            file, f"{_PREFIX}.{relative}", f"give exactly one of {absolute} and {relative}"
        )
    if relative in raw:
        return relative
    if values[absolute] is None:
        raise CaseError(
            file,
            f"{_PREFIX}.{absolute}",
            f"missing required key (or give {relative}, or a standard)",
        )
    return absolute


def _agree(
    raw: Mapping[str, Any], key: str, given: float, expected: float, std: RatingStandard, file: str
) -> None:
    if key in raw and not abs(given - expected) <= _AGREEMENT:
        raise CaseError(
            file,
            f"{_PREFIX}.{key}",
            f"gives {given:.6g} K where standard {std.name} sets {expected:.6g} K; remove the "
            f"key or set {_PREFIX}.standard = 'none'",
        )


def suction_gas_temperature(
    values: Mapping[str, Any],
    raw: Mapping[str, Any],
    std: RatingStandard | None,
    dew_temperature: float,
    file: str,
) -> float:
    """Suction-gas temperature [K] at the compressor inlet from ``suction_temperature``,
    ``superheat`` (above ``dew_temperature`` [K]) or the standard."""
    explicit = {
        "suction_temperature": values["suction_temperature"],
        "superheat": None if values["superheat"] is None else dew_temperature + values["superheat"],
    }
    if std is None:
        return float(explicit[_one_of(values, raw, "suction_temperature", "superheat", file)])
    if std.suction_temperature is not None:
        expected = std.suction_temperature
    else:
        assert std.superheat is not None
        expected = dew_temperature + std.superheat
    for key, given in explicit.items():
        if given is not None:
            _agree(raw, key, given, expected, std, file)
    return expected


def liquid_temperature(
    values: Mapping[str, Any],
    raw: Mapping[str, Any],
    std: RatingStandard | None,
    bubble_temperature: float,
    file: str,
) -> float:
    """Liquid temperature [K] from ``liquid_temperature``, ``subcooling`` (below
    ``bubble_temperature`` [K], nan above the critical pressure) or the standard."""
    relative = std.subcooling if std is not None else None
    if values["subcooling"] is not None or relative is not None:
        if math.isnan(bubble_temperature):
            raise CaseError(
                file,
                f"{_PREFIX}.subcooling",
                "needs a discharge pressure below the critical pressure (a bubble point); "
                "give liquid_temperature",
            )
    explicit = {
        "liquid_temperature": values["liquid_temperature"],
        "subcooling": None
        if values["subcooling"] is None
        else bubble_temperature - values["subcooling"],
    }
    if std is None:
        return float(explicit[_one_of(values, raw, "liquid_temperature", "subcooling", file)])
    if std.liquid_temperature is not None:
        expected = std.liquid_temperature
    else:
        assert relative is not None
        expected = bubble_temperature - relative
    for key, given in explicit.items():
        if given is not None:
            _agree(raw, key, given, expected, std, file)
    return expected


def ambient_temperature(
    values: Mapping[str, Any], raw: Mapping[str, Any], std: RatingStandard | None, file: str
) -> float:
    """Ambient temperature [K]: the key, else the standard's, else 32.2 C."""
    given = float(values["ambient_temperature"])
    if std is None:
        return given
    _agree(raw, "ambient_temperature", given, std.ambient_temperature, std, file)
    return std.ambient_temperature
