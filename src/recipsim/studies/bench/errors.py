"""Errors of a rung against the reference: relative errors of summary quantities and
the RMS error of the pressure trace.

Compared quantities (:func:`compared_quantities`): discharge mass flow, indicated
power, COP, and every bearing's RMS and peak load (``bearing_rms_<name> [N]``,
``bearing_max_<name> [N]``). Each error is ``|x / x_ref - 1|``. The pressure trace
error is ``sqrt(mean((p - p_ref)^2)) / max(p_ref)`` with the rung's trace interpolated
(periodically, linearly) onto the reference's crank angles. ``max_error`` is the largest
of all of them. A quantity the reference does not have (NaN, e.g. COP without a gas
model) is not compared; one the rung lacks while the reference has it counts as an
infinite error.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping

import numpy as np

#: Summary columns compared besides the bearing loads.
PERFORMANCE = ("discharge_mass_flow [kg/s]", "indicated_power [W]", "COP [-]")
_BEARING = re.compile(r"^bearing_(rms|max)_\w+ \[N\]$")
PRESSURE_ERROR = "error_pressure_trace [-]"
MAX_ERROR = "max_error [-]"


def compared_quantities(row: Mapping[str, object]) -> dict[str, float]:
    """The summary values a rung is judged by, from a summary row (units in the keys)."""
    keys = [k for k in PERFORMANCE if k in row] + [k for k in row if _BEARING.match(k)]
    return {k: float(row[k]) for k in keys}  # type: ignore[arg-type]


def error_column(quantity: str) -> str:
    """CSV column of the relative error of ``quantity``: ``error_<name> [-]``."""
    return f"error_{quantity.split(' [')[0]} [-]"


def relative_error(value: float, reference: float) -> float:
    """``|value / reference - 1|`` (inf if the value is missing, NaN if the reference is)."""
    if not math.isfinite(reference) or reference == 0.0:
        return math.nan
    if not math.isfinite(value):
        return math.inf
    return abs(value / reference - 1.0)


def pressure_trace_error(
    angles: np.ndarray, pressure: np.ndarray, ref_angles: np.ndarray, ref_pressure: np.ndarray
) -> float:
    """RMS difference of two pressure traces relative to the reference's peak [-].

    Parameters
    ----------
    angles, pressure : ndarray
        The rung's trace: crank angle [deg] and cylinder pressure [Pa].
    ref_angles, ref_pressure : ndarray
        The reference's trace; the rung's is interpolated onto ``ref_angles``
        (periodic in 360 deg).
    """
    order = np.argsort(angles)
    p = np.interp(ref_angles, np.asarray(angles)[order], np.asarray(pressure)[order], period=360.0)
    return float(np.sqrt(np.mean((p - ref_pressure) ** 2)) / np.max(ref_pressure))


def error_columns(
    values: Mapping[str, float],
    reference: Mapping[str, float],
    trace: tuple[np.ndarray, np.ndarray] | None,
    ref_trace: tuple[np.ndarray, np.ndarray],
) -> dict[str, float]:
    """Every error column of a rung and ``max_error [-]``.

    Parameters
    ----------
    values, reference : mapping
        Compared quantities of the rung and of the reference (:func:`compared_quantities`).
    trace, ref_trace : tuple of ndarray
        ``(crank angle [deg], cylinder pressure [Pa])`` of the rung and the reference.
    """
    out: dict[str, float] = {}
    for name, ref in reference.items():
        out[error_column(name)] = relative_error(values.get(name, math.nan), ref)
    if trace is None:
        out[PRESSURE_ERROR] = math.inf
    else:
        out[PRESSURE_ERROR] = pressure_trace_error(trace[0], trace[1], ref_trace[0], ref_trace[1])
    finite = [e for e in out.values() if not math.isnan(e)]
    out[MAX_ERROR] = max(finite) if finite else math.nan
    return out
