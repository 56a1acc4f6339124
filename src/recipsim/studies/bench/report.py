"""Tables, figure and metadata of a benchmark run.

``<out>/work_precision.csv``: one row per rung (columns in :data:`SETTING_COLUMNS`,
:data:`RUN_COLUMNS`, then one ``error_<quantity> [-]`` per compared quantity,
``error_pressure_trace [-]`` and ``max_error [-]``); ``work_precision.png``: max error
against median wall time, log-log, one labelled marker per rung; ``bench.json``: machine,
versions, reference settings and convergence, the cheapest rung within the error limit
and the speed-up over the baseline. The directory is built beside its destination and
swapped in whole.
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from recipsim.atomic import atomic_directory
from recipsim.physics.thermo.property_backends import TABLE
from recipsim.report.figure_kit import new_figure
from recipsim.studies.bench.errors import MAX_ERROR, error_columns
from recipsim.studies.bench.measure import OK, Outcome

#: Error limit for "the cheapest setting".
ERROR_LIMIT = 1e-3
WALL = "median_wall_time [s]"
CPU = "median_cpu_time [s]"
SETTING_COLUMNS = (
    "rung",
    "integrator",
    "rtol",
    "atol",
    "cycle_tolerance",
    "max_step [deg]",
    "properties",
    "periodic",
    "periodic_used",
    "valves",
    "mechanics",
    "thermal",
    "motor",
    "friction",
    "speed",
    "fidelity",
    "baseline",
    "status",
    "message",
)
RUN_COLUMNS = (
    WALL,
    CPU,
    "build_time [s]",
    "repeats [-]",
    "rhs_evaluations [-]",
    "steps [-]",
    "revolutions [-]",
    "cycle_residual [-]",
)


def outcome_row(
    outcome: Outcome, reference: dict[str, float], ref_trace: tuple[np.ndarray, np.ndarray]
) -> dict[str, Any]:
    """The CSV row of one rung, errors against the reference."""
    row: dict[str, Any] = {"rung": outcome.rung.name}
    row.update(outcome.settings)
    row["periodic_used"] = outcome.periodic_used
    row["fidelity"] = outcome.fidelity
    row["baseline"] = outcome.rung.baseline
    row["status"] = outcome.status
    row["message"] = outcome.message
    row[WALL] = outcome.wall_time
    row[CPU] = outcome.cpu_time
    row["build_time [s]"] = outcome.build_time
    row["repeats [-]"] = len(outcome.wall_times)
    usable = outcome.usable
    row["rhs_evaluations [-]"] = outcome.rhs_evaluations if usable else math.nan
    row["steps [-]"] = outcome.steps if usable and outcome.steps >= 0 else math.nan
    row["revolutions [-]"] = outcome.revolutions if usable else math.nan
    row["cycle_residual [-]"] = outcome.residual
    errors = error_columns(outcome.quantities, reference, outcome.trace, ref_trace)
    if not usable:
        errors = dict.fromkeys(errors, math.nan)
    row.update(errors)
    return row


def table(rows: Sequence[dict[str, Any]]) -> pd.DataFrame:
    """The work-precision table with its columns in the documented order."""
    frame = pd.DataFrame(list(rows))
    first = [c for c in SETTING_COLUMNS + RUN_COLUMNS if c in frame.columns]
    errors = [c for c in frame.columns if c.startswith("error_")]
    rest = [c for c in frame.columns if c not in first and c not in errors and c != MAX_ERROR]
    return frame[first + rest + errors + [MAX_ERROR]]


def cheapest(
    frame: pd.DataFrame, limit: float = ERROR_LIMIT, baseline: bool = False, by: str = WALL
) -> Any:
    """The fastest ``ok`` rung of the case's own fidelity within ``limit`` (None if none).

    ``baseline`` selects among the pure-Python baseline rungs instead of recipsim's;
    ``by`` is the time column that ranks them (:data:`WALL` or :data:`CPU`).
    """
    ok = frame[
        (frame["status"] == OK)
        & (frame["fidelity"] == "case")
        & (frame["baseline"] == baseline)
        & (frame[MAX_ERROR] <= limit)
    ]
    if ok.empty:
        return None
    return ok.loc[ok[by].idxmin()]


def speedup(frame: pd.DataFrame, limit: float = ERROR_LIMIT, by: str = WALL) -> dict[str, Any]:
    """The cheapest rung within ``limit``, the cheapest baseline within it and their ratio
    (rungs ranked by the time column ``by``; both ratios, wall and CPU, reported)."""
    best = cheapest(frame, limit, by=by)
    base = cheapest(frame, limit, baseline=True, by=by)
    out: dict[str, Any] = {
        "error_limit": limit,
        "ranked_by": by,
        "cheapest": None,
        "baseline": None,
    }
    if best is not None:
        out["cheapest"] = _summary(best)
    if base is not None:
        out["baseline"] = _summary(base)
    if best is not None and base is not None:
        out["speedup_wall"] = float(base[WALL] / best[WALL])
        out["speedup_cpu"] = float(base[CPU] / best[CPU])
    return out


def _summary(row: Any) -> dict[str, Any]:
    return {
        "rung": row["rung"],
        "integrator": row["integrator"],
        "rtol": row["rtol"],
        "cycle_tolerance": row["cycle_tolerance"],
        "max_step [deg]": row["max_step [deg]"],
        "properties": row["properties"],
        "periodic": row["periodic"],
        WALL: float(row[WALL]),
        CPU: float(row[CPU]),
        MAX_ERROR: float(row[MAX_ERROR]),
        "revolutions [-]": row["revolutions [-]"],
    }


_STYLE = {
    "dopri5": ("o", "C0"),
    "RK45": ("s", "C1"),
    "DOP853": ("P", "C5"),
    "LSODA": ("^", "C2"),
    "BDF": ("v", "C4"),
    "Radau": ("D", "C6"),
}


def plot(frame: pd.DataFrame, title: str, limit: float = ERROR_LIMIT, by: str = WALL) -> Any:
    """Max error against median time (column ``by``), log-log, one labelled marker per rung."""
    fig = new_figure(figsize=(11, 8))
    ax = fig.add_subplot()
    shown = frame[frame["status"].isin((OK, "unconverged")) & np.isfinite(frame[MAX_ERROR])]
    best = cheapest(frame, limit, by=by)
    seen: set[str] = set()
    for _, row in shown.iterrows():
        marker, colour = _STYLE.get(row["integrator"], ("o", "k"))
        label = row["integrator"]
        if row["baseline"]:
            marker = "X" if row["integrator"] == "RK45" else "P"
            colour, label = "C3", f"baseline {row['integrator']} (pure Python)"
        elif row["properties"] == TABLE.name:
            colour = "C9"
            label += " table"
        elif row["periodic_used"] == "shooting":
            colour = "C8"
            label += " shooting"
        lower = row["fidelity"] != "case"
        if lower:
            label += " (lower fidelity)"
        err = max(float(row[MAX_ERROR]), 1e-12)
        ax.loglog(
            row[by],
            err,
            marker=marker,
            linestyle="none",
            markerfacecolor="none" if lower or row["status"] != OK else colour,
            markeredgecolor=colour,
            color=colour,
            markersize=7,
            label=None if label in seen else label,
        )
        seen.add(label)
        ax.annotate(
            _short(row),
            (row[by], err),
            fontsize=5,
            xytext=(3, 2),
            textcoords="offset points",
        )
    if best is not None:
        ax.loglog(
            best[by],
            max(float(best[MAX_ERROR]), 1e-12),
            marker="*",
            markersize=20,
            markerfacecolor="none",
            markeredgecolor="k",
            linestyle="none",
            label=f"cheapest within {limit:g}: {best['rung']}",
        )
    ax.axhline(limit, color="0.5", linestyle="--", linewidth=0.8)
    what = "wall" if by == WALL else "CPU"
    ax.set_xlabel(f"median {what} time of the periodic solve [s]")
    ax.set_ylabel("max relative error [-] (mass flow, power, COP, bearing loads, p trace)")
    ax.set_title(title, fontsize=9)
    ax.grid(True, which="both", linewidth=0.3)
    ax.legend(fontsize=6, loc="best")
    fig.tight_layout()
    return fig


def _short(row: Any) -> str:
    text = str(row["rung"])
    for long, short in (("baseline ", "py "), (" rtol=", " "), (" cyc=", "/")):
        text = text.replace(long, short)
    return text


def write_bench(
    out_dir: Path,
    frame: pd.DataFrame,
    meta: dict[str, Any],
    title: str,
    plots: bool = True,
    by: str = WALL,
) -> Path:
    """Write ``work_precision.csv``, ``work_precision.png`` and ``bench.json`` atomically."""
    out_dir = Path(out_dir)
    with atomic_directory(out_dir) as tmp:
        frame.to_csv(tmp / "work_precision.csv", index=False)
        if plots:
            plot(frame, title, by=by).savefig(tmp / "work_precision.png", dpi=150)
        (tmp / "bench.json").write_text(json.dumps(meta, indent=2, default=_json_default) + "\n")
    return out_dir


def _json_default(value: Any) -> Any:
    if isinstance(value, (np.integer,)):
        return int(value)
    if isinstance(value, (np.floating,)):
        return float(value)
    if isinstance(value, (np.bool_,)):
        return bool(value)
    if isinstance(value, Path):
        return str(value)
    raise TypeError(f"not JSON serialisable: {type(value).__name__}")


def console_table(frame: pd.DataFrame) -> str:
    """Rung, status, median wall and CPU time, revolutions, max error: a line per rung."""
    lines = [
        f"{'rung':48s} {'status':11s} {'wall [s]':>9s} {'cpu [s]':>9s} {'revs':>5s} "
        f"{'max error':>9s}"
    ]
    for _, row in frame.iterrows():
        revs = row["revolutions [-]"]
        lines.append(
            f"{str(row['rung'])[:48]:48s} {row['status']:11s} {row[WALL]:9.4f} {row[CPU]:9.4f} "
            f"{'' if pd.isna(revs) else int(revs):>5} {row[MAX_ERROR]:9.2e}"
        )
    return "\n".join(lines)
