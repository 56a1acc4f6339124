"""The paper's bearing-load study: pinned against flexible crank train (Kurka et al. 2010).

Section 4 and Table 1 of the paper compare the bearing loads of the rigid ("pinned")
crank train with those of the crank train on visco-elastic bearings ("flexible") for
three loads. This module runs the same study for any mechanism and pressure curve:

==============  ================================  =====================================
configuration   cylinder pressure                 flexible run
==============  ================================  =====================================
``inertia``     shell pressure at every angle     no damping (see below)
``gas``         the pressure curve                no damping (see below)
``gas_damped``  the pressure curve                the spec's damping, run to periodic
==============  ================================  =====================================

The pinned mechanism is solved algebraically at constant speed (the ``gas_damped``
configuration reuses the ``gas`` pinned run). With the default ``drive="torque_profile"``
the damped crank is driven by the pinned driving torque of the same load (the paper's
procedure) and its speed is free.

Every flexible run is the case (its mechanism, geometry and operating point) under
the load's pressure curve, solved like any case: the compiled scene and the shared
periodic solver (:mod:`.paper_linear_runs`). Undamped flexible runs never settle by
running revolutions (nothing dissipates the free vibration, Floquet multipliers of
modulus 1). With the default ``undamped_start="periodic"`` they are the periodic forced
response, found by shooting (``solver.periodic = "shooting"``,
:func:`recipsim.solve.shooting.solve_shooting`, at a tenth of ``rtol``: undamped
revolutions are noisier in the step sequence) at constant crank speed: under the
angle-only torque profile an undamped crank has no periodic state to find (its speed
drifts by the energy the torque does not balance, and the response of the undamped
high-frequency modes is too sensitive to that speed for either solver to settle).
``undamped_start="quasi_static"`` or ``"unloaded"`` instead report a transient as a
time-marching run of the paper would: ``undamped_revolutions`` revolutions under the
study's drive from the quasi-static pinned pose at TDC, or from the pinned pose with
undeflected bearings, the last one reported.

The hydrodynamic column (``hydrodynamic=True``): the ``inertia`` and ``gas`` loads with
the primary, secondary and eccentric journals on oil films (``finite_journal`` by
default, the case's film geometry and oil), run like any case through
:mod:`recipsim.studies.paper_hydrodynamic` at constant speed; its RMS and peak loads
against pinned answer the paper's conclusion 3 (:func:`.paper_report.conclusion_three`).

:func:`run_paper_study` returns a :class:`PaperStudy` and writes into ``out_dir``
atomically (built in a temporary directory beside it, then swapped in):

- ``table1.csv``: one row per bearing (``bearing``, ``BEARING_NAMES`` order), RMS loads
  ``<config>_<model>_rms [N]``, relative differences ``<config>_flexible_vs_pinned [-]``
  (flexible RMS / pinned RMS - 1), peak loads ``<config>_<model>_peak [N]`` and largest
  orbit radii ``<config>_flexible_orbit_max [m]``; with the hydrodynamic column also
  ``<config>_hydrodynamic_rms [N]``, ``_vs_pinned [-]``, ``_peak [N]``, ``_orbit_max [m]``
  and ``_min_film [m]`` (nan for the bearings without a film) for ``inertia`` and ``gas``;
- ``cycle_<config>_<model>.csv``: the reported revolution of every run; the flexible and
  hydrodynamic ones are ``recipsim run``'s cycle tables plus ``drive_torque [N m]``, the
  pinned ones their bearing, torque, speed and ``cylinder_pressure [Pa]`` columns with
  zero displacements;
- ``bearing_loads_<config>.png``, ``orbits.png``, ``orbits_hydrodynamic.png`` (with the
  column: the journals inside their clearance circles), ``drive_torque.png``;
- ``study.json`` (settings, and per run its revolutions, convergence and wall time; the
  films and the conclusion-3 answer) and ``README.md`` (the same, readable).

The study's data types are in :mod:`.paper_runs`, its tables in :mod:`.paper_tables`,
the runs on linear bearings in :mod:`.paper_linear_runs` (each flexible run a case,
:mod:`.paper_load_run`), the hydrodynamic runs in :mod:`.paper_hydrodynamic`, the
settings in :mod:`.paper_settings` and the files in :mod:`.paper_report`.
"""

from __future__ import annotations

import json
import time
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pandas as pd

