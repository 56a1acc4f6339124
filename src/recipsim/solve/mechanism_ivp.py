"""Thin pure-Python driver of the flexible mechanism with ``scipy.integrate.solve_ivp``.

Integrates revolution by revolution from the quasi-static pinned pose until the
state at the start of a revolution repeats (or a fixed number of revolutions), and
returns the last revolution sampled at equal crank-angle steps. The right-hand side
is the compiled :func:`.flexible.flexible_rhs_tabulated`; the project's compiled
integrator can replace ``solve_ivp`` without touching it.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from recipsim.case.mechanism_spec import CrankGeometry, MechanismSpec
from recipsim.model.mechanism_parameters import mechanism_parameters
from recipsim.model.pinned import pinned_torque_profile
from recipsim.physics.mechanics import layout as lay
from recipsim.physics.mechanics.flexible import (
    flexible_output_history,
    flexible_rhs_tabulated,
)
from recipsim.physics.mechanics.flexible_setup import initial_state, state_scales
from recipsim.physics.mechanics.pinned import force_rms
from recipsim.physics.mechanics.tabulated import tabulated_pressure

TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class MechanismResult:
    """Last revolution of a flexible-mechanism run, sampled at equal crank-angle steps.

    Attributes
    ----------
    crank_angle : numpy.ndarray
        (n,) [rad], from the revolution's start angle (multiple of 2 pi from the start).
    time : numpy.ndarray
        (n,) [s].
    bearing_force : numpy.ndarray
        (n, 6, 3) force on the journal side, ``BEARING_NAMES`` order, X, Y, Z [N].
    bearing_displacement : numpy.ndarray
        (n, 6, 3) journal minus bushing marker, normal to the bearing axis [m].
    drive_torque, crank_speed : numpy.ndarray
        (n,) [N m], [rad/s].
    piston_displacement, piston_lateral, piston_tilt : numpy.ndarray
        (n,) crown displacement from rigid TDC [m], centre of mass Y [m], tilt [rad].
    aux : numpy.ndarray
        (n, N_AUX) every output (layout ``A_*``).
    states : numpy.ndarray
        (n, N_STATE).
    force_rms, force_peak, orbit_radius_max : numpy.ndarray
        (6,) per bearing over the revolution: RMS and peak force magnitude [N], largest
        relative displacement [m].
    revolutions : int
        Revolutions integrated.
    converged : bool
        Whether the periodicity test passed.
    cycle_change : float
        Largest change of a state over the last revolution, relative to its scale [-].
    nfev : int
        Right-hand-side evaluations, all revolutions.
    wall_time : float
        Integration time [s].
    """

    crank_angle: np.ndarray
    time: np.ndarray
    bearing_force: np.ndarray
    bearing_displacement: np.ndarray
    drive_torque: np.ndarray
    crank_speed: np.ndarray
    piston_displacement: np.ndarray
    piston_lateral: np.ndarray
    piston_tilt: np.ndarray
    aux: np.ndarray = field(repr=False)
    states: np.ndarray = field(repr=False)
    force_rms: np.ndarray
    force_peak: np.ndarray
    orbit_radius_max: np.ndarray
    revolutions: int
    converged: bool
    cycle_change: float
    nfev: int
    wall_time: float

    def force(self, name: str) -> np.ndarray:
        """Force of bearing ``name``, (n, 3) [N]."""
        return self.bearing_force[:, lay.BEARING_NAMES.index(name), :]

    def columns(self) -> dict[str, np.ndarray]:
        """Report columns with units (``crank_angle [deg]``, ``bearing_force_primary_x [N]``...)."""
        cols: dict[str, np.ndarray] = {
            "crank_angle [deg]": np.degrees(self.crank_angle - self.crank_angle[0]),
            "time [s]": self.time,
        }
        for i, name in enumerate(lay.BEARING_NAMES):
            for k, ax in enumerate("xyz"):
                cols[f"bearing_force_{name}_{ax} [N]"] = self.bearing_force[:, i, k]
            cols[f"bearing_force_{name} [N]"] = np.linalg.norm(self.bearing_force[:, i], axis=1)
            for k, ax in enumerate("xyz"):
                cols[f"bearing_displacement_{name}_{ax} [m]"] = self.bearing_displacement[:, i, k]
        cols["drive_torque [N m]"] = self.drive_torque
        cols["crank_speed [rad/s]"] = self.crank_speed
        cols["piston_displacement [m]"] = self.piston_displacement
        cols["piston_lateral [m]"] = self.piston_lateral
        cols["piston_tilt [rad]"] = self.piston_tilt
        return cols


def simulate_mechanism(
    spec: MechanismSpec,
    geometry: CrankGeometry,
    pressure_angles: np.ndarray,
    pressures: np.ndarray,
    p_shell: float,
    omega: float,
    drive: str = "constant_speed",
    revolutions: int | None = None,
    rtol: float = 1e-6,
    *,
    method: str = "LSODA",
    samples_per_revolution: int = 360,
    periodic_tolerance: float = 1e-3,
    max_revolutions: int = 30,
    drive_angles: np.ndarray | None = None,
    drive_torques: np.ndarray | None = None,
    initial_angle: float = 0.0,
    y0: np.ndarray | None = None,
) -> MechanismResult:
    """Integrate the flexible mechanism to a periodic response; return the last revolution.

    Parameters
    ----------
    spec : MechanismSpec
    geometry : CrankGeometry
    pressure_angles, pressures : numpy.ndarray
        Periodic cylinder pressure table, crank angle [rad] and pressure [Pa].
    p_shell : float
        Shell pressure under the piston [Pa].
    omega : float
        Crank speed [rad/s] (prescribed for ``constant_speed``; initial speed and speed
        of the pinned torque table for ``torque_profile``).
    drive : {"constant_speed", "torque_profile"}
    revolutions : int, optional
        Fixed number of revolutions; default: until periodic (at most
        ``max_revolutions``).
    rtol : float
        Relative tolerance; absolute tolerances are ``rtol`` times
        :func:`.flexible.state_scales`.
    method : str
        ``solve_ivp`` method. LSODA (default) was measured the fastest or close to it
        at the paper's stiffness and 2-8x faster than RK45/DOP853 with stiffness x100
        and x1000 (it switches to BDF); RK45 is as fast at the paper's stiffness.
    samples_per_revolution : int
        Output samples over the last revolution.
    periodic_tolerance : float
        Convergence when every state changes over a revolution by less than this times
        its scale (its largest value over the revolution, at least its
        :func:`state_scales` entry); at least 2 revolutions are run.
    drive_angles, drive_torques : numpy.ndarray, optional
        Torque table for ``torque_profile`` [rad], [N m]; default: the pinned driving
        torque (:func:`pinned_torque_profile`), as in the paper.
    initial_angle : float
        Crank angle at t = 0 [rad].
    y0 : numpy.ndarray, optional
        Initial state; default the quasi-static pinned pose (:func:`initial_state`).

    Returns
    -------
    MechanismResult
    """
    pa = np.ascontiguousarray(pressure_angles, dtype=float)
    pp = np.ascontiguousarray(pressures, dtype=float)
    par = mechanism_parameters(spec, geometry, shell_pressure=p_shell, speed=omega, drive=drive)
    if drive == "torque_profile":
        if drive_angles is None or drive_torques is None:
            drive_angles, drive_torques = pinned_torque_profile(
                spec, geometry, pa, pp, p_shell, omega
            )
        da = np.ascontiguousarray(drive_angles, dtype=float)
        dt = np.ascontiguousarray(drive_torques, dtype=float)
    else:
        da = np.zeros(1)
        dt = np.zeros(1)
    if y0 is None:
        p0 = tabulated_pressure(initial_angle, pa, pp)
        y = initial_state(par, initial_angle, omega, p0)
    else:
        y = np.array(y0, dtype=float)
    scales = state_scales(par)
    atol = rtol * scales

    dydt = np.zeros(lay.N_STATE)
    aux = np.zeros(lay.N_AUX)
    no_tables = np.zeros(1)  # the paper's linear bearings have no finite_journal table

    def fun(t: float, state: np.ndarray) -> np.ndarray:
        flexible_rhs_tabulated(t, state, dydt, aux, par, pa, pp, da, dt, no_tables)
        return dydt.copy()

    def crank_event(t: float, state: np.ndarray) -> float:
        return float(state[lay.Y_CRANK_ANGLE] - target)

    crank_event.terminal = True  # type: ignore[attr-defined]
    crank_event.direction = 1.0  # type: ignore[attr-defined]

    n_max = revolutions if revolutions is not None else max_revolutions
    t0 = 0.0
    nfev = 0
    converged = False
    change = math.inf
    start = time.perf_counter()
    sol = None
    theta_start = y[lay.Y_CRANK_ANGLE]
    n_done = 0
    for n_done in range(1, n_max + 1):  # noqa: B007
        period = TWO_PI / omega
        # scipy's automatic first step can be far too long here (a rejected blow-up)
        first_step = 1e-5 * period
        target = theta_start + TWO_PI
        # at constant speed a revolution is one period; a driven crank ends on the event
        constant = drive == "constant_speed"
        t_end = t0 + (period if constant else 3.0 * period)
        from scipy.integrate import solve_ivp  # 0.25 s to import: only where used

        sol = solve_ivp(
            fun,
            (t0, t_end),
            y,
            method=method,
            rtol=rtol,
            atol=atol,
            dense_output=True,
            events=None if constant else crank_event,
            first_step=first_step,
        )
        if not constant and sol.status != 1:
            raise RuntimeError("the crank did not complete a revolution in 3 periods")
        if not sol.success:
            raise RuntimeError(f"integration failed: {sol.message}")
        nfev += sol.nfev
        t1 = sol.t[-1]
        y1 = sol.y[:, -1].copy()
        # periodicity: change over the revolution relative to each state's scale
        samples = sol.sol(np.linspace(t0, t1, 64))
        size = np.maximum(np.abs(samples).max(axis=1), scales)
        diff = y1 - y
        diff[lay.Y_CRANK_ANGLE] -= TWO_PI
        change = float(np.max(np.abs(diff) / size))
        y_start, t_start = y, t0
        y, t0 = y1, t1
        theta_start = y[lay.Y_CRANK_ANGLE]
        if revolutions is None and n_done >= 2 and change < periodic_tolerance:
            converged = True
            break
    wall = time.perf_counter() - start
    assert sol is not None

    # sample the last revolution at equal crank-angle steps
    th0 = y_start[lay.Y_CRANK_ANGLE]
    targets = th0 + TWO_PI * np.arange(samples_per_revolution) / samples_per_revolution
    ts = t_start + (targets - th0) / omega
    if drive != "constant_speed":
        for _ in range(8):  # Newton on theta(t) = target with the dense output
            ys = sol.sol(ts)
            ts = ts - (ys[lay.Y_CRANK_ANGLE] - targets) / ys[lay.Y_CRANK_SPEED]
            ts = np.clip(ts, t_start, t0)
    ys = np.ascontiguousarray(sol.sol(ts).T)
    gas = np.array([tabulated_pressure(th, pa, pp) for th in ys[:, lay.Y_CRANK_ANGLE]])
    out = np.zeros((ts.size, lay.N_AUX))
    flexible_output_history(ts, ys, par, gas, da, dt, np.zeros(1), out)
    nb = lay.N_BEARINGS
    forces = out[:, lay.A_BEARING_FORCE : lay.A_BEARING_FORCE + 3 * nb].reshape(-1, nb, 3)
    disp = out[:, lay.A_BEARING_DISPLACEMENT : lay.A_BEARING_DISPLACEMENT + 3 * nb]
    disp = disp.reshape(-1, nb, 3)
    return MechanismResult(
        crank_angle=ys[:, lay.Y_CRANK_ANGLE].copy(),
        time=ts,
        bearing_force=forces.copy(),
        bearing_displacement=disp.copy(),
        drive_torque=out[:, lay.A_DRIVE_TORQUE].copy(),
        crank_speed=out[:, lay.A_CRANK_SPEED].copy(),
        piston_displacement=out[:, lay.A_PISTON_DISPLACEMENT].copy(),
        piston_lateral=out[:, lay.A_PISTON_LATERAL].copy(),
        piston_tilt=out[:, lay.A_PISTON_TILT].copy(),
        aux=out,
        states=ys,
        force_rms=force_rms(forces),
        force_peak=np.linalg.norm(forces, axis=2).max(axis=0),
        orbit_radius_max=np.linalg.norm(disp, axis=2).max(axis=0),
        revolutions=n_done,
        converged=converged,
        cycle_change=change,
        nfev=nfev,
        wall_time=wall,
    )
