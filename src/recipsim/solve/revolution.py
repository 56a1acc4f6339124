"""One revolution of any scene and what is measured on it: integration from 270 deg
with the compiled integrator, the discharge-plenum enthalpy for the next one,
statistics, and the outputs at the samples (the cycle residual against the previous
revolution is :mod:`.residual`).
Shared by the revolution iteration (:mod:`.periodic`) and shooting (:mod:`.shooting`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from recipsim.errors import SolverError
from recipsim.model.build import Model, WorkingModel, scenes
from recipsim.model.scenes import N_AUX
from recipsim.solve.integrator import (
    CHATTERING,
    INTERRUPTED,
    METHOD_AUTO,
    METHOD_AUTO_IN_W,
    METHOD_DOPRI5,
    METHOD_ROSW,
    N_STATS,
    PROPERTY_FAILURE,
    ST_H,
    ST_IN_W,
    ST_NACCEPT,
    ST_NEVENTS,
    ST_NFEV,
    ST_NREJECT,
    ST_NSAMPLES,
    ST_STATUS,
    ST_T,
    STEP_UNDERFLOW,
)
from recipsim.solve.residual import (  # noqa: F401  (re-exported: callers import them here)
    cycle_residual,
    residual_reference,
    state_change,
)
from recipsim.solve.scene_entries import integrate
from recipsim.solve.scene_outputs import evaluate_samples

_FAILURES = {
    STEP_UNDERFLOW: "the step size fell below its floor",
    PROPERTY_FAILURE: (
        "the gas state left the property model's range (the refrigerant file's limits or the "
        "equation of state's domain) and smaller steps did not help"
    ),
    CHATTERING: "more than 50 events at one instant (valve chattering)",
}


@dataclass
class Revolution:
    """One integrated revolution.

    Attributes
    ----------
    y_start, y_end : ndarray
        State at the start and end (quadratures of this revolution in ``y_end``).
    times : ndarray
        Sample times from the start of the revolution [s], sorted by crank angle.
    samples, sample_modes : ndarray
        State and modes at the sample times.
    stats : ndarray
        Integrator counters.
    """

    y_start: np.ndarray
    y_end: np.ndarray
    mode_start: np.ndarray
    mode_end: np.ndarray
    times: np.ndarray
    samples: np.ndarray
    sample_modes: np.ndarray
    stats: np.ndarray
    duration: float = 0.0


@dataclass
class PeriodicSolution:
    """The converged revolution and how it was reached.

    ``revolutions`` counts every integrated revolution, including the finite-difference
    Jacobian columns and trial steps of shooting; ``residual_history`` holds the cycle
    residual of every revolution that was not a Jacobian column. ``model`` is the working
    copy the solve moved (:meth:`~recipsim.model.build.Model.for_solve`): the plenum
    states and the thermal network as the converged revolution left them.
    """

    model: WorkingModel
    final: Revolution
    revolutions: int
    residual: float
    converged: bool
    residual_history: list[float] = field(default_factory=list)
    nfev: int = 0
    steps: int = 0
    rejected: int = 0
    events: int = 0
    wall_time: float = 0.0
    #: how the periodic state was found: "revolutions" or "shooting"
    method: str = "revolutions"
    #: shooting only: Newton steps taken, Jacobians built by finite differences and the
    #: revolutions they cost (included in ``revolutions``)
    newton_iterations: int = 0
    jacobians: int = 0
    jacobian_revolutions: int = 0
    #: shooting only: the last Jacobian (scaled) and its scales, to seed another solve
    jacobian: tuple[np.ndarray, np.ndarray] | None = None
    #: revolutions per period: > 1 for a subharmonic response (``final`` then holds the
    #: quadratures averaged over the period, :mod:`recipsim.solve.periodic`)
    period_revolutions: int = 1
    #: shooting only: eigenvalues of the one-revolution map's Jacobian at the solution
    #: (Floquet multipliers; from the last finite-difference or Broyden Jacobian)
    multipliers: np.ndarray | None = None


def sample_times(model: Model, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Times within a revolution at the uniform crank angles 0, 360/n, ... deg.

    Returns
    -------
    times : ndarray
        Sorted in time [s].
    order : ndarray
        Index that sorts the samples by crank angle.
    """
    times, order = _sample_times(n, model.shaft_speed, model.start_angle)
    return times.copy(), order.copy()


