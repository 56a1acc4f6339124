"""What ``recipsim compare`` prints: a few key rows of the comparison."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

#: Rows printed to the console (the rest is in comparison.csv).
_CONSOLE_ROWS = (
    "discharge_mass_flow [kg/s]",
    "cooling_capacity [W]",
    "indicated_power [W]",
    "shaft_power [W]",
)


def console_summary(
    labels: tuple[str, str],
    columns: Mapping[str, Any],
    summaries: Sequence[Mapping[str, Any]],
    out: Path,
    wall_time: float,
) -> str:
    """A few key rows of the comparison as text: mass flow, capacity, powers and the
    RMS load of every bearing, with the relative difference in percent.

    Parameters
    ----------
    labels : tuple of str
        The two cases' columns in ``comparison.csv``.
    columns : mapping
        The comparison table (:func:`recipsim.studies.compare.comparison_table`).
    summaries : sequence of mapping
        The two cases' summary rows.
    out : Path
        The comparison's directory.
    wall_time : float
        Wall time of the comparison [s].
    """
    label_a, label_b = labels
    shown = [
        (q, float(a), float(b), float(rel))
        for q, a, b, rel in zip(
            columns["quantity"],
            columns[label_a],
            columns[label_b],
            columns["relative_difference [-]"],
            strict=True,
        )
        if q in _CONSOLE_ROWS or q.startswith("bearing_rms_")
    ]
    width = max(len(row[0]) for row in shown)
    cols = [max(len(label_a), 10), max(len(label_b), 10)]
    lines = []
    for k, row in enumerate(summaries):
        conv = "" if row.get("converged [-]", True) else ", NOT converged"
        lines.append(
            f"{'AB'[k]} {labels[k]}: {row['refrigerant']}, "
            f"{row['shaft_speed [rpm]']:.0f} rpm, pressure {row['pressure']}, "
            f"mechanics {row['mechanics']}, drive {row['drive']}{conv}"
        )
    lines.append(
        f"  {'quantity':<{width}}  {label_a:>{cols[0]}}  {label_b:>{cols[1]}}  {'B-A [%]':>8}"
    )
    for quantity, a, b, rel in shown:
        pct = "-" if math.isnan(rel) else f"{100.0 * rel:+.2f}"
        lines.append(f"  {quantity:<{width}}  {_fmt(a):>{cols[0]}}  {_fmt(b):>{cols[1]}}  {pct:>8}")
    lines.append(f"-> {out} ({wall_time:.1f} s)")
    return "\n".join(lines)


def _fmt(value: float) -> str:
    return "-" if math.isnan(value) else f"{value:.5g}"
