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
from typing import TYPE_CHECKING

from recipsim.case.envelope_table import ENVELOPE_QUANTITIES
from recipsim.errors import CaseError

if TYPE_CHECKING:
    from recipsim.case.case import Case


class OutsideEnvelopeError(CaseError):
    """The operating point lies outside the refrigerant's documented envelope."""


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
        name, unit = ENVELOPE_QUANTITIES[stem]
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
