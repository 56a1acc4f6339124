"""Provenance of a run: versions, options, solver settings and statistics, command line."""

from __future__ import annotations

import platform
import subprocess
import sys
import time
from functools import lru_cache
from pathlib import Path
from typing import Any

import numba
import numpy
import pandas
import scipy

from recipsim.case.case import Case
from recipsim.physics.thermo.coolprop_info import coolprop_version
from recipsim.solve.periodic import PeriodicSolution
from recipsim.version import __version__


def case_provenance(case: Case, argv: list[str] | None = None) -> dict[str, Any]:
    """Versions, options and solver settings of a run of ``case``."""
    return {
        "recipsim": __version__,
        "git_commit": git_commit(),
        "python": sys.version.split()[0],
        "platform": platform.platform(),
        "CoolProp": coolprop_version(),
        "numpy": numpy.__version__,
        "scipy": scipy.__version__,
        "numba": numba.__version__,
        "pandas": pandas.__version__,
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


@lru_cache(maxsize=1)
def git_commit() -> str:
    """Commit of recipsim's source checkout (``""`` outside one), asked of git once per
    process."""
    try:
        root = Path(__file__).resolve().parents[3]
        out = subprocess.run(
            ["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True, text=True, timeout=5
        )
        return out.stdout.strip() if out.returncode == 0 else ""
    except (OSError, subprocess.SubprocessError):
        return ""