@lru_cache(maxsize=64)
def _sample_times(n: int, omega: float, theta0: float) -> tuple[np.ndarray, np.ndarray]:
    """:func:`sample_times` at ``n`` samples, crank speed ``omega`` [rad/s] and start
    angle ``theta0`` [rad]; the same for every revolution of a solve (kept here, handed
    out as copies, rather than sorted again at every revolution)."""
    angles = 2.0 * math.pi * np.arange(n) / n
    times = np.mod(angles - theta0, 2.0 * math.pi) / omega
    order_time = np.argsort(times, kind="stable")
    times_sorted = times[order_time]
    # position in the time-sorted array of each crank-angle sample
    order = np.empty(n, dtype=np.int64)
    order[order_time] = np.arange(n)
    return times_sorted, order


def working(model: Model) -> WorkingModel:
    """``model`` itself if it is a working copy (:meth:`~recipsim.model.build.Model.for_solve`).

    Raises
    ------
    TypeError
        For a built model: its arrays are read-only, and the compiled code would be
        compiled again for them (a read-only array is another numba type).
    """
    if not isinstance(model, WorkingModel):
        raise TypeError("integrate a working copy of the model: model.for_solve()")
    return model


def revolution_setup(
    model: WorkingModel, y: np.ndarray, mode: np.ndarray, n_samples: int
) -> tuple[np.ndarray, np.ndarray, float, np.ndarray, np.ndarray, np.ndarray]:
    """What any integrator needs to run one revolution from ``y``, ``mode``.

    Returns the state copy with the quadratures reset, the mode copy, the end time
    (three nominal periods when the speed is free: the crank-angle event ends the
    revolution, armed here in the working copy ``model``), the sample times and the sample
    buffers.
    """
    working(model)
    y_run = y.copy()
    y_run[model.quadratures] = 0.0
    mode_run = mode.copy()
    t_end = model.period
    if model.free_speed:
        theta = model.crank_angle(y_run)
        model.set_revolution_end(theta + 2.0 * math.pi)
        t_end = 3.0 * model.period
        times = model.period * np.arange(n_samples) / n_samples
    else:
        times, _ = sample_times(model, n_samples)
    samples = np.zeros((n_samples, y.shape[0]))
    sample_modes = np.zeros((n_samples, mode.shape[0]), dtype=np.int64)
    return y_run, mode_run, t_end, times, samples, sample_modes


#: ``solver.method`` -> ``method`` of the compiled integrator. ``"dopri5"`` stays pure
#: DOPRI5; ``"dopri5_stiff"`` switches to the Rosenbrock-W step where DOPRI5's stability
#: limits the step (30 % fewer right-hand sides on the reference case at rtol 1e-6);
#: ``"ros34pw2"`` uses the W-step throughout. The bench runs ``"dopri5_stiff"`` as its own
#: rung.
INTEGRATOR_METHODS = {
    "dopri5": METHOD_DOPRI5,
    "dopri5_stiff": METHOD_AUTO,
    "ros34pw2": METHOD_ROSW,
}


def integrator_method(model: Model) -> int:
    """The compiled integrator's ``method`` code for the case's ``solver.method``."""
    return INTEGRATOR_METHODS[model.case.solver.method]


