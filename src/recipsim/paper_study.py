"""The paper's bearing-load study: pinned against flexible crank train (Kurka et al. 2010).

Section 4 and Table 1 of the paper compare the bearing loads of the rigid ("pinned")
crank train with those of the crank train on visco-elastic bearings ("flexible") for
three loads. This module runs the same study for any mechanism and pressure curve:

==============  ================================  =====================================
configuration   cylinder pressure                 flexible run
==============  ================================  =====================================
``inertia``     shell pressure at every angle     no damping, fixed revolutions
``gas``         the pressure curve                no damping, fixed revolutions
``gas_damped``  the pressure curve                the spec's damping, run to periodic
==============  ================================  =====================================

The pinned mechanism is solved algebraically at constant speed (the ``gas_damped``
configuration reuses the ``gas`` pinned run). Undamped flexible runs never settle to a
periodic state (nothing dissipates the free vibration), so they are a transient from
the quasi-static pose, as in a time-marching run of the paper: ``undamped_revolutions``
revolutions from the quasi-static pinned pose at TDC (or, with
``undamped_start="unloaded"``, from the pinned pose with undeflected bearings), the last
one reported. With the default ``drive="torque_profile"`` the crank is driven by the
pinned driving torque of the same load (the paper's procedure) and its speed is free.

:func:`run_paper_study` returns a :class:`PaperStudy` and writes into ``out_dir``
atomically (built in a temporary directory beside it, then swapped in):

- ``table1.csv``: one row per bearing (``bearing``, ``BEARING_NAMES`` order), RMS loads
  ``<config>_<model>_rms [N]``, relative differences ``<config>_flexible_vs_pinned [-]``
  (flexible RMS / pinned RMS - 1), peak loads ``<config>_<model>_peak [N]`` and largest
  orbit radii ``<config>_flexible_orbit_max [m]``;
- ``cycle_<config>_<model>.csv``: the reported revolution of every run (report columns
  of :meth:`recipsim.mechanics.MechanismResult.columns` plus ``cylinder_pressure [Pa]``;
  pinned tables have zero displacements);
- ``bearing_loads_<config>.png``, ``orbits.png``, ``drive_torque.png``;
- ``study.json`` (settings, and per run its revolutions, convergence and wall time) and
  ``README.md`` (the same, readable).
"""

from __future__ import annotations

import json
import math
import shutil
import tempfile
import time
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from . import __version__
from .atomic import swap_in
from .mechanics import (
    BEARING_NAMES,
    CrankGeometry,
    MechanismResult,
    MechanismSpec,
    PinnedLoads,
    PressureCurve,
    initial_state,
    mechanism_parameters,
    pinned_loads,
    simulate_mechanism,
    tabulated_pressure,
    with_damping,
)

#: Load configurations, in the paper's order.
CONFIGURATIONS = ("inertia", "gas", "gas_damped")
#: Starting poses of the undamped runs.
UNDAMPED_STARTS = ("quasi_static", "unloaded")
#: Runs, as ``<config>_<model>`` (``gas_damped`` reuses the ``gas`` pinned run).
RUNS = ("inertia_pinned", "inertia_flexible", "gas_pinned", "gas_flexible", "gas_damped_flexible")
_PINNED_OF = {"inertia": "inertia_pinned", "gas": "gas_pinned", "gas_damped": "gas_pinned"}
_LABELS = {
    "inertia": "inertia load only",
    "gas": "gas (compressive) load",
    "gas_damped": "gas load with dissipation",
}
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
        ``"pinned"`` or ``"flexible"``.
    mode : str
        ``"algebraic"`` (pinned), ``"fixed_revolutions"`` (undamped flexible) or
        ``"until_periodic"`` (damped flexible).
    revolutions : int
        Revolutions integrated (0 for pinned).
    converged : bool or None
        Periodicity test passed (damped runs); True for pinned (exactly periodic);
        None for fixed-revolution runs (not tested).
    cycle_change : float or None
        Largest state change over the last revolution relative to its scale [-]
        (flexible runs).
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
    flexible : dict of str to MechanismResult
        The flexible runs (``inertia_flexible``, ``gas_flexible``, ``gas_damped_flexible``).
    pinned : dict of str to PinnedLoads
        The pinned runs (``inertia_pinned``, ``gas_pinned``).
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
    flexible: dict[str, MechanismResult] = field(repr=False)
    pinned: dict[str, PinnedLoads] = field(repr=False)
    out_dir: Path | None = None
    files: tuple[Path, ...] = ()


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


