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

Undamped flexible runs never settle by running revolutions (nothing dissipates the
free vibration, Floquet multipliers of modulus 1). With the default
``undamped_start="periodic"`` they are the periodic forced response, found by shooting
(:func:`recipsim.solve.shooting.newton_fixed_point` on the one-revolution map,
integrated with ``method`` at a tenth of ``rtol``: undamped revolutions are noisier
in the step sequence) at constant crank speed: under the angle-only
torque profile an undamped crank has no periodic state to find (its speed drifts by
the energy the torque does not balance, and the response of the undamped
high-frequency modes is too sensitive to that speed for either solver to settle). The
reported revolution is integrated once more from the periodic state and its
periodicity is tested like the damped run's. ``undamped_start="quasi_static"`` or
``"unloaded"`` instead report a transient as a time-marching run of the paper would:
``undamped_revolutions`` revolutions under the study's drive from the quasi-static
pinned pose at TDC, or from the pinned pose with undeflected bearings, the last one
reported.

The hydrodynamic column (``hydrodynamic=case``): the ``inertia`` and ``gas`` loads with
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
- ``cycle_<config>_<model>.csv``: the reported revolution of every run (report columns
  of :meth:`recipsim.physics.mechanics.MechanismResult.columns` plus ``cylinder_pressure [Pa]``;
  pinned tables have zero displacements);
  ``cycle_<config>_hydrodynamic.csv`` are ``recipsim run``'s cycle tables;
- ``bearing_loads_<config>.png``, ``orbits.png``, ``orbits_hydrodynamic.png`` (with the
  column: the journals inside their clearance circles), ``drive_torque.png``;
- ``study.json`` (settings, and per run its revolutions, convergence and wall time; the
  films and the conclusion-3 answer) and ``README.md`` (the same, readable).

The module is over 400 lines because the study is one table built from three kinds of
run; its data types (:mod:`.paper_runs`), the undamped shooting (:mod:`.paper_undamped`),
the hydrodynamic runs (:mod:`.paper_hydrodynamic`) and the files (:mod:`.paper_report`)
live apart.
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

from recipsim import __version__
from recipsim.atomic import atomic_directory
from recipsim.case.mechanism_spec import CrankGeometry, MechanismSpec, with_damping
from recipsim.model.mechanism_parameters import mechanism_parameters
from recipsim.model.pinned import pinned_loads
from recipsim.physics.mechanics.flexible_setup import initial_state
from recipsim.physics.mechanics.layout import BEARING_NAMES
from recipsim.physics.mechanics.pinned import PinnedLoads
from recipsim.physics.mechanics.tabulated import PressureCurve, tabulated_pressure
from recipsim.solve.mechanism_ivp import MechanismResult, simulate_mechanism
from recipsim.studies.paper_hydrodynamic import (
    DEFAULT_LAW,
    JOURNALS,
    SOLVER_METHOD,
    HydrodynamicRun,
    constant_curve,
    run_hydrodynamic,
)
from recipsim.studies.paper_runs import (
    CONFIGURATIONS,
    HYDRODYNAMIC_RUNS,
    LABELS,  # noqa: F401 (re-exported)
    PINNED_OF,
    PRESSURE_COLUMN,
    RUNS,
    UNDAMPED_STARTS,
    PaperStudy,
    RunRecord,
)
from recipsim.studies.paper_undamped import (  # noqa: F401 (re-exported)
    undamped_periodic,
    undamped_periodic_response,
)

if TYPE_CHECKING:
    from recipsim.case.load import Case

__all__ = [
    "CONFIGURATIONS",
    "HYDRODYNAMIC_RUNS",
    "RUNS",
    "PaperStudy",
    "RunRecord",
    "flexible_table",
    "pinned_table",
    "run_paper_study",
    "simulate_mechanism",
    "table1_columns",
    "undamped_periodic_response",
    "write_paper_study",
]

