"""Periodic steady state by shooting: Newton on the one-revolution map.

The one-revolution map ``G`` takes the unknowns ``z`` at the section (crank angle
270 deg, where every revolution starts) to their values one revolution later; the
periodic state solves ``F(z) = G(z) - z = 0``. Revolution iteration is the fixed-point
iteration ``z <- G(z)``: it converges like the largest Floquet multiplier ``|mu|`` of
the cycle, so never for undamped flexible bearings (``|mu| = 1``) and slowly for
lightly damped ones. Newton converges whatever ``|mu|`` is, as long as no multiplier
is 1 (a forcing harmonic exactly on a natural frequency).

Unknowns (:func:`shooting_unknowns`):

- cylinder gas T and rho; the lift and velocity of a reed that is free (off its
  seat and stop) at the section (a seated or stopped reed is pinned there);
- the discharge plenum's enthalpy, the source of back-flow, which revolution
  iteration updates from each revolution's mass-weighted discharge enthalpy: an
  unknown with the equation "it equals the enthalpy discharged over the revolution"
  (with it the cylinder's slowest multiplier, 0.41, is solved for, not waited out);
- every mechanism state except the crank angle (the section, not an unknown) and
  the crank speed unless the drive has a restoring torque (a free speed under a
  speed-dependent drive torque, e.g. an induction motor). Under ``constant_speed`` it
  is prescribed; under ``torque_profile`` the torque depends on the crank angle only,
  so the speed is a neutral direction (Floquet multiplier 1 - 5e-5 with the paper's
  damping, 1 without): it is held at its section value and its drift per revolution,
  the energy imbalance, is judged by the cycle residual like every other state;
- not the quadratures (reset every revolution).

Method:

1. ``_PLAIN_FIRST`` plain revolutions from the initial state (in ``"auto"`` mode the
   revolutions already run), which damp the fast modes (the gas state's multipliers
   are 0.41 and below) and set the discharge enthalpy;
2. :func:`recipsim.solve.newton.newton_fixed_point` (finite-difference Jacobian,
   truncated-SVD steps, Broyden updates): one revolution per unknown, steps
   ``_FD_STEP_*`` times the state's residual reference. The mechanism map is nearly
   linear in the deflections while the integrator's step selection makes it noisy at
   the level of the tolerance, so its steps are large (a fifth of the vibration
   amplitude: a tenth of that leaves a Jacobian too noisy for one Newton step to gain
   more than 3x); gas states get 1e-3;
3. Newton stops when the states repeat to half the tolerance
   (:func:`.periodic.state_change`); then a plain revolution from the end state: the
   solution is accepted when its :func:`.periodic.cycle_residual` against the previous
   revolution is below ``solver.cycle_tolerance``, exactly the criterion of
   revolution iteration, so both solvers are judged alike. If the totals (work, mass)
   or the closures of that revolution still moved, Newton aims closer and tries again.
   (A response of period n is shot on the n-revolution map: :mod:`.subharmonic`.)

Discrete valve modes: the modes at the section are those of the last plain
revolution; every map evaluation starts from them. Steps of 1e-3 of T and rho move
valve events continuously and do not flip the modes at the section (both valves are
shut at 270 deg); a difference revolution that ends in other modes than the base is
retried with a step ten times smaller and kept if it still does. When Newton stalls
(no step reduces the residual with a fresh Jacobian), a difference revolution fails or
the cycle residual stops decaying (:func:`.residual.stalled`: the iterates have left for
an orbit of several revolutions, which the one-revolution map does not have), the solver
falls back to revolution iteration for the remaining revolutions, which ends on a period
of n revolutions as revolution iteration does (:func:`.subharmonic.subharmonic_period`).

Limits: the map is only as smooth as the integrator makes it. Undamped bearings ring
at up to 6.6 kHz, over a hundred periods per revolution, and at ``rtol = 1e-6`` the
end state of a revolution jumps by about 1e-4 of the vibration amplitude when the
start state moves by 1e-9 (the step sequence changes): that is the cycle tolerance,
so undamped runs need a tighter ``solver.rtol``: 1e-7 under the tabulated curve,
1e-8 on the coupled scene (measured: at 1e-7 Newton stalls there; 68 revolutions at
1e-8, ``cases/hard/bearings_undamped.toml``). With the
``torque_profile`` drive and light or no damping there is no periodic state to find:
the crank speed drifts every revolution by the energy the angle-only torque does not
balance, and the response of the undamped high-frequency modes is so sensitive to
that speed that neither solver settles; use ``constant_speed`` (or a drive with a
restoring torque) for the periodic response of undamped bearings.
"""

