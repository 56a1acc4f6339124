"""Physical priors of calibrated parameters: the plausible range each case key declares
(``Field.plausible`` in the case schema, with its source) and the verdict on a fitted
value and its 95 % interval.

A fit is judged, not refused, on its priors: a value outside the plausible range, or an
interval over more than :data:`MAX_INTERVAL_DECADES` decades, is reported in the
parameters table, ``calibration.json`` and the console, naming the parameter. (The fit
itself refuses a parameter whose one standard deviation spans more than a decade:
:func:`recipsim.studies.calibrate.fit.check_determined`.)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from recipsim.case.case import Case
from recipsim.case.case_schema import (
    GEOMETRY_SPEC,
    HEAT_TRANSFER_SPEC,
    LEAKAGE_SPEC,
    OPERATING_POINT_SPEC,
    SOLVER_SPEC,
    VALVE_SPEC,
    VALVES_TOP_SPEC,
)
from recipsim.case.motor import MOTOR_SPEC
from recipsim.case.thermal import THERMAL_SPEC
from recipsim.schema import Field, Spec

#: Widest 95 % interval of a fitted parameter judged determined [decades].
MAX_INTERVAL_DECADES = 1.0
#: Verdicts (the ``verdict`` column starts with one of these words).
PLAUSIBLE, OUTSIDE, LOOSE, AT_BOUND = "plausible", "outside", "loose", "at a bound"
UNDECLARED = "no range"

#: Tables of a case file whose keys are declared in one spec (``valves.<name>.<key>``
#: are the valves' own keys).
_TABLES: dict[str, Spec] = {
    "operating_point": OPERATING_POINT_SPEC,
    "geometry": GEOMETRY_SPEC,
    "leakage": LEAKAGE_SPEC,
    "heat_transfer": HEAT_TRANSFER_SPEC,
    "solver": SOLVER_SPEC,
    "motor": MOTOR_SPEC,
    "thermal": THERMAL_SPEC,
}


@dataclass(frozen=True)
class Prior:
    """The plausible range of a case key [SI] and where it comes from."""

    lower: float
    upper: float
    source: str


def declared_field(key: str) -> Field | None:
    """The schema's declaration of a dotted case key (None: not a declared number)."""
    parts = key.split(".")
    if parts[0] == "valves":
        spec = VALVE_SPEC if len(parts) == 3 else VALVES_TOP_SPEC
    else:
        spec = _TABLES.get(parts[0], {})
    field = spec.get(parts[-1]) if len(parts) in (2, 3) else None
    return field if isinstance(field, Field) else None


def _option(case: Case, key: str) -> str:
    table, _, name = key.partition(".")
    return str(getattr(getattr(case, table, None), name, ""))


def prior_of(case: Case, key: str) -> Prior | None:
    """The plausible range ``key`` declares for ``case`` (None: none declared, or one
    that holds under another option than the case's)."""
    field = declared_field(key)
    if field is None or field.plausible is None:
        return None
    if field.plausible_when is not None:
        option, value = field.plausible_when
        if _option(case, option) != value:
            return None
    return Prior(field.plausible[0], field.plausible[1], field.plausible_source)


def interval_decades(low: float, high: float) -> float:
    """Width of a 95 % interval in decades (inf when it reaches zero or below)."""
    if not (low > 0.0 and high > 0.0):
        return math.inf
    return math.log10(high / low)


def verdict(
    value: float, interval: tuple[float, float], prior: Prior | None, at_bound: bool = False
) -> str:
    """One phrase on a fitted value: within its plausible range, outside it, its interval
    too wide (over :data:`MAX_INTERVAL_DECADES` decades, or reaching zero), ended on a
    bound of the fit, or no range declared. Every fault that holds is named."""
    faults = [f"{AT_BOUND} of the fit: the data push it further"] if at_bound else []
    if prior is not None and not prior.lower <= value <= prior.upper:
        faults.append(f"{OUTSIDE} the plausible range {prior.lower:.3g} to {prior.upper:.3g}")
    decades = interval_decades(*interval)
    if decades > MAX_INTERVAL_DECADES:
        width = "reaches zero" if math.isinf(decades) else f"spans {decades:.2g} decades"
        faults.append(f"{LOOSE}: the 95 % interval {width}")
    if faults:
        return "; ".join(faults)
    if prior is None:
        return f"{UNDECLARED}: no plausible range declared"
    return f"{PLAUSIBLE}: within {prior.lower:.3g} to {prior.upper:.3g}"


def judged(verdict_text: str) -> bool:
    """Whether a verdict reports a fault (outside its range or a loose interval)."""
    return verdict_text.startswith((OUTSIDE, LOOSE, AT_BOUND))
