"""Per-case report: CSV tables (the contract), figures, the case as run, provenance.

A report directory is built beside its destination and swapped in with renames, so a
reader never sees a half-written report and an interrupted run leaves the previous
one intact.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pandas as pd

from recipsim.atomic import atomic_directory

if TYPE_CHECKING:
    from recipsim.results.run import CaseRun


def write_report(
    out_dir: Path,
    summary_row: dict[str, Any],
    cycle: pd.DataFrame,
    case_text: str,
    overrides: list[str],
    meta: dict[str, Any],
    plenum: tuple[float, float] | None = None,
    plots: bool = True,
) -> Path:
    """Write one case's report into ``out_dir`` atomically.

    ``out_dir`` is replaced whole if it is a recipsim output directory (or empty);
    any other existing directory is refused (:func:`recipsim.atomic.atomic_directory`).

    Returns
    -------
    Path
        ``out_dir``.
    """
    out_dir = Path(out_dir)
    with atomic_directory(out_dir) as tmp:
        pd.DataFrame([summary_row]).to_csv(tmp / "summary.csv", index=False)
        cycle.to_csv(tmp / "cycle.csv", index=False)
        header = "".join(f"# --set {o}\n" for o in overrides)
        (tmp / "case.toml").write_text(
            ("# overrides applied on top of this file:\n" + header if overrides else "") + case_text
        )
        (tmp / "provenance.json").write_text(json.dumps(meta, indent=2, default=str))
        if plots:
            from recipsim.report.plotting import save_cycle_figures

            save_cycle_figures(cycle, tmp, plenum=plenum)
    return out_dir


def write_case_report(
    run: CaseRun, out_dir: Path, overrides: list[str], plots: bool = True
) -> Path:
    """Write the report of ``run`` atomically into ``out_dir`` (see reports/README.md)."""
    op = run.case.operating_point
    return write_report(
        out_dir,
        run.row,
        run.cycle,
        run.case.source_text,
        overrides,
        run.meta,
        plenum=(op.suction_pressure, op.discharge_pressure),
        plots=plots,
    )