from __future__ import annotations

import time

import numpy as np

from recipsim.model.build import Model, WorkingModel
from recipsim.solve.newton import newton_fixed_point
from recipsim.solve.residual import cycle_residual, stalled, state_change
from recipsim.solve.revolution import (
    PeriodicSolution,
    Revolution,
    _Tally,
    discharge_enthalpy,
    integrate_revolution,
)
from recipsim.solve.shooting_map import (  # noqa: F401  (shooting_unknowns re-exported)
    RevolutionMap,
    shooting_cost,
    shooting_unknowns,
)
from recipsim.solve.subharmonic import SUBHARMONIC_PERIODS, settled_period

#: Plain revolutions before the first Jacobian when shooting starts from the initial
#: state (the first sets the discharge enthalpy, both damp the fast gas modes).
_PLAIN_FIRST = 2
#: Newton stops when the state change over a revolution is below ``_TARGET`` times the
#: cycle tolerance; when the plain revolution that follows still fails the cycle
#: residual, the aim shrinks by ``_TARGET_SHRINK`` (down to ``_TARGET_FLOOR``).
_TARGET = 0.5
_TARGET_SHRINK = 0.2
_TARGET_FLOOR = 1e-3


def solve_shooting(
    model: Model,
    start: tuple[Revolution, float] | None = None,
    history: list[float] | None = None,
    tally: _Tally | None = None,
    t0: float | None = None,
    jacobian: tuple[np.ndarray, np.ndarray] | None = None,
) -> PeriodicSolution:
    """Periodic steady state by Newton on the one-revolution map (module docstring).

    Parameters
    ----------
    model : Model
        Not changed: shooting moves a working copy of it
        (:meth:`~recipsim.model.build.Model.for_solve`), which the result carries.
    start : (Revolution, float), optional
        The last revolution already run and the integrator's step [s] (hand-over from
        revolution iteration); the discharge enthalpy of ``model`` must already be the
        one that revolution delivered. Default: start from ``model.y0``.
    history, tally, t0
        Residual history, counters and start time of the revolutions already run.
    jacobian : (numpy.ndarray, numpy.ndarray), optional
        A scaled Jacobian and its scales (``PeriodicSolution.jacobian`` of a solve of a
        model with the same unknowns, e.g. the same crank train under another pressure
        table at constant speed, whose map has the same linear part): the first Newton
        solve starts from it instead of finite differences.

    Returns
    -------
    PeriodicSolution
        ``revolutions`` counts every integrated revolution, the Jacobian columns and
        trial steps included; ``newton_iterations``, ``jacobians`` and
        ``jacobian_revolutions`` tell how they were spent.

    Raises
    ------
    SolverError
        If a plain revolution fails (with crank angle and state).
    """
    return shoot(model.for_solve(), start, history, tally, t0, jacobian)


def shoot(
    model: WorkingModel,
    start: tuple[Revolution, float] | None = None,
    history: list[float] | None = None,
    tally: _Tally | None = None,
    t0: float | None = None,
    jacobian: tuple[np.ndarray, np.ndarray] | None = None,
) -> PeriodicSolution:
    """:func:`solve_shooting` on the working copy ``model`` itself, which it moves (the
    hand-over from revolution iteration, which goes on with the same copy)."""
    return _Shooting(model, start, history, tally, t0, jacobian).run()


