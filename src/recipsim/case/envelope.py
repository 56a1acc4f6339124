"""The operating envelope of a refrigerant on the shipped compressors, checked before
integrating.

A refrigerant file may carry an ``[envelope]`` table (every key optional, units as in
case files)::

    [envelope]
    evaporating_temperature_min = "-35 degC"
    evaporating_temperature_max = "-5 degC"
    condensing_temperature_min = "35 degC"      # subcritical points
    condensing_temperature_max = "60 degC"
    discharge_pressure_min = "75 bar"           # transcritical points (no condensing T)
    discharge_pressure_max = "110 bar"
    pressure_ratio_max = 20
    shaft_speed_min = "1500 rpm"
    shaft_speed_max = "6000 rpm"

Inside it every point of the shipped wide maps (``cases/sweeps/wide_map_*.toml``)
converges, or ends ``no_delivery`` / ``subharmonic`` with consistent values
(:mod:`recipsim.results.outcome`); outside it a point is refused before anything is
integrated with one line naming the quantity, its value and the bound
(:func:`envelope_refusal`). ``solver.envelope = "ignore"`` runs such a point anyway
(the hard cases that probe beyond the envelope do).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from recipsim.case.schema import Field, Spec, read_table
from recipsim.errors import CaseError

if TYPE_CHECKING:
    from recipsim.case.load import Case

ENVELOPE_SPEC: Spec = {
    "evaporating_temperature_min": Field("K", None, lo=100.0, hi=700.0),
    "evaporating_temperature_max": Field("K", None, lo=100.0, hi=700.0),
    "condensing_temperature_min": Field("K", None, lo=100.0, hi=700.0),
    "condensing_temperature_max": Field("K", None, lo=100.0, hi=700.0),
    "discharge_pressure_min": Field("Pa", None, lo=0.0, open_lo=True),
    "discharge_pressure_max": Field("Pa", None, lo=0.0, open_lo=True),
    "pressure_ratio_max": Field("dimensionless", None, lo=1.0, open_lo=True),
    "shaft_speed_min": Field("rad/s", None, lo=0.0, open_lo=True),
    "shaft_speed_max": Field("rad/s", None, lo=0.0, open_lo=True),
}

#: quantity -> (envelope key stem, how the value and bound are written)
_QUANTITIES = {
    "evaporating_temperature": ("evaporating temperature", "degC"),
    "condensing_temperature": ("condensing temperature", "degC"),
    "discharge_pressure": ("discharge pressure", "bar"),
    "pressure_ratio": ("pressure ratio", ""),
    "shaft_speed": ("shaft speed", "rpm"),
}


class OutsideEnvelopeError(CaseError):
    """The operating point lies outside the refrigerant's documented envelope."""


def read_envelope(raw: Mapping[str, Any] | None, file: str) -> dict[str, float]:
    """Validate the ``[envelope]`` table of a refrigerant file.

    Returns
    -------
    dict
        The bounds that are set, in SI (K, Pa, rad/s, -); empty without the table.

    Raises
    ------
    CaseError
        For an unknown key, a bad unit or a minimum above its maximum.
    """
    values = read_table(raw, ENVELOPE_SPEC, file, "envelope")
    bounds = {k: float(v) for k, v in values.items() if v is not None}
    for stem in _QUANTITIES:
        lo, hi = bounds.get(f"{stem}_min"), bounds.get(f"{stem}_max")
        if lo is not None and hi is not None and lo > hi:
            raise CaseError(file, f"envelope.{stem}_min", "must not exceed the maximum")
    return bounds


def _written(value: float, unit: str) -> str:
    if unit == "degC":
        return f"{value - 273.15:.1f} C"
    if unit == "bar":
        return f"{value / 1e5:.1f} bar"
    if unit == "rpm":
        return f"{value * 60.0 / (2.0 * math.pi):.0f} rpm"
    return f"{value:.3g}"


def envelope_refusal(case: Case) -> str | None:
    """Why ``case``'s operating point lies outside its refrigerant's envelope, or None.

    Checks evaporating and condensing temperature (the discharge pressure for a
    transcritical point), pressure ratio and shaft speed [rad/s] against the bounds
    of the refrigerant file's ``[envelope]``; a missing bound is not checked.
    """
    bounds: dict[str, float] = getattr(case.refrigerant, "envelope", {}) or {}
    op = case.operating_point
    values = {
        "evaporating_temperature": op.evaporating_temperature,
        "condensing_temperature": op.condensing_temperature,
        "discharge_pressure": op.discharge_pressure,
        "pressure_ratio": op.pressure_ratio,
        "shaft_speed": op.shaft_speed,
    }
    for stem, value in values.items():
        if not math.isfinite(value):  # transcritical: no condensing temperature
            continue
        name, unit = _QUANTITIES[stem]
        lo, hi = bounds.get(f"{stem}_min"), bounds.get(f"{stem}_max")
        side = "below the minimum" if lo is not None and value < lo * (1 - 1e-9) else None
        if side is None and hi is not None and value > hi * (1 + 1e-9):
            side = "above the maximum"
        if side is not None:
            bound = lo if side.startswith("below") else hi
            assert bound is not None
            return (
                f"outside the envelope of {case.refrigerant.name}: {name} "
                f"{_written(value, unit)} is {side} {_written(bound, unit)} "
                f'({case.refrigerant.path}, [envelope]); set solver.envelope = "ignore" '
                "to run it anyway"
            )
    return None


def check_envelope(case: Case) -> None:
    """Refuse a point outside the envelope (unless ``solver.envelope = "ignore"``).

    Raises
    ------
    OutsideEnvelopeError
        With the one line of :func:`envelope_refusal`.
    """
    if getattr(case.solver, "envelope", "refuse") == "ignore":
        return
    refusal = envelope_refusal(case)
    if refusal is not None:
        raise OutsideEnvelopeError(case.name, "operating_point", refusal)