#: The undamped shooting integrates at this times the study's ``rtol``: an undamped
#: revolution's end state jumps with the step sequence by ~1e-3 of the vibration
#: amplitude at rtol 1e-6 under LSODA (the periodicity tolerance), ~1e-4 at 1e-7.
_PERIODIC_RTOL_FACTOR = 0.1

# ----------------------------------------------------------------------------- tables


def _pressures(theta: np.ndarray, angles: np.ndarray, pressures: np.ndarray) -> np.ndarray:
    return np.array([tabulated_pressure(float(t), angles, pressures) for t in theta])


def pinned_table(
    loads: PinnedLoads, omega: float, cylinder_pressure: np.ndarray | None = None
) -> pd.DataFrame:
    """Report table of a pinned run, with the columns of a flexible one.

    Parameters
    ----------
    loads : PinnedLoads
        Pinned results at crank angles from TDC over one revolution [rad].
    omega : float
        Crank speed [rad/s] (constant).
    cylinder_pressure : numpy.ndarray, optional
        Cylinder pressure at the samples [Pa], added as ``cylinder_pressure [Pa]``.

    Returns
    -------
    pandas.DataFrame
        ``crank_angle [deg]``, ``time [s]``, ``bearing_force_<name>_x|_y|_z [N]``,
        ``bearing_force_<name> [N]``, ``bearing_displacement_<name>_x|_y|_z [m]``
        (zero: rigid bearings), ``drive_torque [N m]``, ``crank_speed [rad/s]``,
        ``piston_displacement [m]``, ``piston_lateral [m]``, ``piston_tilt [rad]``.
    """
    theta = loads.crank_angle
    n = theta.size
    cols: dict[str, np.ndarray] = {
        "crank_angle [deg]": np.degrees(theta),
        "time [s]": (theta - theta[0]) / omega,
    }
    for i, name in enumerate(BEARING_NAMES):
        for k, ax in enumerate("xyz"):
            cols[f"bearing_force_{name}_{ax} [N]"] = loads.bearing_force[:, i, k]
        cols[f"bearing_force_{name} [N]"] = np.linalg.norm(loads.bearing_force[:, i], axis=1)
        for ax in "xyz":
            cols[f"bearing_displacement_{name}_{ax} [m]"] = np.zeros(n)
    cols["drive_torque [N m]"] = loads.drive_torque
    cols["crank_speed [rad/s]"] = np.full(n, omega)
    cols["piston_displacement [m]"] = loads.piston_displacement
    cols["piston_lateral [m]"] = np.zeros(n)
    cols["piston_tilt [rad]"] = np.zeros(n)
    if cylinder_pressure is not None:
        cols[PRESSURE_COLUMN] = np.asarray(cylinder_pressure, dtype=float)
    return pd.DataFrame(cols)


def flexible_table(
    result: MechanismResult, cylinder_pressure: np.ndarray | None = None
) -> pd.DataFrame:
    """Report table of a flexible run (:meth:`MechanismResult.columns` as a DataFrame).

    Parameters
    ----------
    result : MechanismResult
    cylinder_pressure : numpy.ndarray, optional
        Cylinder pressure at the samples [Pa], added as ``cylinder_pressure [Pa]``.

    Returns
    -------
    pandas.DataFrame
    """
    cols = result.columns()
    if cylinder_pressure is not None:
        cols[PRESSURE_COLUMN] = np.asarray(cylinder_pressure, dtype=float)
    return pd.DataFrame(cols)


