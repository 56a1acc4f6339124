"""The check's outputs: a fixed-width text table and ``check.csv``."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import asdict
from pathlib import Path
from typing import TYPE_CHECKING

from recipsim.atomic import atomic_write
from recipsim.studies.check.judge import CheckRow
from recipsim.studies.check.metrics import METRICS, ORBIT_METRIC

if TYPE_CHECKING:
    import pandas as pd

TABLE_COLUMNS = (
    ("case", "case"),
    ("expected", "expected"),
    ("outcome", "outcome"),
    ("ok", "match"),
    ("revs", "revolutions"),
    ("wall [s]", "wall_time"),
    ("solve [s]", "solve_time"),
    ("mass", "mass_closure"),
    ("energy", "energy_closure"),
    ("drive", "drive_closure"),
    ("message / note", "text"),
)


def _cell(row: CheckRow, attr: str, width: int = 70) -> str:
    if attr == "match":
        return "yes" if row.matches else "NO"
    if attr in ("expected", "outcome"):
        return str(getattr(row, attr)).replace("_", " ")
    if attr == "text":
        message = row.message.removeprefix(f"{row.file}: ")  # the case column names it
        text = f"{row.note} ({message})" if not row.matches and message else row.note or message
        return text if len(text) <= width else text[: width - 3] + "..."
    value = getattr(row, attr)
    if value is None:
        return "-"
    if attr == "revolutions":
        return str(value)
    if attr in ("wall_time", "solve_time"):
        return f"{value:.2f}"
    if isinstance(value, float):
        return "nan" if math.isnan(value) else f"{value:.1e}"
    return str(value)


def format_table(rows: Sequence[CheckRow], width: int = 70) -> str:
    """A fixed-width text table of ``rows`` (closures [-], wall time [s]) and a count."""
    header = [h for h, _ in TABLE_COLUMNS]
    cells = [[_cell(r, a, width) for _, a in TABLE_COLUMNS] for r in rows]
    widths = [max([len(h)] + [len(c[i]) for c in cells]) for i, h in enumerate(header)]

    def line(values: Sequence[str]) -> str:
        return "  ".join(v.ljust(w) for v, w in zip(values, widths, strict=True)).rstrip()

    lines = [line(header), line(["-" * w for w in widths])]
    lines += [line(c) for c in cells]
    n_ok = sum(r.matches for r in rows)
    lines.append(f"{n_ok} of {len(rows)} cases as expected")
    return "\n".join(lines)


def rows_frame(rows: Sequence[CheckRow]) -> pd.DataFrame:
    """``check.csv``'s table: one row per case, units in the column names."""
    import pandas as pd

    units = {
        "revolutions": "revolutions [-]",
        "cycle_residual": "cycle_residual [-]",
        "wall_time": "wall_time [s]",
        "solve_time": "solve_time [s]",
        "steps": "steps [-]",
        "mass_closure": "mass_closure [-]",
        "energy_closure": "energy_closure [-]",
        "drive_closure": "drive_closure [-]",
        "mass_balance_residual": "mass_balance_residual [-]",
        "energy_balance_residual": "energy_balance_residual [-]",
        "volumetric_efficiency": "volumetric_efficiency [-]",
    }
    records = []
    for row in rows:
        data = asdict(row)
        metrics = data.pop("metrics")
        data["non_finite"] = " ".join(data["non_finite"])
        data["finite"] = row.finite
        record = {units.get(k, k): v for k, v in data.items()}
        for metric in (*METRICS, ORBIT_METRIC):
            if metric not in units:  # volumetric efficiency has its column already
                record[f"{metric} [-]"] = metrics.get(metric)
        records.append(record)
    return pd.DataFrame.from_records(records)


def write_check_csv(rows: Sequence[CheckRow], out: Path) -> Path:
    """Write ``out/check.csv`` atomically; returns its path."""
    path = Path(out) / "check.csv"
    frame = rows_frame(rows)
    atomic_write(path, lambda tmp: frame.to_csv(tmp, index=False))
    return path
