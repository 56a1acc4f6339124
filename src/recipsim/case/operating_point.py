"""``[operating_point]``: the thermodynamic state the compressor runs at, validated
against the refrigerant (its temperature and pressure limits, its critical point, the
two-phase dome) and completed from a rating point or a rating standard.

One step per side of the compressor: :func:`_suction_side` (evaporating temperature or
suction pressure), :func:`_discharge_side` (condensing temperature or discharge
pressure), then the suction gas, the liquid line and the shell.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from recipsim.case.case_schema import OPERATING_POINT_SPEC
from recipsim.case.rating import (
    SATURATED_LIQUID_BAND,
    RatingStandard,
    ambient_temperature,
    liquid_temperature,
    rating_standard,
    suction_gas_temperature,
)
from recipsim.case.refrigerant import RefrigerantSpec
from recipsim.case.sections import OperatingPoint
from recipsim.errors import CaseError
from recipsim.schema import read_table

if TYPE_CHECKING:
    from recipsim.case.refrigerant import AnyFluid

PREFIX = "operating_point"


@dataclass(frozen=True)
class _Keys:
    """The table's values read once, and the checks every step makes on them."""

    values: dict[str, Any]
    ref: RefrigerantSpec
    file: str

    def need(self, key: str) -> float:
        if self.values[key] is None:
            raise CaseError(self.file, f"{PREFIX}.{key}", "missing required key")
        return float(self.values[key])

    def in_range(self, key: str, value: float) -> float:
        t_lo, t_hi = self.ref.min_temperature, self.ref.max_temperature
        if not t_lo <= value <= t_hi:
            raise CaseError(
                self.file,
                f"{PREFIX}.{key}",
                f"{value:.2f} K is outside the range of {self.ref.name}: "
                f"[{t_lo:.2f}, {t_hi:.2f}] K",
            )
        return value

    def exactly_one(self, a: str, b: str) -> str:
        if (self.values[a] is None) == (self.values[b] is None):
            raise CaseError(self.file, f"{PREFIX}.{a}", f"give exactly one of {a} and {b}")
        return a if self.values[a] is not None else b


def operating_point(
    raw: dict[str, Any] | None, ref: RefrigerantSpec, fluid: AnyFluid, file: str
) -> OperatingPoint:
    """Validate ``[operating_point]`` against the refrigerant ``ref``, in SI."""
    raw = dict(raw or {})
    values = read_table(raw, OPERATING_POINT_SPEC, file, PREFIX)
    _fill_rating_point(values, raw, ref, file)
    standard = rating_standard(values, raw, file)
    keys = _Keys(values, ref, file)
    p_suc, t_evap = _suction_side(keys, fluid)
    p_dis, t_cond = _discharge_side(keys, fluid, t_evap)
    if p_dis <= p_suc:
        key = "condensing_temperature" if values["condensing_temperature"] else "discharge_pressure"
        raise CaseError(
            file,
            f"{PREFIX}.{key}",
            f"discharge pressure {p_dis:.4g} Pa must exceed suction pressure {p_suc:.4g} Pa",
        )
    t_suc = _suction_gas(keys, raw, standard, fluid, p_suc)
    t_liq = _liquid_line(keys, raw, standard, fluid, p_dis)
    return OperatingPoint(
        evaporating_temperature=t_evap,
        condensing_temperature=t_cond,
        suction_pressure=p_suc,
        discharge_pressure=p_dis,
        suction_temperature=t_suc,
        liquid_temperature=t_liq,
        shell_pressure=_shell_pressure(keys, p_suc, p_dis),
        shaft_speed=float(values["shaft_speed"]),
        ambient_temperature=ambient_temperature(values, raw, standard, file),
        standard=values["standard"],
    )


def _fill_rating_point(
    values: dict[str, Any], raw: dict[str, Any], ref: RefrigerantSpec, file: str
) -> None:
    """Keys the case leaves unset take the values of the named rating point."""
    if values["rating_point"] is None:
        return
    name = values["rating_point"]
    if name not in ref.rating_points:
        raise CaseError(
            file,
            f"{PREFIX}.rating_point",
            f"{name!r} is not a rating point of {ref.name}; available: {sorted(ref.rating_points)}",
        )
    for key, value in ref.rating_points[name].items():
        if key in values and values[key] is None and key not in raw:
            values[key] = value