def table1_columns(hydrodynamic: bool = False) -> list[str]:
    """Column names of ``table1.csv``, in order (``bearing`` first).

    Parameters
    ----------
    hydrodynamic : bool
        With the hydrodynamic column's entries (after the flexible ones of each kind).
    """
    runs = [*RUNS, *(HYDRODYNAMIC_RUNS if hydrodynamic else ())]
    compared = [f"{c}_flexible" for c in CONFIGURATIONS]
    if hydrodynamic:
        compared += list(HYDRODYNAMIC_RUNS)
    rms = [f"{run}_rms [N]" for run in runs]
    rel = [f"{run}_vs_pinned [-]" for run in compared]
    peak = [f"{run}_peak [N]" for run in runs]
    orbit = [f"{run}_orbit_max [m]" for run in compared]
    film = [f"{run}_min_film [m]" for run in HYDRODYNAMIC_RUNS] if hydrodynamic else []
    return ["bearing", *rms, *rel, *peak, *orbit, *film]


def _table1(
    pinned: dict[str, PinnedLoads],
    flexible: dict[str, MechanismResult],
    hydrodynamic: dict[str, HydrodynamicRun],
) -> pd.DataFrame:
    rms: dict[str, np.ndarray] = {k: v.force_rms() for k, v in pinned.items()}
    peak: dict[str, np.ndarray] = {k: v.force_peak() for k, v in pinned.items()}
    orbit: dict[str, np.ndarray] = {}
    for k, v in flexible.items():
        rms[k], peak[k], orbit[k] = v.force_rms, v.force_peak, v.orbit_radius_max
    cols: dict[str, Any] = {"bearing": list(BEARING_NAMES)}
    for config, h in hydrodynamic.items():
        run = f"{config}_hydrodynamic"
        rms[run], peak[run], orbit[run] = h.force_rms, h.force_peak, h.orbit_radius_max
        cols[f"{run}_min_film [m]"] = h.min_film_thickness
    for run in [*RUNS, *(f"{c}_hydrodynamic" for c in hydrodynamic)]:
        config, model = run.rsplit("_", 1)
        cols[f"{run}_rms [N]"] = rms[run]
        cols[f"{run}_peak [N]"] = peak[run]
        if model != "pinned":
            cols[f"{run}_vs_pinned [-]"] = rms[run] / rms[PINNED_OF[config]] - 1.0
            cols[f"{run}_orbit_max [m]"] = orbit[run]
    table = pd.DataFrame(cols)
    return table[table1_columns(bool(hydrodynamic))]


# ------------------------------------------------------------------------------- study