from recipsim.atomic import atomic_directory
from recipsim.model.build import crank_geometry
from recipsim.physics.mechanics.drives import DRIVES, TORQUE_PROFILE
from recipsim.physics.mechanics.tabulated import PressureCurve
from recipsim.studies.paper_hydrodynamic import DEFAULT_LAW, constant_curve, run_hydrodynamic
from recipsim.studies.paper_linear_runs import flexible_runs, pinned_runs
from recipsim.studies.paper_load_run import LoadRun
from recipsim.studies.paper_report import readme, study_summary, write_figures
from recipsim.studies.paper_runs import (
    HYDRODYNAMIC_RUNS,
    RUNS,
    UNDAMPED_STARTS,
    PaperStudy,
    RunRecord,
)
from recipsim.studies.paper_settings import hydrodynamic_settings, study_settings
from recipsim.studies.paper_tables import build_table1, flexible_table

if TYPE_CHECKING:
    from recipsim.case.load import Case

__all__ = ["run_paper_study", "write_paper_study"]


# ------------------------------------------------------------------------------- study


def run_paper_study(
    case: Case,
    curve: PressureCurve,
    out_dir: str | Path | None,
    *,
    drive: str = TORQUE_PROFILE.name,
    rtol: float = 1e-6,
    undamped_revolutions: int = 8,
    samples_per_revolution: int = 360,
    plots: bool = True,
    undamped_start: str = "periodic",
    periodic_tolerance: float = 1e-3,
    max_revolutions: int = 30,
    hydrodynamic: bool = False,
    bearing_law: str = DEFAULT_LAW,
) -> PaperStudy:
    """Run the paper's pinned-against-flexible study and write its report; the
    :class:`PaperStudy`.

    Parameters
    ----------
    case : Case
        Gives the mechanism (the bearings' stiffness and damping: the undamped runs use
        it with zero damping, the ``gas_damped`` run as given), the geometry, the shell
        pressure (also the cylinder pressure of the ``inertia`` configuration: no net
        gas force), the crank speed (constant for the pinned runs; prescribed, or
        initial and nominal for ``drive="torque_profile"``) and the solver
        (``solver.method``; the study sets the tolerances below).
    curve : PressureCurve
        Cylinder pressure against crank angle from TDC [rad], [Pa] (the ``gas`` load).
    out_dir : str or pathlib.Path or None
        Report directory, replaced atomically if it exists; None writes nothing.
    drive : {"torque_profile", "constant_speed"}
        Drive of the flexible runs; ``torque_profile`` applies the pinned driving torque
        of the same load (the paper's procedure).
    rtol, periodic_tolerance : float
        Relative tolerance of the flexible runs (``solver.rtol``) [-]; cycle tolerance of
        the damped and the shooting runs (``solver.cycle_tolerance``).
    undamped_revolutions : int
        Revolutions of the undamped transients (``undamped_start`` other than
        ``"periodic"``); the last one is reported.
    samples_per_revolution : int
        Samples of every reported revolution (equal crank-angle steps from TDC).
    plots : bool
        Write the figures.
    undamped_start : {"periodic", "quasi_static", "unloaded"}
        The undamped runs: their periodic response at constant speed, by shooting
        (``periodic``); or a transient of ``undamped_revolutions`` with the bearings
        deflected by the pinned loads (``quasi_static``, a case's initial state) or
        undeflected (``unloaded``), which starts a much larger free vibration.
    max_revolutions : int
        Revolution limit of the damped run; of a shooting run, twice this (its
        Jacobian costs one revolution per state).
    hydrodynamic : bool
        Add the hydrodynamic column: the ``inertia`` and ``gas`` loads with the case's
        journals on films (:func:`recipsim.studies.paper_hydrodynamic.run_hydrodynamic`).
    bearing_law : str
        One of :data:`recipsim.studies.paper_hydrodynamic.FILM_LAWS`.
        Film law of the hydrodynamic journals.

    Raises
    ------
    ValueError
        An unknown ``drive`` or ``undamped_start``, fewer than 1 revolution or 4 samples.
    SolverError
        If an integration fails.
    CaseError
        A setting outside a case key's range, or journals without film data (``hydrodynamic``).
    """
    _check_settings(drive, undamped_start, undamped_revolutions, samples_per_revolution)
    start = time.perf_counter()
    loads = {"inertia": constant_curve(case.operating_point.shell_pressure), "gas": curve}
    options: dict[str, Any] = {
        "drive": drive, "rtol": rtol, "method": case.solver.method,
        "undamped_revolutions": undamped_revolutions, "undamped_start": undamped_start,
        "samples_per_revolution": samples_per_revolution,
        "periodic_tolerance": periodic_tolerance, "max_revolutions": max_revolutions,
    }  # fmt: skip
    study = _run_study(case, curve, loads, options, hydrodynamic, bearing_law)
    return _write_study(study, out_dir, plots, start)