def table1_columns() -> list[str]:
    """Column names of ``table1.csv``, in order (``bearing`` first)."""
    rms = [
        "inertia_pinned_rms [N]",
        "inertia_flexible_rms [N]",
        "gas_pinned_rms [N]",
        "gas_flexible_rms [N]",
        "gas_damped_flexible_rms [N]",
    ]
    rel = [f"{c}_flexible_vs_pinned [-]" for c in CONFIGURATIONS]
    peak = [c.replace("_rms [N]", "_peak [N]") for c in rms]
    orbit = [f"{c}_flexible_orbit_max [m]" for c in CONFIGURATIONS]
    return ["bearing", *rms, *rel, *peak, *orbit]


def _table1(pinned: dict[str, PinnedLoads], flexible: dict[str, MechanismResult]) -> pd.DataFrame:
    rms: dict[str, np.ndarray] = {k: v.force_rms() for k, v in pinned.items()}
    peak: dict[str, np.ndarray] = {k: v.force_peak() for k, v in pinned.items()}
    rms.update({k: v.force_rms for k, v in flexible.items()})
    peak.update({k: v.force_peak for k, v in flexible.items()})
    cols: dict[str, Any] = {"bearing": list(BEARING_NAMES)}
    for run in RUNS:
        cols[f"{run}_rms [N]"] = rms[run]
    for config in CONFIGURATIONS:
        ref = rms[_PINNED_OF[config]]
        cols[f"{config}_flexible_vs_pinned [-]"] = rms[f"{config}_flexible"] / ref - 1.0
    for run in RUNS:
        cols[f"{run}_peak [N]"] = peak[run]
    for config in CONFIGURATIONS:
        cols[f"{config}_flexible_orbit_max [m]"] = flexible[f"{config}_flexible"].orbit_radius_max
    table = pd.DataFrame(cols)
    return table[table1_columns()]


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
    undamped_start: str = "quasi_static",
    periodic_tolerance: float = 1e-3,
    max_revolutions: int = 30,
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
        Revolutions of the undamped runs (a transient from the quasi-static pose, as in
        a time-marching run of the paper); the last one is reported.
    samples_per_revolution : int
        Samples of every reported revolution (equal crank-angle steps from TDC).
    plots : bool
        Write the figures.
    undamped_start : {"quasi_static", "unloaded"}
        Initial state of the undamped runs at TDC: bearings deflected by the pinned
        loads (``quasi_static``, the default of
        :func:`recipsim.mechanics.simulate_mechanism`), or undeflected (``unloaded``),
        which starts a much larger free vibration.
    periodic_tolerance : float
        Periodicity tolerance of the damped run [-].
    max_revolutions : int
        Revolution limit of the damped run.

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
    """
    if drive not in ("torque_profile", "constant_speed"):
        raise ValueError(f"drive {drive!r}; allowed: 'torque_profile', 'constant_speed'")
    if undamped_start not in UNDAMPED_STARTS:
        raise ValueError(f"undamped_start {undamped_start!r}; allowed: {UNDAMPED_STARTS}")
    if undamped_revolutions < 1:
        raise ValueError(f"undamped_revolutions {undamped_revolutions}; allowed: >= 1")
    if samples_per_revolution < 4:
        raise ValueError(f"samples_per_revolution {samples_per_revolution}; allowed: >= 4")
    start = time.perf_counter()
    angles = np.ascontiguousarray(curve.crank_angle, dtype=float)
    loads = {
        "inertia": np.full(angles.shape, float(shell_pressure)),
        "gas": np.ascontiguousarray(curve.pressure, dtype=float),
    }
    theta = 2.0 * math.pi * np.arange(samples_per_revolution) / samples_per_revolution
    undamped = with_damping(spec, 0.0)

    pinned: dict[str, PinnedLoads] = {}
    flexible: dict[str, MechanismResult] = {}
    cycles: dict[str, pd.DataFrame] = {}
    runs: dict[str, RunRecord] = {}
    timings: dict[str, float] = {}

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
        pinned[name] = result
        cycles[name] = pinned_table(result, omega, _pressures(theta, angles, pressures))
        timings[name] = time.perf_counter() - t0
        runs[name] = RunRecord(name, load, "pinned", "algebraic", 0, True, None, 0, timings[name])

    for config in CONFIGURATIONS:
        name = f"{config}_flexible"
        pressures = loads["inertia" if config == "inertia" else "gas"]
        damped = config == "gas_damped"
        options: dict[str, Any] = {}
        if not damped and undamped_start == "unloaded":
            par = mechanism_parameters(undamped, geometry, shell_pressure=shell_pressure)
            options["y0"] = initial_state(par, 0.0, omega, static_deflection=False)
        t0 = time.perf_counter()
        result_f = simulate_mechanism(
            spec if damped else undamped,
            geometry,
            angles,
            pressures,
            shell_pressure,
            omega,
            drive=drive,
            revolutions=None if damped else undamped_revolutions,
            rtol=rtol,
            method=method,
            samples_per_revolution=samples_per_revolution,
            periodic_tolerance=periodic_tolerance,
            max_revolutions=max_revolutions,
            **options,
        )
        flexible[name] = result_f
        gas = _pressures(result_f.crank_angle, angles, pressures)
        cycles[name] = flexible_table(result_f, gas)
        timings[name] = time.perf_counter() - t0
        runs[name] = RunRecord(
            name,
            config,
            "flexible",
            "until_periodic" if damped else "fixed_revolutions",
            result_f.revolutions,
            result_f.converged if damped else None,
            result_f.cycle_change,
            result_f.nfev,
            timings[name],
        )

    cycles = {k: cycles[k] for k in RUNS}
    settings = _settings(
        spec,
        geometry,
        curve,
        shell_pressure,
        omega,
        drive=drive,
        rtol=rtol,
        method=method,
        undamped_revolutions=undamped_revolutions,
        undamped_start=undamped_start,
        samples_per_revolution=samples_per_revolution,
        periodic_tolerance=periodic_tolerance,
        max_revolutions=max_revolutions,
    )
    study = PaperStudy(
        table1=_table1(pinned, flexible),
        cycles=cycles,
        runs={k: runs[k] for k in RUNS},
        timings=timings,
        settings=settings,
        flexible=flexible,
        pinned=pinned,
    )
    files: tuple[Path, ...] = ()
    if out_dir is not None:
        t0 = time.perf_counter()
        timings["compute"] = t0 - start
        files = tuple(write_paper_study(study, out_dir, plots=plots))
        timings["write"] = time.perf_counter() - t0
    timings["total"] = time.perf_counter() - start
    return replace(study, out_dir=None if out_dir is None else Path(out_dir), files=files)


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
            f"transient from the {options['undamped_start'].replace('_', '-')} pose at TDC, "
            f"{options['undamped_revolutions']} revolutions, the last one reported, as in a "
            "time-marching run of the paper (no dissipation: never periodic)"
        ),
        "damped_run": "from the quasi-static pose until periodic",
        **options,
    }


# ------------------------------------------------------------------------------ output


def write_paper_study(study: PaperStudy, out_dir: str | Path, *, plots: bool = True) -> list[Path]:
    """Write a study's files into ``out_dir`` atomically.

    Everything is built in a temporary directory beside ``out_dir`` and swapped in
    with renames (:func:`recipsim.atomic.swap_in`); a previous ``out_dir`` is
    replaced entirely, and left untouched if writing fails.

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
    out_dir.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{out_dir.name}.", dir=out_dir.parent))
    try:
        names = ["table1.csv"]
        study.table1.to_csv(tmp / "table1.csv", index=False)
        for run, table in study.cycles.items():
            names.append(f"cycle_{run}.csv")
            table.to_csv(tmp / names[-1], index=False)
        if plots:
            names.extend(p.name for p in _write_figures(study, tmp))
        names.extend(["study.json", "README.md"])
        (tmp / "study.json").write_text(json.dumps(_summary(study, names), indent=2) + "\n")
        (tmp / "README.md").write_text(_readme(study, names))
        swap_in(tmp, out_dir)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    return [out_dir / n for n in names]


