"""The paper study's runs and results as data: configurations, run names, :class:`RunRecord`
and :class:`PaperStudy` (shared by :mod:`.paper`, which runs the study, and
:mod:`.paper_report`, which writes it).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pandas as pd

from recipsim.physics.mechanics.pinned import PinnedLoads
from recipsim.studies.paper_load_run import LoadRun

#: Load configurations, in the paper's order.
CONFIGURATIONS = ("inertia", "gas", "gas_damped")
#: How the undamped runs are made: their periodic response (shooting), or a transient
#: of fixed revolutions from the quasi-static or the unloaded pose.
#: the undamped start from the pose the pinned loads deflect the mechanism to
DEFLECTED_START = "quasi_static"
UNDAMPED_STARTS = ("periodic", DEFLECTED_START, "unloaded")
#: Runs, as ``<config>_<model>`` (``gas_damped`` reuses the ``gas`` pinned run).
RUNS = ("inertia_pinned", "inertia_flexible", "gas_pinned", "gas_flexible", "gas_damped_flexible")
#: Runs of the hydrodynamic column (``hydrodynamic=case``), after :data:`RUNS`.
HYDRODYNAMIC_RUNS = ("inertia_hydrodynamic", "gas_hydrodynamic")
#: The pinned run each configuration is compared with.
PINNED_OF = {"inertia": "inertia_pinned", "gas": "gas_pinned", "gas_damped": "gas_pinned"}
#: Figure labels of the configurations.
LABELS = {
    "inertia": "inertia load only",
    "gas": "gas (compressive) load",
    "gas_damped": "gas load with dissipation",
}
#: Cylinder pressure column of the study's cycle tables.
PRESSURE_COLUMN = "cylinder_pressure [Pa]"


@dataclass(frozen=True)
class RunRecord:
    """How one run of the study went.

    Attributes
    ----------
    name : str
        ``<config>_<model>``, e.g. ``gas_flexible``.
    configuration : str
        One of :data:`CONFIGURATIONS`.
    model : str
        ``"pinned"``, ``"flexible"`` or ``"hydrodynamic"``.
    mode : str
        ``"algebraic"`` (pinned), ``"shooting"`` (undamped flexible, periodic
        response), ``"fixed_revolutions"`` (undamped flexible transient),
        ``"until_periodic"`` (damped flexible) or ``"case"`` (hydrodynamic); every
        flexible run is a case solved by :func:`recipsim.solve.periodic.solve_periodic`.
    revolutions : int
        Revolutions integrated (0 for pinned; with shooting every revolution, the
        Jacobian's included).
    converged : bool or None
        Periodicity test passed (damped and shooting runs); True for pinned (exactly
        periodic); None for fixed-revolution runs (not tested).
    cycle_change : float or None
        Cycle residual of the reported revolution [-]
        (:func:`recipsim.solve.residual.cycle_residual`; flexible runs).
    nfev : int
        Right-hand-side evaluations (0 for pinned).
    wall_time : float
        Wall time of the run including its report table [s].
    """

    name: str
    configuration: str
    model: str
    mode: str
    revolutions: int
    converged: bool | None
    cycle_change: float | None
    nfev: int
    wall_time: float


@dataclass(frozen=True)
class PaperStudy:
    """Results of :func:`run_paper_study`.

    Attributes
    ----------
    table1 : pandas.DataFrame
        One row per bearing (column ``bearing``), the columns of ``table1.csv``.
    cycles : dict of str to pandas.DataFrame
        Reported revolution of each run in :data:`RUNS`, report columns.
    runs : dict of str to RunRecord
        Per run: revolutions, convergence, wall time.
    timings : dict of str to float
        Wall time per run, ``"compute"`` (all runs), ``"write"`` (files and figures)
        and ``"total"`` [s]; ``study.json`` holds the runs' and ``"compute"``.
    settings : dict
        The study's settings (as written to ``study.json``).
    flexible : dict of str to LoadRun
        The flexible runs (``inertia_flexible``, ``gas_flexible``, ``gas_damped_flexible``).
    pinned : dict of str to PinnedLoads
        The pinned runs (``inertia_pinned``, ``gas_pinned``).
    hydrodynamic : dict of str to LoadRun
        The hydrodynamic runs by configuration (``inertia``, ``gas``); empty without
        the column.
    out_dir : pathlib.Path or None
        Where the study was written.
    files : tuple of pathlib.Path
        Files written (under ``out_dir``).
    """

    table1: pd.DataFrame
    cycles: dict[str, pd.DataFrame]
    runs: dict[str, RunRecord]
    timings: dict[str, float]
    settings: dict[str, Any]
    flexible: dict[str, LoadRun] = field(repr=False)
    pinned: dict[str, PinnedLoads] = field(repr=False)
    hydrodynamic: dict[str, LoadRun] = field(default_factory=dict, repr=False)
    out_dir: Path | None = None
    files: tuple[Path, ...] = ()