class _StatesRepeat:
    """Newton's convergence test: the states repeat over the revolution to ``target``."""

    def __init__(self, model: WorkingModel, target: float) -> None:
        self.model = model
        self.target = target

    def __call__(self, z: np.ndarray, g: np.ndarray, rev: Revolution) -> bool:
        return state_change(self.model, rev) < self.target


class _Shooting:
    """State of one shooting solve."""

    def __init__(
        self,
        model: WorkingModel,
        start: tuple[Revolution, float] | None,
        history: list[float] | None,
        tally: _Tally | None,
        t0: float | None,
        seed: tuple[np.ndarray, np.ndarray] | None = None,
    ) -> None:
        self.model = model
        self.seed = seed
        self.jacobian: tuple[np.ndarray, np.ndarray] | None = None
        self.s = model.case.solver
        self.t0 = time.perf_counter() if t0 is None else t0
        self.history = [] if history is None else history
        self.first = len(self.history)  # the residuals before are the hand-over's
        self.tally = _Tally() if tally is None else tally
        self.previous: Revolution | None = start[0] if start is not None else None
        self.h = model.period * 1e-4 if start is None else start[1]
        self.chained = False  # the last revolution started where the previous one ended
        self.newton = 0
        self.jacobians = 0
        self.jacobian_revolutions = 0
        self.map_jacobian: np.ndarray | None = None  # the last scaled dG/dz - I
        self.method = "shooting"
        self.chain: list[Revolution] = []  # the last plain revolutions run end to end

    def _plain(self, y: np.ndarray, mode: np.ndarray) -> Revolution:
        """A revolution of revolution iteration: from ``y`` with the discharge enthalpy
        of the previous revolution, which then follows this one; its residual against
        the previous revolution is recorded."""
        model = self.model
        rev, self.h = integrate_revolution(model, y, mode, self.h, self.s.samples_per_revolution)
        self.tally.add(rev)
        thermal_change = self._follow_enthalpy(rev)
        self.history.append(max(cycle_residual(model, rev, self.previous), thermal_change))
        self.chained = self.previous is not None and np.array_equal(
            rev.y_start, self.previous.y_end
        )
        keep = 2 * SUBHARMONIC_PERIODS[-1]
        self.chain = [*self.chain[-keep:], rev] if self.chained else [rev]
        self.previous = rev
        return rev

    def _subharmonic(self) -> PeriodicSolution | None:
        """Where the residual stalled and the chained plain revolutions repeat after n
        revolutions (:func:`.subharmonic.settled_period`), the solution of period n
        (quadratures averaged over it), as revolution iteration ends such a run; else
        None."""
        if not stalled(self.history):
            return None
        period, average = settled_period(self.model, self.chain, self.s.cycle_tolerance)
        if average is None:
            return None
        solution = self._solution(average, True)
        solution.period_revolutions = period
        return solution

    def _follow_enthalpy(self, rev: Revolution) -> float:
        """The discharge plenum takes the enthalpy ``rev`` delivered (the source of
        back-flow for the next revolution, as in revolution iteration), the shell's
        thermal network (if any) the revolution's flows: its relative change [-]. The
        network is held fixed over the map evaluations of a Newton solve."""
        enthalpy = discharge_enthalpy(self.model, rev)
        if enthalpy is not None:
            self.model.set_discharge_enthalpy(enthalpy)
        return self.model.update_thermal(rev.y_end, rev.duration)

    def _budget(self) -> int:
        return self.s.max_revolutions - self.tally.revolutions

    def _done(self, rev: Revolution) -> bool:
        """Converged as revolution iteration judges it: ``rev`` is a plain revolution
        from the end of the previous one and its cycle residual is below tolerance."""
        return (
            rev is self.previous
            and self.chained
            and self.history[-1] < self.s.cycle_tolerance
            and self.tally.revolutions >= self.s.min_revolutions
        )

    def _solution(self, rev: Revolution, converged: bool) -> PeriodicSolution:
        t = self.tally
        return PeriodicSolution(
            model=self.model,
            final=rev,
            revolutions=t.revolutions,
            residual=self.history[-1],
            converged=converged,
            residual_history=self.history,
            nfev=t.nfev,
            steps=t.steps,
            rejected=t.rejected,
            events=t.events,
            wall_time=time.perf_counter() - self.t0,
            method=self.method,
            newton_iterations=self.newton,
            jacobians=self.jacobians,
            jacobian_revolutions=self.jacobian_revolutions,
            jacobian=self.jacobian,
            multipliers=None
            if self.map_jacobian is None
            else np.linalg.eigvals(self.map_jacobian + np.eye(len(self.map_jacobian))),
        )

    def run(self) -> PeriodicSolution:
        model = self.model
        tol = self.s.cycle_tolerance
        # plain revolutions first (or those already run before the hand-over)
        if self.previous is None:
            rev = self._plain(model.y0.copy(), model.mode0.copy())
            for _ in range(_PLAIN_FIRST - 2):  # the last one is the first base below
                if self._done(rev) or self._budget() <= 0:
                    break
                rev = self._plain(rev.y_end.copy(), rev.mode_end.copy())
        else:
            rev = self.previous
        fmap = RevolutionMap(model, self.tally)
        jacobian: np.ndarray | None = None
        ref = np.ones(0)
        newton_failed = False
        target = _TARGET * tol  # Newton's aim for the state change
        while True:
            if self._done(rev):
                return self._solution(rev, True)
            if self._budget() <= 0:
                return self._solution(rev, False)
            if rev is not self.previous:
                # rev is a Newton iterate: the plain revolutions go on from its end
                self._follow_enthalpy(rev)
                self.previous = rev
                self.chained = False
            # the next base: a plain revolution from the end of the last one
            if fmap.set_base(rev.y_end, rev.mode_end):
                jacobian = None
                if self.seed is not None and self.seed[0].shape[0] == fmap.size:
                    jacobian, ref = self.seed  # the first base only
                self.seed = None
            z = fmap.pack(rev.y_end)
            rev = self._plain(rev.y_end.copy(), rev.mode_end.copy())
            g = fmap.pack(rev.y_end)
            if not newton_failed and stalled(self.history[self.first :]):
                # Newton gains nothing (the orbit may have a period of n revolutions,
                # which the one-revolution map does not have): revolutions settle it
                self.method = "shooting, fell back to revolutions"
                newton_failed = True
            if newton_failed:
                periodic = self._subharmonic()
                if periodic is not None:
                    return periodic
            if newton_failed or self._done(rev) or self._budget() <= 0:
                continue  # revolution iteration settles the rest
            change = state_change(model, rev)
            if change < tol:
                # the states repeat but the totals changed: aim closer (undamped
                # vibration keeps whatever error the periodic state has)
                target = max(min(_TARGET_SHRINK * target, 0.5 * change), _TARGET_FLOOR * tol)
            if jacobian is None:
                ref = fmap.reference(rev)
            fmap.h = self.h
            result = newton_fixed_point(
                fmap,
                z,
                (g, rev),
                ref,
                fmap.fd_step,
                _StatesRepeat(model, target),
                self._budget(),
                jacobian=jacobian,
                same_branch=lambda base, col: np.array_equal(base.mode_end, col.mode_end),
            )
            self.newton += result.iterations
            self.jacobians += result.jacobians
            self.jacobian_revolutions += result.jacobian_evaluations
            jacobian = self.map_jacobian = result.jacobian
            if jacobian is not None:
                self.jacobian = (jacobian, ref)
            if result.stalled:
                self.method = "shooting, fell back to revolutions"
                newton_failed = True
            if result.payload is not rev:
                self.history.append(cycle_residual(model, result.payload, rev))
                rev = result.payload