def run_paper_study(
    spec: MechanismSpec,
    geometry: CrankGeometry,
    curve: PressureCurve,
    shell_pressure: float,
    omega: float,
    out_dir: str | Path | None,
    *,
    drive: str = "torque_profile",
    rtol: float = 1e-6,
    method: str = "LSODA",
    undamped_revolutions: int = 8,
    samples_per_revolution: int = 360,
    plots: bool = True,
    undamped_start: str = "periodic",
    periodic_tolerance: float = 1e-3,
    max_revolutions: int = 30,
    hydrodynamic: Case | None = None,
    bearing_law: str = DEFAULT_LAW,
) -> PaperStudy:
    """Run the paper's pinned-against-flexible study and write its report.

    Parameters
    ----------
    spec : MechanismSpec
        Mechanism with the bearings' stiffness and damping; the undamped runs use it
        with zero damping, the ``gas_damped`` run as given.
    geometry : CrankGeometry
    curve : PressureCurve
        Cylinder pressure against crank angle from TDC [rad], [Pa] (the ``gas`` load).
    shell_pressure : float
        Pressure under the piston [Pa]; also the cylinder pressure of the ``inertia``
        configuration (no net gas force).
    omega : float
        Crank speed [rad/s]: constant for the pinned runs; prescribed, or initial and
        nominal for ``drive="torque_profile"``.
    out_dir : str or pathlib.Path or None
        Report directory, replaced atomically if it exists; None writes nothing.
    drive : {"torque_profile", "constant_speed"}
        Drive of the flexible runs; ``torque_profile`` applies the pinned driving torque
        of the same load (the paper's procedure).
    rtol : float
        Relative tolerance of the flexible runs [-].
    method : str
        ``solve_ivp`` method.
    undamped_revolutions : int
        Revolutions of the undamped transients (``undamped_start`` other than
        ``"periodic"``); the last one is reported.
    samples_per_revolution : int
        Samples of every reported revolution (equal crank-angle steps from TDC).
    plots : bool
        Write the figures.
    undamped_start : {"periodic", "quasi_static", "unloaded"}
        The undamped runs: their periodic response at constant speed, by shooting
        (``periodic``); or a transient of ``undamped_revolutions`` from TDC with the
        bearings deflected by the pinned loads (``quasi_static``, the default of
        :func:`recipsim.solve.mechanism_ivp.simulate_mechanism`) or undeflected
        (``unloaded``), which starts a much larger free vibration.
    periodic_tolerance : float
        Periodicity tolerance of the damped and the shooting runs [-].
    max_revolutions : int
        Revolution limit of the damped run; of a shooting run, twice this (its
        Jacobian costs one revolution per state).
    hydrodynamic : Case, optional
        Adds the hydrodynamic column: the case whose journals' film data and oil the
        ``inertia`` and ``gas`` loads run on (its shell pressure and speed are used;
        :func:`recipsim.studies.paper_hydrodynamic.run_hydrodynamic`); its mechanism
        should be ``spec``, whose pinned runs it is compared with.
    bearing_law : {"finite_journal", "short_journal"}
        Film law of the hydrodynamic journals.

    Returns
    -------
    PaperStudy

    Raises
    ------
    ValueError
        For an unknown ``drive`` or ``undamped_start``, or fewer than 1 revolution or
        4 samples.
    RuntimeError
        If an integration fails.
    CaseError
        If the ``hydrodynamic`` case's journals lack film data.
    """
    _check_settings(drive, undamped_start, undamped_revolutions, samples_per_revolution)
    start = time.perf_counter()
    angles = np.ascontiguousarray(curve.crank_angle, dtype=float)
    loads = {
        "inertia": np.full(angles.shape, float(shell_pressure)),
        "gas": np.ascontiguousarray(curve.pressure, dtype=float),
    }
    options: dict[str, Any] = {
        "drive": drive,
        "rtol": rtol,
        "method": method,
        "undamped_revolutions": undamped_revolutions,
        "undamped_start": undamped_start,
        "samples_per_revolution": samples_per_revolution,
        "periodic_tolerance": periodic_tolerance,
        "max_revolutions": max_revolutions,
    }
    cycles: dict[str, pd.DataFrame] = {}
    runs: dict[str, RunRecord] = {}
    pinned = _pinned_runs(spec, geometry, angles, loads, shell_pressure, omega, options)
    for name, (table, _, record) in pinned.items():
        cycles[name], runs[name] = table, record
    flexible = _flexible_runs(spec, geometry, angles, loads, shell_pressure, omega, options)
    for name, (result_f, record) in flexible.items():
        gas = _pressures(result_f.crank_angle, angles, loads[_load_of(record.configuration)])
        cycles[name], runs[name] = flexible_table(result_f, gas), record
    films: dict[str, HydrodynamicRun] = {}
    settings = _settings(spec, geometry, curve, shell_pressure, omega, **options)
    if hydrodynamic is not None:
        inertia_curve = constant_curve(shell_pressure)
        films = run_hydrodynamic(
            hydrodynamic,
            {"inertia": inertia_curve, "gas": curve},
            law=bearing_law,
            samples_per_revolution=samples_per_revolution,
        )
        for config, h in films.items():
            name = f"{config}_hydrodynamic"
            cycles[name] = h.cycle
            runs[name] = RunRecord(
                name, config, "hydrodynamic", "case", h.revolutions, h.converged, h.residual,
                h.nfev, h.wall_time,
            )  # fmt: skip
        settings["hydrodynamic"] = _hydrodynamic_settings(hydrodynamic, bearing_law)
    order = [*RUNS, *(HYDRODYNAMIC_RUNS if films else ())]
    timings = {name: runs[name].wall_time for name in order}
    loads_p = {k: v[1] for k, v in pinned.items()}
    study = PaperStudy(
        table1=_table1(loads_p, {k: v[0] for k, v in flexible.items()}, films),
        cycles={k: cycles[k] for k in order},
        runs={k: runs[k] for k in order},
        timings=timings,
        settings=settings,
        flexible={k: v[0] for k, v in flexible.items()},
        pinned=loads_p,
        hydrodynamic=films,
    )
    files: tuple[Path, ...] = ()
    if out_dir is not None:
        t0 = time.perf_counter()
        timings["compute"] = t0 - start
        files = tuple(write_paper_study(study, out_dir, plots=plots))
        timings["write"] = time.perf_counter() - t0
    timings["total"] = time.perf_counter() - start
    return replace(study, out_dir=None if out_dir is None else Path(out_dir), files=files)