def _suction_side(keys: _Keys, fluid: AnyFluid) -> tuple[float, float]:
    """Suction pressure and evaporating temperature, from whichever of the two is given."""
    ref, file = keys.ref, keys.file
    if keys.exactly_one("evaporating_temperature", "suction_pressure") == "evaporating_temperature":
        t_evap = keys.in_range("evaporating_temperature", keys.need("evaporating_temperature"))
        if t_evap >= ref.critical_temperature:
            raise CaseError(
                file,
                f"{PREFIX}.evaporating_temperature",
                f"{t_evap:.2f} K is not below the critical temperature "
                f"{ref.critical_temperature:.2f} K",
            )
        return fluid.saturation_pressure(t_evap, 1.0), t_evap
    p_suc = keys.need("suction_pressure")
    if p_suc >= ref.critical_pressure:
        raise CaseError(
            file,
            f"{PREFIX}.suction_pressure",
            f"{p_suc:.4g} Pa is not below the critical pressure {ref.critical_pressure:.4g} Pa",
        )
    p_lo = fluid.saturation_pressure(ref.min_temperature, 1.0)
    if p_suc < p_lo:
        raise CaseError(
            file,
            f"{PREFIX}.suction_pressure",
            f"{p_suc:.4g} Pa is below the saturation pressure at the lowest temperature "
            f"of {ref.name} ({ref.min_temperature:.2f} K): allowed [{p_lo:.4g}, "
            f"{ref.critical_pressure:.4g}) Pa",
        )
    return p_suc, fluid.saturation_temperature(p_suc, 1.0)


def _discharge_side(keys: _Keys, fluid: AnyFluid, t_evap: float) -> tuple[float, float]:
    """Discharge pressure and condensing temperature (``nan`` above the critical pressure)."""
    ref, file = keys.ref, keys.file
    if keys.exactly_one("condensing_temperature", "discharge_pressure") == "condensing_temperature":
        t_cond = keys.in_range("condensing_temperature", keys.need("condensing_temperature"))
        if t_cond <= t_evap:
            raise CaseError(
                file,
                f"{PREFIX}.condensing_temperature",
                f"{t_cond:.2f} K must be above the evaporating temperature {t_evap:.2f} K",
            )
        if t_cond >= ref.critical_temperature:
            raise CaseError(
                file,
                f"{PREFIX}.condensing_temperature",
                f"{t_cond:.2f} K is not below the critical temperature "
                f"{ref.critical_temperature:.2f} K; give "
                "discharge_pressure for a transcritical point",
            )
        return fluid.saturation_pressure(t_cond, 0.0), t_cond
    p_dis = keys.need("discharge_pressure")
    t_cond = fluid.saturation_temperature(p_dis, 0.0) if p_dis < ref.critical_pressure else math.nan
    if p_dis > ref.max_pressure:
        raise CaseError(
            file,
            f"{PREFIX}.discharge_pressure",
            f"{p_dis:.4g} Pa is above the limit of {ref.name}: {ref.max_pressure:.4g} Pa",
        )
    return p_dis, t_cond


def _suction_gas(
    keys: _Keys, raw: dict[str, Any], standard: RatingStandard | None, fluid: AnyFluid, p_suc: float
) -> float:
    """The gas temperature at the suction line: superheated, never inside the dome."""
    t_dew = fluid.saturation_temperature(p_suc, 1.0)
    t_suc = keys.in_range(
        "suction_temperature",
        suction_gas_temperature(keys.values, raw, standard, t_dew, keys.file),
    )
    if t_suc <= t_dew + 1e-3:
        raise CaseError(
            keys.file,
            f"{PREFIX}.suction_temperature",
            f"{t_suc:.2f} K puts the suction state inside the two-phase dome (dew point at "
            f"{p_suc:.4g} Pa is {t_dew:.2f} K); wet suction is outside the model, allowed: "
            f"above {t_dew:.2f} K",
        )
    return t_suc


def _liquid_line(
    keys: _Keys, raw: dict[str, Any], standard: RatingStandard | None, fluid: AnyFluid, p_dis: float
) -> float:
    """The liquid temperature at the expansion device: at or below the bubble point."""
    subcritical = p_dis < keys.ref.critical_pressure
    t_bubble = fluid.saturation_temperature(p_dis, 0.0) if subcritical else math.nan
    t_liq = keys.in_range(
        "liquid_temperature",
        liquid_temperature(keys.values, raw, standard, t_bubble, keys.file),
    )
    # within SATURATED_LIQUID_BAND of the bubble point: saturated liquid
    if subcritical and t_liq > t_bubble + SATURATED_LIQUID_BAND:
        raise CaseError(
            keys.file,
            f"{PREFIX}.liquid_temperature",
            f"{t_liq:.2f} K is above the bubble point {t_bubble:.2f} K at the discharge "
            "pressure: the liquid would not be liquid",
        )
    return t_liq


def _shell_pressure(keys: _Keys, p_suc: float, p_dis: float) -> float:
    """The shell's pressure, the suction pressure unless given."""
    ref = keys.ref
    given = keys.values["shell_pressure"]
    p_shell: float = given if given is not None else p_suc
    if not 0.0 < p_shell <= ref.max_pressure:
        raise CaseError(
            keys.file,
            f"{PREFIX}.shell_pressure",
            f"{p_shell:.4g} Pa is outside the pressure range of {ref.name}: "
            f"(0, {ref.max_pressure:.4g}] Pa (a hermetic shell sits at suction or discharge "
            f"pressure, here {p_suc:.4g} or {p_dis:.4g} Pa)",
        )
    return p_shell