def _write_figures(study: PaperStudy, directory: Path) -> list[Path]:
    from .mechanics_plots import plot_bearing_loads, plot_drive_torque, plot_orbits, save_figure

    c = study.cycles
    written = []
    for config in CONFIGURATIONS:
        tables = {"pinned": c[_PINNED_OF[config]], "flexible": c[f"{config}_flexible"]}
        fig = plot_bearing_loads(tables, title=f"bearing loads: {_LABELS[config]}")
        written.append(save_figure(fig, directory / f"bearing_loads_{config}.png"))
    orbit_tables = {_LABELS[k]: c[f"{k}_flexible"] for k in CONFIGURATIONS}
    fig = plot_orbits(orbit_tables, title="orbits of the primary and secondary bearings")
    written.append(save_figure(fig, directory / "orbits.png"))
    torque_tables = {
        "pinned, inertia": c["inertia_pinned"],
        "pinned, gas": c["gas_pinned"],
        "flexible, inertia": c["inertia_flexible"],
        "flexible, gas": c["gas_flexible"],
        "flexible, gas + damping": c["gas_damped_flexible"],
    }
    written.append(save_figure(plot_drive_torque(torque_tables), directory / "drive_torque.png"))
    return written


def _json_value(value: Any) -> Any:
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _summary(study: PaperStudy, files: list[str]) -> dict[str, Any]:
    runs = [
        {k: _json_value(v) for k, v in record.__dict__.items()} for record in study.runs.values()
    ]
    table = {
        row["bearing"]: {k: float(v) for k, v in row.items() if k != "bearing"}
        for row in study.table1.to_dict(orient="records")
    }
    return {
        "settings": study.settings,
        "runs": runs,
        "timings [s]": study.timings,
        "table1": table,
        "files": files,
    }


