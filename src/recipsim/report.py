"""Per-case report: CSV tables (the contract), figures, the case as run, provenance.

A report directory is built beside its destination and swapped in with renames, so a
reader never sees a half-written report and an interrupted run leaves the previous
one intact.
"""

from __future__ import annotations

import json
import platform
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pandas as pd

from . import __version__
from .atomic import atomic_directory
from .case import Case
from .solve.periodic import PeriodicSolution
from .thermo.coolprop_info import coolprop_version


def case_provenance(case: Case, argv: list[str] | None = None) -> dict[str, Any]:
    """Versions, options and solver settings of a run of ``case``."""
    import numba
    import numpy
    import scipy

    return {
        "recipsim": __version__,
        "git_commit": git_commit(),
        "python": sys.version.split()[0],
        "platform": platform.platform(),
        "CoolProp": coolprop_version(),
        "numpy": numpy.__version__,
        "scipy": scipy.__version__,
        "numba": numba.__version__,
        "pandas": pd.__version__,
        "property_backend": f"CoolProp {case.options.properties.upper()}",
        "fluid": case.refrigerant.coolprop_name,
        "options": case.options.__dict__,
        "solver": case.solver.__dict__,
        "created": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
        "command": argv or sys.argv,
    }


def provenance(solution: PeriodicSolution, argv: list[str] | None = None) -> dict[str, Any]:
    """:func:`case_provenance` plus the solver statistics of a run."""
    meta = case_provenance(solution.model.case, argv)
    meta.update(
        {
            "revolutions": solution.revolutions,
            "cycle_residual": solution.residual,
            "residual_history": solution.residual_history,
            "rhs_evaluations": solution.nfev,
            "steps": solution.steps,
            "rejected_steps": solution.rejected,
            "events": solution.events,
            "wall_time_s": solution.wall_time,
        }
    )
    table = getattr(solution.model.props, "table", None)
    if table is not None:  # properties = "table": its measured error against HEOS, cache
        meta.update(table.provenance())
    return meta


def git_commit() -> str:
    try:
        root = Path(__file__).resolve().parents[2]
        out = subprocess.run(
            ["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True, text=True, timeout=5
        )
        return out.stdout.strip() if out.returncode == 0 else ""
    except (OSError, subprocess.SubprocessError):
        return ""


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
            from .plotting import save_cycle_figures

            save_cycle_figures(cycle, tmp, plenum=plenum)
    return out_dir