def _check_settings(drive: str, undamped_start: str, revolutions: int, samples: int) -> None:
    if drive not in ("torque_profile", "constant_speed"):
        raise ValueError(f"drive {drive!r}; allowed: 'torque_profile', 'constant_speed'")
    if undamped_start not in UNDAMPED_STARTS:
        raise ValueError(f"undamped_start {undamped_start!r}; allowed: {UNDAMPED_STARTS}")
    if revolutions < 1:
        raise ValueError(f"undamped_revolutions {revolutions}; allowed: >= 1")
    if samples < 4:
        raise ValueError(f"samples_per_revolution {samples}; allowed: >= 4")


def _load_of(config: str) -> str:
    return "inertia" if config == "inertia" else "gas"


def _pinned_runs(
    spec: MechanismSpec,
    geometry: CrankGeometry,
    angles: np.ndarray,
    loads: dict[str, np.ndarray],
    shell_pressure: float,
    omega: float,
    options: dict[str, Any],
) -> dict[str, tuple[pd.DataFrame, PinnedLoads, RunRecord]]:
    """The pinned runs at constant speed (inverse dynamics): table, loads, record."""
    n = options["samples_per_revolution"]
    theta = 2.0 * math.pi * np.arange(n) / n
    out = {}
    for load, pressures in loads.items():
        name = f"{load}_pinned"
        t0 = time.perf_counter()
        result = pinned_loads(
            spec,
            geometry,
            theta,
            omega,
            pressure_angles=angles,
            pressures=pressures,
            shell_pressure=shell_pressure,
        )
        table = pinned_table(result, omega, _pressures(theta, angles, pressures))
        wall = time.perf_counter() - t0
        out[name] = (
            table,
            result,
            RunRecord(name, load, "pinned", "algebraic", 0, True, None, 0, wall),
        )
    return out


