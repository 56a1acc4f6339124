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

:func:`run_paper_study` returns a :class:`PaperStudy` and writes into ``out_dir``
atomically (built in a temporary directory beside it, then swapped in):

- ``table1.csv``: one row per bearing (``bearing``, ``BEARING_NAMES`` order), RMS loads
  ``<config>_<model>_rms [N]``, relative differences ``<config>_flexible_vs_pinned [-]``
  (flexible RMS / pinned RMS - 1), peak loads ``<config>_<model>_peak [N]`` and largest
  orbit radii ``<config>_flexible_orbit_max [m]``;
- ``cycle_<config>_<model>.csv``: the reported revolution of every run (report columns
  of :meth:`recipsim.physics.mechanics.MechanismResult.columns` plus ``cylinder_pressure [Pa]``;
  pinned tables have zero displacements);
- ``bearing_loads_<config>.png``, ``orbits.png``, ``drive_torque.png``;
- ``study.json`` (settings, and per run its revolutions, convergence and wall time) and
  ``README.md`` (the same, readable).
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
from scipy.integrate import solve_ivp

from recipsim import __version__
from recipsim.atomic import atomic_directory
from recipsim.case.mechanism import CrankGeometry, MechanismSpec, with_damping
from recipsim.model.mechanism_parameters import mechanism_parameters
from recipsim.model.pinned import pinned_loads
from recipsim.physics.mechanics import layout as lay
from recipsim.physics.mechanics.flexible import flexible_rhs_tabulated
from recipsim.physics.mechanics.flexible_setup import initial_state, state_scales
from recipsim.physics.mechanics.layout import BEARING_NAMES
from recipsim.physics.mechanics.pinned import PinnedLoads
from recipsim.physics.mechanics.tabulated import PressureCurve, tabulated_pressure
from recipsim.solve.mechanism_ivp import MechanismResult, simulate_mechanism
from recipsim.solve.shooting import newton_fixed_point