def _run_study(
    case: Case,
    curve: PressureCurve,
    loads: dict[str, PressureCurve],
    options: dict[str, Any],
    hydrodynamic: bool,
    bearing_law: str,
) -> PaperStudy:
    """Every run of the study (pinned, flexible, and the hydrodynamic column if asked),
    its tables and settings; nothing written, no ``compute``/``write``/``total`` times."""
    cycles: dict[str, pd.DataFrame] = {}
    runs: dict[str, RunRecord] = {}
    pinned = pinned_runs(case, loads, options)
    for name, (table, _, record) in pinned.items():
        cycles[name], runs[name] = table, record
    flexible = flexible_runs(case, loads, options)
    for name, (result_f, record) in flexible.items():
        cycles[name], runs[name] = flexible_table(result_f), record
    films: dict[str, LoadRun] = {}
    op = case.operating_point
    settings = study_settings(
        case.mechanism, crank_geometry(case), curve, op.shell_pressure, op.shaft_speed,
        case=case.name, **options,
    )  # fmt: skip
    if hydrodynamic:
        samples = options["samples_per_revolution"]
        films = run_hydrodynamic(case, loads, law=bearing_law, samples_per_revolution=samples)
        for config, h in films.items():
            name = f"{config}_hydrodynamic"
            cycles[name] = h.cycle
            runs[name] = RunRecord(
                name, config, "hydrodynamic", "case", h.revolutions, h.converged, h.residual,
                h.nfev, h.wall_time,
            )  # fmt: skip
        settings["hydrodynamic"] = hydrodynamic_settings(case, bearing_law)
    order = [*RUNS, *(HYDRODYNAMIC_RUNS if films else ())]
    loads_p = {k: v[1] for k, v in pinned.items()}
    return PaperStudy(
        table1=build_table1(loads_p, {k: v[0] for k, v in flexible.items()}, films),
        cycles={k: cycles[k] for k in order},
        runs={k: runs[k] for k in order},
        timings={name: runs[name].wall_time for name in order},
        settings=settings,
        flexible={k: v[0] for k, v in flexible.items()},
        pinned=loads_p,
        hydrodynamic=films,
    )


def _write_study(
    study: PaperStudy, out_dir: str | Path | None, plots: bool, start: float
) -> PaperStudy:
    """Write the report into ``out_dir`` (None: nothing); the study with its files and
    the ``compute``, ``write`` and ``total`` times since ``start`` [s]."""
    timings = study.timings
    files: tuple[Path, ...] = ()
    if out_dir is not None:
        t0 = time.perf_counter()
        timings["compute"] = t0 - start
        files = tuple(write_paper_study(study, out_dir, plots=plots))
        timings["write"] = time.perf_counter() - t0
    timings["total"] = time.perf_counter() - start
    return replace(study, out_dir=None if out_dir is None else Path(out_dir), files=files)


def _check_settings(drive: str, undamped_start: str, revolutions: int, samples: int) -> None:
    allowed = [d.name for d in DRIVES if not d.motor_curve]  # the paper's drives
    if drive not in allowed:
        raise ValueError(f"drive {drive!r}; allowed: {', '.join(map(repr, allowed))}")
    if undamped_start not in UNDAMPED_STARTS:
        raise ValueError(f"undamped_start {undamped_start!r}; allowed: {UNDAMPED_STARTS}")
    if revolutions < 1:
        raise ValueError(f"undamped_revolutions {revolutions}; allowed: >= 1")
    if samples < 4:
        raise ValueError(f"samples_per_revolution {samples}; allowed: >= 4")


# ------------------------------------------------------------------------------ output


def write_paper_study(study: PaperStudy, out_dir: str | Path, *, plots: bool = True) -> list[Path]:
    """Write a study's files into ``out_dir`` atomically.

    Everything is built in a temporary directory beside ``out_dir`` and swapped in
    with renames (:func:`recipsim.atomic.atomic_directory`); a previous ``out_dir``
    written by recipsim is replaced entirely, and left untouched if writing fails; any
    other existing directory is refused.

    Parameters
    ----------
    study : PaperStudy
    out_dir : str or pathlib.Path
    plots : bool
        Write the figures.

    Returns
    -------
    list of pathlib.Path
        The files written, as paths under ``out_dir``.
    """
    out_dir = Path(out_dir)
    with atomic_directory(out_dir) as tmp:
        names = ["table1.csv"]
        study.table1.to_csv(tmp / "table1.csv", index=False)
        for run, table in study.cycles.items():
            names.append(f"cycle_{run}.csv")
            table.to_csv(tmp / names[-1], index=False)
        if plots:
            names.extend(p.name for p in _write_figures(study, tmp))
        names.extend(["study.json", "README.md"])
        info = study_summary(study, names)
        (tmp / "study.json").write_text(json.dumps(info, indent=2) + "\n")
        (tmp / "README.md").write_text(readme(study, names))
    return [out_dir / n for n in names]


def _write_figures(study: PaperStudy, directory: Path) -> list[Path]:

    return write_figures(study, directory)