def _flexible_runs(
    spec: MechanismSpec,
    geometry: CrankGeometry,
    angles: np.ndarray,
    loads: dict[str, np.ndarray],
    shell_pressure: float,
    omega: float,
    options: dict[str, Any],
) -> dict[str, tuple[MechanismResult, RunRecord]]:
    """The three flexible runs on linear bearings (``solve_ivp`` driver), in order."""
    undamped = with_damping(spec, 0.0)
    out: dict[str, tuple[MechanismResult, RunRecord]] = {}
    jacobian: tuple[np.ndarray, np.ndarray] | None = None
    for config in CONFIGURATIONS:
        name = f"{config}_flexible"
        pressures = loads[_load_of(config)]
        damped = config == "gas_damped"
        t0 = time.perf_counter()
        converged: bool | None
        if not damped and options["undamped_start"] == "periodic":
            result, jacobian = undamped_periodic(
                undamped,
                geometry,
                angles,
                pressures,
                shell_pressure,
                omega,
                rtol=_PERIODIC_RTOL_FACTOR * options["rtol"],
                method=options["method"],
                samples_per_revolution=options["samples_per_revolution"],
                periodic_tolerance=options["periodic_tolerance"],
                max_revolutions=2 * options["max_revolutions"],
                jacobian=jacobian,
            )
            mode, converged = "shooting", result.converged
        else:
            extra: dict[str, Any] = {}
            if not damped and options["undamped_start"] == "unloaded":
                par = mechanism_parameters(undamped, geometry, shell_pressure=shell_pressure)
                extra["y0"] = initial_state(par, 0.0, omega, static_deflection=False)
            result = simulate_mechanism(
                spec if damped else undamped,
                geometry,
                angles,
                pressures,
                shell_pressure,
                omega,
                drive=options["drive"],
                revolutions=None if damped else options["undamped_revolutions"],
                rtol=options["rtol"],
                method=options["method"],
                samples_per_revolution=options["samples_per_revolution"],
                periodic_tolerance=options["periodic_tolerance"],
                max_revolutions=options["max_revolutions"],
                **extra,
            )
            mode = "until_periodic" if damped else "fixed_revolutions"
            converged = result.converged if damped else None
        wall = time.perf_counter() - t0
        record = RunRecord(
            name, config, "flexible", mode, result.revolutions, converged,
            result.cycle_change, result.nfev, wall,
        )  # fmt: skip
        out[name] = (result, record)
    return out


def _hydrodynamic_settings(case: Case, law: str) -> dict[str, Any]:
    journals = {}
    for name in JOURNALS:
        film = case.mechanism.bearing(name).film
        journals[name] = (
            None
            if film is None
            else {
                "diameter [m]": film.diameter,
                "length [m]": film.length,
                "radial_clearance [m]": film.radial_clearance,
                "film_temperature [K]": film.film_temperature,
                "viscosity [Pa s]": film.viscosity,
            }
        )
    return {
        "case": case.name,
        "law": law,
        "journals": journals,
        "drive": "constant_speed",
        "solver": SOLVER_METHOD,
        "description": (
            f"the case `{case.name}` with primary, secondary and eccentric on `{law}` films, "
            "at constant speed (the pinned torque profile supplies no friction), solved "
            f"like a case (`{SOLVER_METHOD}`, cycle tolerance {case.solver.cycle_tolerance:g})"
        ),
    }


def _settings(
    spec: MechanismSpec,
    geometry: CrankGeometry,
    curve: PressureCurve,
    shell_pressure: float,
    omega: float,
    **options: Any,
) -> dict[str, Any]:
    return {
        "recipsim": __version__,
        "shell_pressure [Pa]": float(shell_pressure),
        "crank_speed [rad/s]": float(omega),
        "crank_speed [rpm]": float(omega) * 60.0 / (2.0 * math.pi),
        "geometry": {
            "bore [m]": geometry.bore,
            "crank_radius [m]": geometry.crank_radius,
            "rod_length [m]": geometry.rod_length,
        },
        "pressure_curve": {
            "points": int(curve.crank_angle.size),
            "min [Pa]": float(np.min(curve.pressure)),
            "max [Pa]": float(np.max(curve.pressure)),
        },
        "bearings": {
            name: {"law": b.law, "stiffness [N/m]": b.stiffness, "damping [N s/m]": b.damping}
            for name, b in zip(BEARING_NAMES, spec.bearings, strict=True)
        },
        "undamped_runs": (
            "periodic response at constant speed, by shooting (Newton on the one-revolution map)"
            if options["undamped_start"] == "periodic"
            else f"transient from the {options['undamped_start'].replace('_', '-')} pose at "
            f"TDC, {options['undamped_revolutions']} revolutions, the last one reported, as "
            "in a time-marching run of the paper (no dissipation: never periodic)"
        ),
        "damped_run": "from the quasi-static pose until periodic",
        **options,
    }


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
    from recipsim.studies.paper_report import readme, study_summary

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
    from recipsim.studies.paper_report import write_figures

    return write_figures(study, directory)