#: Load configurations, in the paper's order.
CONFIGURATIONS = ("inertia", "gas", "gas_damped")
#: How the undamped runs are made: their periodic response (shooting), or a transient
#: of fixed revolutions from the quasi-static or the unloaded pose.
UNDAMPED_STARTS = ("periodic", "quasi_static", "unloaded")
#: Finite-difference step of the undamped shooting, relative to each state's size.
_FD_STEP = 0.2
#: The undamped shooting integrates at this times the study's ``rtol``: an undamped
#: revolution's end state jumps with the step sequence by ~1e-3 of the vibration
#: amplitude at rtol 1e-6 under LSODA (the periodicity tolerance), ~1e-4 at 1e-7.
_PERIODIC_RTOL_FACTOR = 0.1
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
        ``"algebraic"`` (pinned), ``"shooting"`` (undamped flexible, periodic
        response), ``"fixed_revolutions"`` (undamped flexible transient) or
        ``"until_periodic"`` (damped flexible).
    revolutions : int
        Revolutions integrated (0 for pinned; with shooting every revolution, the
        Jacobian's included).
    converged : bool or None
        Periodicity test passed (damped and shooting runs); True for pinned (exactly
        periodic); None for fixed-revolution runs (not tested).
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


# -------------------------------------------------------------------- undamped periodic


def undamped_periodic_response(
    spec: MechanismSpec,
    geometry: CrankGeometry,
    pressure_angles: np.ndarray,
    pressures: np.ndarray,
    shell_pressure: float,
    omega: float,
    *,
    rtol: float = 1e-6,
    method: str = "LSODA",
    samples_per_revolution: int = 360,
    periodic_tolerance: float = 1e-3,
    max_revolutions: int = 60,
) -> MechanismResult:
    """Periodic response of the flexible mechanism at constant speed, by shooting.

    See :func:`_undamped_periodic` (which also returns the Jacobian, for reuse).
    """
    return _undamped_periodic(
        spec,
        geometry,
        pressure_angles,
        pressures,
        shell_pressure,
        omega,
        rtol=rtol,
        method=method,
        samples_per_revolution=samples_per_revolution,
        periodic_tolerance=periodic_tolerance,
        max_revolutions=max_revolutions,
    )[0]


def _undamped_periodic(
    spec: MechanismSpec,
    geometry: CrankGeometry,
    pressure_angles: np.ndarray,
    pressures: np.ndarray,
    shell_pressure: float,
    omega: float,
    *,
    rtol: float,
    method: str,
    samples_per_revolution: int,
    periodic_tolerance: float,
    max_revolutions: int,
    jacobian: tuple[np.ndarray, np.ndarray] | None = None,
) -> tuple[MechanismResult, tuple[np.ndarray, np.ndarray] | None]:
    """Periodic response of the flexible mechanism at constant speed, by shooting.

    Newton (:func:`recipsim.solve.shooting.newton_fixed_point`) on the map from the
    state at TDC to the state one revolution later (``solve_ivp`` with ``method`` at
    ``rtol``, absolute tolerances ``rtol`` times :func:`state_scales`), over every state
    but the crank angle and speed (prescribed), from the quasi-static pose; finite
    differences of a fifth of each state's size over the revolution (the map is nearly
    linear in the deflections). It works whatever the damping, undamped included,
    unless a forcing harmonic sits exactly on a natural frequency. The reported
    revolution is integrated once more from the periodic state by
    :func:`recipsim.physics.mechanics.simulate_mechanism`, whose periodicity test (the largest
    state change over it relative to the state's size, below ``periodic_tolerance``)
    decides ``converged``.

    Parameters
    ----------
    spec : MechanismSpec
        The mechanism (its bearings' damping as given; zero for the paper's study).
    geometry : CrankGeometry
    pressure_angles, pressures : numpy.ndarray
        Periodic cylinder pressure table [rad], [Pa].
    shell_pressure : float
        [Pa].
    omega : float
        Crank speed [rad/s].
    rtol : float
        Relative tolerance of the integration [-].
    method : str
        ``solve_ivp`` method.
    samples_per_revolution : int
        Samples of the reported revolution.
    periodic_tolerance : float
        Periodicity tolerance [-]; Newton aims at half of it.
    max_revolutions : int
        Revolutions the shooting may integrate (a Jacobian costs 20).

    jacobian : (numpy.ndarray, numpy.ndarray), optional
        Scaled Jacobian and its scales from a run of the same mechanism and speed:
        at constant speed the pressure table only adds a forcing, so the map's linear
        part is the same for every load and the Jacobian carries over.

    Returns
    -------
    MechanismResult
        The periodic revolution; ``revolutions`` and ``nfev`` count the shooting's too.
    (numpy.ndarray, numpy.ndarray) or None
        The Jacobian and its scales, for the next load.

    Raises
    ------
    RuntimeError
        If the reported revolution fails to integrate.
    """
    pa = np.ascontiguousarray(pressure_angles, dtype=float)
    pp = np.ascontiguousarray(pressures, dtype=float)
    par = mechanism_parameters(
        spec, geometry, shell_pressure=shell_pressure, speed=omega, drive="constant_speed"
    )
    scales = state_scales(par)
    period = 2.0 * math.pi / omega
    no_drive = np.zeros(1)
    dydt = np.zeros(lay.N_STATE)
    aux = np.zeros(lay.N_AUX)

    def fun(t: float, state: np.ndarray) -> np.ndarray:
        flexible_rhs_tabulated(t, state, dydt, aux, par, pa, pp, no_drive, no_drive, no_drive)
        return dydt.copy()

    y0 = initial_state(par, 0.0, omega, tabulated_pressure(0.0, pa, pp))
    fixed = (lay.Y_CRANK_ANGLE, lay.Y_CRANK_SPEED)
    idx = np.array([i for i in range(lay.N_STATE) if i not in fixed])
    nfev = 0

    def one_revolution(z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        nonlocal nfev
        y = y0.copy()
        y[idx] = z
        sol = solve_ivp(
            fun,
            (0.0, period),
            y,
            method=method,
            rtol=rtol,
            atol=rtol * scales,
            dense_output=True,
            first_step=1e-5 * period,
        )
        if not sol.success:
            raise RuntimeError(f"integration failed: {sol.message}")
        nfev += sol.nfev
        return sol.y[idx, -1].copy(), sol.sol(np.linspace(0.0, period, 64))

    def change(z: np.ndarray, g: np.ndarray, samples: np.ndarray) -> float:
        # simulate_mechanism's periodicity measure
        size = np.maximum(np.abs(samples).max(axis=1), scales)[idx]
        return float(np.max(np.abs(g - z) / size))

    z = y0[idx]
    g, samples = one_revolution(z)
    ref = np.maximum(np.abs(samples).max(axis=1), scales)[idx] if jacobian is None else jacobian[1]
    result = newton_fixed_point(
        one_revolution,
        z,
        (g, samples),
        ref,
        np.full(idx.size, _FD_STEP),
        lambda zz, gg, smp: change(zz, gg, smp) < 0.5 * periodic_tolerance,
        max(max_revolutions - 1, 0),
        jacobian=None if jacobian is None else jacobian[0],
        failures=(RuntimeError,),
    )
    start = y0.copy()
    start[idx] = result.z
    final = simulate_mechanism(
        spec,
        geometry,
        pa,
        pp,
        shell_pressure,
        omega,
        drive="constant_speed",
        revolutions=1,
        rtol=rtol,
        method=method,
        samples_per_revolution=samples_per_revolution,
        y0=start,
    )
    periodic = replace(
        final,
        revolutions=2 + result.evaluations,
        converged=bool(final.cycle_change < periodic_tolerance),
        nfev=final.nfev + nfev,
    )
    return periodic, None if result.jacobian is None else (result.jacobian, ref)


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
        :func:`recipsim.physics.mechanics.simulate_mechanism`) or undeflected (``unloaded``),
        which starts a much larger free vibration.
    periodic_tolerance : float
        Periodicity tolerance of the damped and the shooting runs [-].
    max_revolutions : int
        Revolution limit of the damped run; of a shooting run, twice this (its
        Jacobian costs one revolution per state).

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

    jacobian: tuple[np.ndarray, np.ndarray] | None = None
    for config in CONFIGURATIONS:
        name = f"{config}_flexible"
        pressures = loads["inertia" if config == "inertia" else "gas"]
        damped = config == "gas_damped"
        t0 = time.perf_counter()
        converged: bool | None
        if not damped and undamped_start == "periodic":
            result_f, jacobian = _undamped_periodic(
                undamped,
                geometry,
                angles,
                pressures,
                shell_pressure,
                omega,
                rtol=_PERIODIC_RTOL_FACTOR * rtol,
                method=method,
                samples_per_revolution=samples_per_revolution,
                periodic_tolerance=periodic_tolerance,
                max_revolutions=2 * max_revolutions,
                jacobian=jacobian,
            )
            mode, converged = "shooting", result_f.converged
        else:
            options: dict[str, Any] = {}
            if not damped and undamped_start == "unloaded":
                par = mechanism_parameters(undamped, geometry, shell_pressure=shell_pressure)
                options["y0"] = initial_state(par, 0.0, omega, static_deflection=False)
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
            mode = "until_periodic" if damped else "fixed_revolutions"
            converged = result_f.converged if damped else None
        flexible[name] = result_f
        gas = _pressures(result_f.crank_angle, angles, pressures)
        cycles[name] = flexible_table(result_f, gas)
        timings[name] = time.perf_counter() - t0
        runs[name] = RunRecord(
            name,
            config,
            "flexible",
            mode,
            result_f.revolutions,
            converged,
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
        (tmp / "study.json").write_text(json.dumps(_summary(study, names), indent=2) + "\n")
        (tmp / "README.md").write_text(_readme(study, names))
    return [out_dir / n for n in names]


def _write_figures(study: PaperStudy, directory: Path) -> list[Path]:
    from recipsim.report.mechanics_plots import (
        plot_bearing_loads,
        plot_drive_torque,
        plot_orbits,
        save_figure,
    )

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
        f"`recipsim.studies.paper.run_paper_study` (recipsim {s['recipsim']}).",
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
