"""The parameters of a calibration: dotted case keys with their bounds
(``KEY=LOWER:UPPER``), read and checked against the case before any fit."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from recipsim.case.case import Case
from recipsim.errors import CaseError, RecipsimError
from recipsim.studies.calibrate.priors import declared_field
from recipsim.units import _registry


class CalibrationError(RecipsimError):
    """An ill-posed or failed calibration (the message says why)."""


@dataclass(frozen=True)
class Parameter:
    """A case value to fit, in SI.

    Attributes
    ----------
    key : str
        Dotted case key (``"heat_transfer.coefficient"``).
    lower, upper : float
        Bounds [SI unit of the key].
    initial : float
        Starting value (the case's own, else the bounds' geometric or plain mean).
    """

    key: str
    lower: float
    upper: float
    initial: float

    @property
    def logarithmic(self) -> bool:
        """Fitted in its logarithm (positive bounds)."""
        return self.lower > 0.0

    def to_x(self, value: float) -> float:
        return math.log(value) if self.logarithmic else (value - self.lower) / self.span

    def from_x(self, x: float) -> float:
        return math.exp(x) if self.logarithmic else self.lower + x * self.span

    @property
    def span(self) -> float:
        return self.upper - self.lower


def _si(text: str, where: str) -> float:
    """A bound or value as written (bare number in SI, or a quantity with its unit)."""
    text = text.strip()
    try:
        return float(text)
    except ValueError:
        pass
    try:
        quantity = _registry().Quantity(text).to_base_units()
        return float(quantity.magnitude)
    except Exception:  # pint raises several unrelated types for bad strings
        raise CalibrationError(f"{where}: cannot read {text!r} as a number or quantity") from None


def case_value(case: Case, key: str) -> float | None:
    """The case's own value of a dotted key, in SI (None when the file leaves it to its
    default or it is not a number)."""
    node: object = case.raw
    for part in key.split("."):
        if not isinstance(node, dict) or part not in node:
            return None
        node = node[part]
    if isinstance(node, bool) or not isinstance(node, int | float | str):
        return None
    try:
        return _si(str(node), key)
    except CalibrationError:
        return None


def _check_declared_range(key: str, lower: float, upper: float) -> None:
    """Refuse bounds beyond the range the case schema allows for ``key`` (a bound on an
    open end, such as 0 for a positive key, is kept: the fit stays inside its bounds)."""
    field = declared_field(key)
    if field is not None and (lower < field.lo or upper > field.hi):
        raise CalibrationError(
            f"{key}: bounds {lower:g}:{upper:g} reach beyond the allowed {field.allowed()}"
        )


def parse_parameter(text: str, case: Case) -> Parameter:
    """``KEY`` or ``KEY=LOWER:UPPER`` (bounds bare in SI or with units, e.g.
    ``thermal.shell_ua=0.5:10`` or ``valves.discharge.preload=0 N:0.5 N``).

    Without bounds the case's value must be positive; the bounds are then a tenth and
    ten times it.
    """
    key, _, bounds = text.partition("=")
    key = key.strip()
    if not re.fullmatch(r"[A-Za-z_]\w*(\.[A-Za-z_]\w*)+", key):
        raise CalibrationError(f"--parameters {text!r}: expected a dotted case key")
    value = case_value(case, key)
    if bounds:
        low_text, sep, high_text = bounds.partition(":")
        if not sep:
            raise CalibrationError(f"--parameters {text!r}: bounds are written LOWER:UPPER")
        lower, upper = _si(low_text, key), _si(high_text, key)
        if not (math.isfinite(lower) and math.isfinite(upper)):
            raise CalibrationError(f"{key}: bounds must be finite numbers ({lower:g}:{upper:g})")
        if not lower < upper:
            raise CalibrationError(f"{key}: lower bound {lower:g} is not below {upper:g}")
        _check_declared_range(key, lower, upper)
    elif value is not None and value > 0.0:
        lower, upper = 0.1 * value, 10.0 * value
    else:
        raise CalibrationError(
            f"{key}: the case has no positive value to start from ({value}); give bounds "
            f"as {key}=LOWER:UPPER"
        )
    if value is None or not lower <= value <= upper:
        value = math.sqrt(lower * upper) if lower > 0.0 else 0.5 * (lower + upper)
    try:  # a key the case does not have, or a value it refuses, named before any fit
        case.with_({key: value})
    except CaseError as exc:
        raise CalibrationError(f"--parameters {text!r}: {exc.message}") from None
    return Parameter(key, lower, upper, value)