def integrate_revolution(
    model: WorkingModel, y: np.ndarray, mode: np.ndarray, h: float, n_samples: int
) -> tuple[Revolution, float]:
    """Integrate one revolution from ``y`` (modified copy returned in the result).

    With a free crank speed the revolution ends on the crank-angle event at the start
    angle plus 2 pi (at most three nominal periods); samples are then taken at equal
    time steps of the nominal period and :func:`recipsim.results.tables.cycle_table`
    resamples them at equal crank angles.

    Under ``"dopri5_stiff"`` a revolution starts with the step the previous one on the
    working copy ended with, W or DOPRI5 (``model.ended_in_w_step``), as one continuous
    integration would. Restarted in DOPRI5, the switch waits for Hairer's stiffness
    test, which misses a strongly damped mode holding DOPRI5's step below its stability
    boundary: the piston on its skirt film (eigenvalue about -1.3e7 1/s, ``h |lambda|``
    held near 2.4 < 3.25) ran 2 000-10 000 explicit steps at the start of some
    revolutions and 5 of others, by the first step; their end states differed by 5e-3
    of the piston's lateral travel at rtol 1e-5, a jump in the one-revolution map that
    stalled the mixed revolutions and shooting.
    """
    s = model.case.solver
    y_run, mode_run, t_end, times, samples, sample_modes = revolution_setup(
        model, y, mode, n_samples
    )
    y_start = y.copy()
    mode_start = mode.copy()
    stats = np.zeros(N_STATS)
    omega = model.shaft_speed
    method = integrator_method(model)
    if method == METHOD_AUTO and model.ended_in_w_step:
        method = METHOD_AUTO_IN_W
    with model.props.interrupts_deferred():
        integrate(
            0.0,
            t_end,
            y_run,
            mode_run,
            model.par,
            model.ipar,
            model.props,
            model.props.buffer,
            s.rtol,
            s.atol,
            model.scale,
            model.n_err,
            h,
            s.max_step / omega,
            times,
            samples,
            sample_modes,
            stats,
            method,
        )
    model.props.raise_if_interrupted()  # a Ctrl-C caught inside the property callback
    status = int(stats[ST_STATUS])
    model.ended_in_w_step = stats[ST_IN_W] != 0.0
    if status != 0:
        _raise_failure(model, status, stats[ST_T], y_run, mode_run)
    if model.free_speed:
        n_done = int(stats[ST_NSAMPLES])
        if stats[ST_T] >= t_end:
            raise SolverError(
                "the crank did not complete a revolution in three nominal periods "
                "(crank speed at the end "
                f"{scenes.named_state(model.scene, y_run).mechanism_crank_speed:.4g}"
                " rad/s): the drive torque cannot keep the mechanism turning"
            )
        times, samples, sample_modes = times[:n_done], samples[:n_done], sample_modes[:n_done]
    if model.scene != scenes.SCENE_CYLINDER:
        # the model is 2 pi-periodic in the crank angle: keep the state near the start angle
        model.unwind_crank(y_run)
    rev = Revolution(y_start, y_run, mode_start, mode_run, times, samples, sample_modes, stats)
    rev.duration = float(stats[ST_T])
    return rev, next_first_step(model, float(stats[ST_H]))


#: Smallest first step carried into the next revolution, as a fraction of the period.
FIRST_STEP_FLOOR = 1e-6


def next_first_step(model: Model, h_last: float) -> float:
    """First trial step of the next revolution [s] from the integrator's last step.

    The last step of a revolution is cut to land on its end (or on an event there) and
    can be a round-off (1e-16 s with ideal valves, whose closing event sits at the end
    angle); carried over as the next revolution's first step it would start below the
    step floor. Such a step is replaced by the usual first step, 1e-4 of the period.
    """
    if not h_last >= FIRST_STEP_FLOOR * model.period:
        return model.period * 1e-4
    return h_last


