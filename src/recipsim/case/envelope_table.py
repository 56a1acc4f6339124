"""The ``[envelope]`` table of a refrigerant file: its keys, units and validation
(the check of an operating point against it is :mod:`recipsim.case.envelope`)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from recipsim.errors import CaseError
from recipsim.schema import Field, Spec, read_table

ENVELOPE_SPEC: Spec = {
    "evaporating_temperature_min": Field(
        "K",
        None,
        lo=100.0,
        hi=700.0,
        doc="lowest evaporating temperature",
    ),
    "evaporating_temperature_max": Field(
        "K", None, lo=100.0, hi=700.0, doc="highest evaporating temperature"
    ),
    "condensing_temperature_min": Field(
        "K", None, lo=100.0, hi=700.0, doc="lowest condensing temperature"
    ),
    "condensing_temperature_max": Field(
        "K", None, lo=100.0, hi=700.0, doc="highest condensing temperature"
    ),
    "discharge_pressure_min": Field(
        "Pa", None, lo=0.0, open_lo=True, doc="lowest discharge pressure"
    ),
    "discharge_pressure_max": Field(
        "Pa", None, lo=0.0, open_lo=True, doc="highest discharge pressure"
    ),
    "pressure_ratio_max": Field(
        "dimensionless", None, lo=1.0, open_lo=True, doc="highest discharge over suction pressure"
    ),
    "shaft_speed_min": Field(
        "rad/s", None, lo=0.0, open_lo=True, doc="lowest shaft speed, e.g. '1500 rpm'"
    ),
    "shaft_speed_max": Field("rad/s", None, lo=0.0, open_lo=True, doc="highest shaft speed"),
}

#: quantity -> (envelope key stem, how the value and bound are written)
ENVELOPE_QUANTITIES = {
    "evaporating_temperature": ("evaporating temperature", "degC"),
    "condensing_temperature": ("condensing temperature", "degC"),
    "discharge_pressure": ("discharge pressure", "bar"),
    "pressure_ratio": ("pressure ratio", ""),
    "shaft_speed": ("shaft speed", "rpm"),
}


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
    for stem in ENVELOPE_QUANTITIES:
        lo, hi = bounds.get(f"{stem}_min"), bounds.get(f"{stem}_max")
        if lo is not None and hi is not None and lo > hi:
            raise CaseError(file, f"envelope.{stem}_min", "must not exceed the maximum")
    return bounds