def _readme(study: PaperStudy, files: list[str]) -> str:
    s = study.settings
    lines = [
        "# Bearing loads: pinned against flexible crank train",
        "",
        "The study of Kurka, Paulino & Izuka (ISMA 2010), section 4 and Table 1, run by",
        f"`recipsim.paper_study.run_paper_study` (recipsim {s['recipsim']}).",
        "",
        f"- speed {s['crank_speed [rpm]']:.1f} rpm,"
        f" shell pressure {s['shell_pressure [Pa]']:.4g} Pa,"
        f" drive `{s['drive']}`, `{s['method']}` at rtol {s['rtol']:g},"
        f" {s['samples_per_revolution']} samples per revolution;",
        f"- undamped runs: {s['undamped_runs']};",
        f"- damped run: {s['damped_run']} (tolerance {s['periodic_tolerance']:g}).",
        "",
        "| run | mode | revolutions | converged | wall time [s] |",
        "| --- | --- | --- | --- | --- |",
    ]
    for r in study.runs.values():
        converged = "n/a (not tested)" if r.converged is None else ("yes" if r.converged else "NO")
        lines.append(f"| {r.name} | {r.mode} | {r.revolutions} | {converged} | {r.wall_time:.2f} |")
    lines += [
        "",
        "RMS bearing loads [N] (flexible against pinned in brackets):",
        "",
        "| bearing | inertia pinned | inertia flexible | gas pinned | gas flexible "
        "| gas damped flexible |",
        "| --- | --- | --- | --- | --- | --- |",
    ]
    t = study.table1
    for _, row in t.iterrows():
        cells = [str(row["bearing"])]
        for run in RUNS:
            cell = f"{row[f'{run}_rms [N]']:.1f}"
            config = run.rsplit("_", 1)[0]
            if run.endswith("_flexible"):
                cell += f" ({100.0 * row[f'{config}_flexible_vs_pinned [-]']:+.1f} %)"
            cells.append(cell)
        lines.append("| " + " | ".join(cells) + " |")
    lines += ["", "Files: " + ", ".join(f"`{f}`" for f in files) + ".", ""]
    return "\n".join(lines)