def _raise_failure(model: Model, status: int, t: float, y: np.ndarray, mode: np.ndarray) -> None:
    if status == INTERRUPTED:  # Ctrl-C under a handler that does not raise it itself
        raise KeyboardInterrupt
    if model.scene == scenes.SCENE_CYLINDER:
        theta_rad = model.start_angle + model.shaft_speed * t
    else:
        theta_rad = model.crank_angle(y)
    theta = math.degrees(theta_rad % (2 * math.pi))
    parts = []
    state = scenes.named_state(model.scene, y)
    if model.has_gas:
        parts.append(
            f"T = {state.gas_temperature:.6g} K, rho = {state.gas_density:.6g} kg/m3, "
            f"suction lift = {state.suction_valve_lift:.4g} m (mode {mode[0]}), "
            f"discharge lift = {state.discharge_valve_lift:.4g} m (mode {mode[1]})"
        )
    if model.scene != scenes.SCENE_CYLINDER:
        parts.append(
            f"crank speed = {state.mechanism_crank_speed:.6g} rad/s, rotor at "
            f"({state.mechanism_rotor_x:.4g}, {state.mechanism_rotor_y:.4g}) m, piston lateral "
            f"{state.mechanism_piston_y:.4g} m"
        )
    raise SolverError(
        f"integration failed at crank angle {theta:.3f} deg (t = {t:.6g} s into the revolution): "
        f"{_FAILURES.get(status, 'unknown failure')}; state: " + "; ".join(parts)
    )


def discharge_enthalpy(model: Model, rev: Revolution) -> float | None:
    """Mass-weighted enthalpy of the gas discharged over ``rev`` [J/kg] (None without
    gas or discharge, and with the shell's thermal network, whose discharge chamber node
    is then the back-flow's source: :mod:`recipsim.model.thermal`)."""
    if not model.has_gas or model.thermal is not None:
        return None
    end = scenes.named_state(model.scene, rev.y_end)
    m_out = end.discharge_mass_out
    return float(end.discharge_enthalpy_out / m_out) if m_out > 0.0 else None


class _Tally:
    """Integrator counters over every revolution of a solve; ``budget``: the most
    accepted steps it may take (``solver.step_budget``), None for no limit."""

    def __init__(self, budget: int | None = None) -> None:
        self.budget = budget
        self.revolutions = 0
        self.nfev = 0
        self.steps = 0
        self.rejected = 0
        self.events = 0

    def add(self, rev: Revolution) -> None:
        """Count one revolution; a negative step count (an integrator that does not
        report it) makes the total unknown (-1)."""
        self.revolutions += 1
        self.nfev += int(rev.stats[ST_NFEV])
        self.events += int(rev.stats[ST_NEVENTS])
        for name, slot in (("steps", ST_NACCEPT), ("rejected", ST_NREJECT)):
            count = int(rev.stats[slot])
            total = getattr(self, name)
            setattr(self, name, total + count if total >= 0 and count >= 0 else -1)
        if self.budget is not None and self.steps > self.budget:
            raise SolverError(
                f"the solve took {self.steps:,} steps in {self.revolutions} revolutions, "
                f"over solver.step_budget = {self.budget:,}: loosen solver.rtol or "
                "solver.max_step, or raise solver.step_budget"
            )


def sample_outputs(model: Model, rev: Revolution, cylinder_only: bool = False) -> np.ndarray:
    """Auxiliary outputs (layout ``A_*`` of the scene) at every sample, in time order,
    with the post-processing outputs (peak film pressures) switched on; ``model`` is a
    working copy, e.g. the solution's (:func:`working`).

    ``cylinder_only``: only the cylinder's block (its first ``cylinder.N_AUX`` columns),
    for the cylinder on the rigid crank, whose right-hand side fills nothing else (the
    summary of a rigid-crank point, which need not evaluate all of the scene's 111
    outputs, most of them the mechanism's).
    """
    width = N_AUX
    if cylinder_only:
        if model.scene != scenes.SCENE_CYLINDER:
            raise ValueError("cylinder_only is for the cylinder on the rigid crank")
        width = scenes.A_MECH
    out = np.zeros((rev.times.shape[0], width))
    par = working(model).detailed_output_par()
    evaluate_samples(
        rev.times,
        rev.samples,
        rev.sample_modes,
        par,
        model.ipar,
        model.props,
        model.props.buffer,
        out,
    )
    return out
