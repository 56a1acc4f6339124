"""Start-up from rest on the induction motor (``solver.start = "rest"``).

The coupled scene (cylinder gas + flexible crank train, ``options.drive =
"induction_motor"``) is integrated in time from standstill, one window per revolution,
until the revolutions settle; the state reached is then handed to the periodic solver.

Initial state (:func:`rest_state`): crank at top dead centre (:data:`REST_ANGLE`, where
the gas force has no lever arm, so the motor's starting torque alone decides the start),
speed 0, bodies at their static pose (equal pressures on both sides of the piston: no
deflection), reeds shut on their seats, the cylinder gas at the standstill pressure
``p0`` (``solver.standstill_pressure``, default the saturation pressure at the ambient
temperature: the refrigerant equalised through the capillary at room temperature) and
at least :data:`REST_SUPERHEAT` above its dew point (the compressor body is warmer than
the room; gas at its dew point would condense on the first compression).

Boundary conditions (:func:`plenum_pressures`): the suction, discharge and shell
pressures start equalised at ``p0`` and move to the case's values along a smooth ramp
(``3 x^2 - 2 x^3``, ``x = t / solver.pull_down_time``), updated at the start of every
window; from ``t = pull_down_time`` on they are exactly the case's. Why not the case's
pressures from ``t = 0``: the reference PSC motor's starting torque (0.20 N m) is below
the mean load torque (0.27 N m), and against the full LBP pressures it stalls in the
first compression and runs backwards (measured), as a real PSC compressor does; it
starts against equalised pressures. A real system pulls down in minutes, which is
outside this model (no system model): the ramp time is the case's choice, and 0 applies
the case's pressures from ``t = 0`` (only the cylinder starts equalised). The suction gas
temperature moves with the ramp, from its rest value to the case's suction temperature.
The discharge plenum takes the mass-weighted enthalpy of the previous window's discharge
(as between revolutions in :mod:`recipsim.solve.periodic`).

Windows: the first from top dead centre to 270 deg, then one revolution each from 270
deg (both valves shut) on the crank-angle event, at most :data:`WINDOW_PERIODS` nominal
periods long (longer: the motor cannot turn the crank, :class:`SolverError`). The
transient has settled when, after the ramp, the cycle residual of
:func:`recipsim.solve.residual.cycle_residual` falls below ``solver.cycle_tolerance``.

Energy over the transient (mechanism quadratures, summed over the windows): motor work
= kinetic energy gained + gas work (the piston's work on the gas, net of the shell side,
``int (p - p_shell) dV``) + dissipation (bearing films and dampers: the work the bearings
absorb less the elastic energy they store).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from recipsim.errors import SolverError
from recipsim.model import scenes
from recipsim.model.build import START_ANGLE, Model, WorkingModel
from recipsim.physics.layout_table import Layout
from recipsim.physics.mechanics import layout as mlay
from recipsim.solve.integrator import (
    N_STATS,
    ST_H,
    ST_NACCEPT,
    ST_NFEV,
    ST_NSAMPLES,
    ST_STATUS,
    ST_T,
)
from recipsim.solve.periodic import solve_periodic
from recipsim.solve.residual import cycle_residual
from recipsim.solve.revolution import (
    PeriodicSolution,
    Revolution,
    _raise_failure,
    discharge_enthalpy,
    integrator_method,
    sample_outputs,
)
from recipsim.solve.scene_entries import integrate as integrate_scene
from recipsim.solve.startup_boundary import (
    ramp_fraction,
    rest_state,
    set_plenums,
    standstill_pressure,
)

#: samples of the start-up trace per nominal period (5 deg at the running speed)
SAMPLES_PER_PERIOD = 72
#: longest window, in nominal periods: a revolution taking longer is a stall
WINDOW_PERIODS = 50

#: Columns of StartupTransient.trace (names and units: startup.csv's where it writes them).
TRACE = Layout("start-up trace")
TR_TIME = TRACE.add("time", "s", "time from standstill")
TR_ANGLE = TRACE.add("crank_angle", "rad", "crank angle, unwrapped")
TR_SPEED = TRACE.add("crank_speed", "rad/s", "crank speed (the rotor's spin rate)")
TR_MOTOR_TORQUE = TRACE.add(
    "motor_torque",
    "N m",
    "torque of the induction motor's curve at that speed, positive along the rotation",
)
TR_PRESSURE = TRACE.add("cylinder_pressure", "Pa", "gas pressure in the cylinder")
TR_SUCTION_PRESSURE = TRACE.add("suction_pressure", "Pa", "suction plenum along the pull-down ramp")
TR_DISCHARGE_PRESSURE = TRACE.add(
    "discharge_pressure", "Pa", "discharge plenum along the pull-down ramp"
)
TR_BEARING_LOAD = TRACE.add_series(
    "bearing_load_{}", mlay.BEARING_NAMES, "N", "force magnitude of the bearing"
)
N_TRACE = TRACE.size


@dataclass
class StartupEnergy:
    """Energy balance of the crank train over the transient [J].

    ``closure = |motor_work - kinetic_energy_gained - gas_work - dissipation| /
    motor_work`` [-].
    """

    motor_work: float
    kinetic_energy_gained: float
    gas_work: float
    dissipation: float

    @property
    def closure(self) -> float:
        """Relative residual of the balance [-]."""
        rest = self.motor_work - self.kinetic_energy_gained - self.gas_work - self.dissipation
        return abs(rest) / abs(self.motor_work)


@dataclass
class StartupTransient:
    """The start-up transient, from standstill to the settled revolution.

    Attributes
    ----------
    trace : ndarray
        Shape ``(n, N_TRACE)``, columns ``TR_*``, at equal time steps.
    revolution_times : ndarray
        End time of every window [s] (the first is the 3/4 turn to 270 deg).
    revolution_speeds : ndarray
        Mean crank speed of every window, its angle over its duration [rad/s].
    residuals : list of float
        Cycle residual of every full revolution.
    final : Revolution
        The last revolution (its quadratures, for flow and power).
    settled : bool
        Whether the residual fell below the cycle tolerance after the ramp.
    model : WorkingModel or None
        The working copy the transient moved, left with the case's boundary conditions
        and the discharge plenum of the last revolution (the periodic solve goes on
        from it).
    """

    trace: np.ndarray
    revolution_times: np.ndarray
    revolution_speeds: np.ndarray
    residuals: list[float]
    final: Revolution
    settled: bool
    energy: StartupEnergy
    standstill_pressure: float
    nfev: int = 0
    steps: int = 0
    wall_time: float = 0.0
    windows: int = 0
    extra: dict[str, float] = field(default_factory=dict)
    model: WorkingModel | None = field(default=None, repr=False)

    @property
    def duration(self) -> float:
        """Time from standstill to the end of the settled revolution [s]."""
        return float(self.revolution_times[-1])


def _outputs_at(model: Model, y: np.ndarray, mode: np.ndarray) -> np.ndarray:
    """Scene outputs (``A_*``) at one state."""
    one = Revolution(y, y, mode, mode, np.zeros(1), y[None, :], mode[None, :], np.zeros(N_STATS))
    return sample_outputs(model, one)[0]


def _mechanical_energy(model: Model, aux: np.ndarray) -> tuple[float, float]:
    """Kinetic energy of the crank train and elastic energy of its bearings [J]."""
    out = scenes.OUTPUTS.bundle(aux)
    kinetic = (
        out.mechanism_kinetic_energy_rotor
        + out.mechanism_kinetic_energy_rod
        + out.mechanism_kinetic_energy_piston
    )
    return float(kinetic), float(out.mechanism_spring_energy)


def _trace_rows(model: Model, rev: Revolution, t_window: float) -> np.ndarray:
    """The trace columns at the samples of one window."""
    out = scenes.OUTPUTS.bundle(sample_outputs(model, rev))
    states = scenes.named_state(model.scene, rev.samples)
    rows = np.empty((rev.times.shape[0], N_TRACE))
    rows[:, TR_TIME] = t_window + rev.times
    rows[:, TR_ANGLE] = states.mechanism_crank_angle
    rows[:, TR_SPEED] = states.mechanism_crank_speed
    rows[:, TR_MOTOR_TORQUE] = out.mechanism_drive_torque
    rows[:, TR_PRESSURE] = out.cylinder_pressure
    rows[:, TR_SUCTION_PRESSURE] = model.suction.pressure
    rows[:, TR_DISCHARGE_PRESSURE] = model.discharge.pressure
    for i, name in enumerate(mlay.BEARING_NAMES):
        fx = getattr(out, f"mechanism_bearing_force_{name}_x")
        fy = getattr(out, f"mechanism_bearing_force_{name}_y")
        rows[:, TR_BEARING_LOAD + i] = np.hypot(fx, fy)
    return rows


def _window(
    model: WorkingModel,
    y: np.ndarray,
    mode: np.ndarray,
    t_window: float,
    theta_end: float,
    h: float,
) -> tuple[Revolution, float]:
    """Integrate from ``y`` at time ``t_window`` until the crank angle ``theta_end``."""
    s = model.case.solver
    omega = model.shaft_speed
    dt = model.period / SAMPLES_PER_PERIOD
    t_limit = WINDOW_PERIODS * model.period
    k0 = math.ceil(t_window / dt - 1e-9)
    k1 = math.floor((t_window + t_limit) / dt)
    times = np.arange(k0, k1 + 1) * dt - t_window
    samples = np.zeros((times.shape[0], y.shape[0]))
    sample_modes = np.zeros((times.shape[0], mode.shape[0]), dtype=np.int64)
    y_run = y.copy()
    y_run[model.quadratures] = 0.0
    mode_run = mode.copy()
    stats = np.zeros(N_STATS)
    model.set_revolution_end(theta_end)
    with model.props.interrupts_deferred():
        integrate_scene(
            0.0, t_limit, y_run, mode_run, model.par, model.ipar, model.props,
            model.props.buffer, s.rtol, s.atol, model.scale, model.n_err, h, s.max_step / omega,
            times, samples, sample_modes, stats, integrator_method(model),
        )  # fmt: skip
    model.props.raise_if_interrupted()
    status = int(stats[ST_STATUS])
    if status != 0:
        _raise_failure(model, status, stats[ST_T], y_run, mode_run)
    if stats[ST_T] >= t_limit:
        speed = scenes.named_state(model.scene, y_run).mechanism_crank_speed
        raise SolverError(
            f"start-up from rest: the crank did not reach {math.degrees(theta_end):.0f} deg "
            f"within {t_limit:.3g} s after t = {t_window:.4g} s (crank speed "
            f"{speed:.4g} rad/s): the motor cannot start the compressor "
            f"against the pressures at that time; lengthen "
            f"solver.pull_down_time or lower solver.standstill_pressure"
        )
    n = int(stats[ST_NSAMPLES])
    rev = Revolution(
        y.copy(), y_run, mode.copy(), mode_run, times[:n], samples[:n], sample_modes[:n], stats
    )
    rev.duration = float(stats[ST_T])
    return rev, float(stats[ST_H])


def run_startup(model: Model) -> StartupTransient:
    """Integrate the start-up from rest until the revolutions settle (module docstring).

    ``model`` is not changed: the transient moves a working copy of it
    (:meth:`~recipsim.model.build.Model.for_solve`), which the result carries, left with
    the case's boundary conditions and the discharge plenum of the last revolution,
    ready for the periodic solver from ``final.y_end``.

    Raises
    ------
    SolverError
        If a window fails (with crank angle and state) or the motor cannot turn the crank.
    """
    model = model.for_solve()
    s = model.case.solver
    start = time.perf_counter()
    p0 = standstill_pressure(model)
    y, mode = rest_state(model, p0)
    kinetic0, spring0 = _mechanical_energy(model, _outputs_at(model, y, mode))
    work = np.zeros(scenes.N_MECH_QUAD)
    rows: list[np.ndarray] = []
    ends: list[float] = []
    speeds: list[float] = []
    residuals: list[float] = []
    t, h, nfev, steps = 0.0, model.period * 1e-4, 0, 0
    previous: Revolution | None = None
    rev: Revolution | None = None
    settled = False
    for count in range(1, s.max_revolutions + 1):
        theta_start = model.crank_angle(y)
        theta_end = START_ANGLE if count == 1 else theta_start + 2.0 * math.pi
        rev, h = _window(model, y, mode, t, theta_end, h)
        rows.append(_trace_rows(model, rev, t))
        work += model.mechanism_quadratures(rev.y_end)
        nfev += int(rev.stats[ST_NFEV])
        steps += int(rev.stats[ST_NACCEPT])
        t += rev.duration
        ends.append(t)
        speeds.append((theta_end - theta_start) / rev.duration)
        if count > 1:
            model.unwind_crank(rev.y_end)
        y, mode = rev.y_end.copy(), rev.mode_end.copy()
        ramp_done = ramp_fraction(t - rev.duration, s.pull_down_time) >= 1.0
        if count > 1:
            residuals.append(cycle_residual(model, rev, previous if count > 2 else None))
            settled = ramp_done and count > 2 and residuals[-1] < s.cycle_tolerance
        if settled:
            break
        set_plenums(model, p0, t, discharge_enthalpy(model, rev))
        previous = rev
    assert rev is not None
    kinetic1, spring1 = _mechanical_energy(model, _outputs_at(model, y, mode))
    totals = scenes.MECH_QUAD.bundle(work)
    energy = StartupEnergy(
        motor_work=float(totals.drive_work),
        kinetic_energy_gained=kinetic1 - kinetic0,
        gas_work=-float(totals.gas_work_on_piston),
        dissipation=float(totals.bearing_dissipation) - (spring1 - spring0),
    )
    enthalpy = discharge_enthalpy(model, rev)
    if enthalpy is not None:
        model.set_discharge_enthalpy(enthalpy)
    return StartupTransient(
        trace=np.concatenate(rows),
        revolution_times=np.array(ends),
        revolution_speeds=np.array(speeds),
        residuals=residuals,
        final=rev,
        settled=settled,
        energy=energy,
        standstill_pressure=p0,
        nfev=nfev,
        steps=steps,
        wall_time=time.perf_counter() - start,
        windows=len(ends),
        model=model,
    )


@dataclass
class StartupRun:
    """The start-up transient and the periodic state it was handed to.

    ``flow_difference`` and ``power_difference``: the last revolution of the transient
    against the periodic solution, relative [-]: mean suction mass flow (in less
    back-flow) and mean drive power.
    """

    transient: StartupTransient
    solution: PeriodicSolution
    flow_difference: float
    power_difference: float


def revolution_flow_and_power(model: Model, rev: Revolution) -> tuple[float, float]:
    """Mean net suction mass flow [kg/s] and mean drive power [W] over ``rev``."""
    end = scenes.named_state(model.scene, rev.y_end)
    mass = end.suction_mass_in - end.suction_mass_out
    return float(mass / rev.duration), float(end.drive_work / rev.duration)


def solve_from_rest(model: Model) -> StartupRun:
    """Start-up transient (:func:`run_startup`), then the periodic solver from its end
    (from the transient's working copy; ``model`` is not changed).

    Raises
    ------
    SolverError
        If the transient or the periodic solve fails.
    """
    transient = run_startup(model)
    work = transient.model
    assert work is not None
    work.y0 = transient.final.y_end.copy()
    work.mode0 = transient.final.mode_end.copy()
    solution = solve_periodic(work)
    flow_t, power_t = revolution_flow_and_power(work, transient.final)
    flow_p, power_p = revolution_flow_and_power(work, solution.final)
    return StartupRun(
        transient=transient,
        solution=solution,
        flow_difference=abs(flow_t - flow_p) / abs(flow_p),
        power_difference=abs(power_t - power_p) / abs(power_p),
    )
