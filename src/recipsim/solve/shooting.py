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
2. :func:`newton_fixed_point`: the Jacobian of ``G`` by forward differences, one
   revolution per unknown, steps ``_FD_STEP_*`` times the state's residual reference
   (the size the cycle residual divides by). The mechanism map is nearly linear in the
   deflections while the integrator's step selection makes it noisy at the level of
   the tolerance, so its steps are large (a fifth of the vibration amplitude: a tenth
   of that was measured to leave a Jacobian too noisy for one Newton step to gain more
   than 3x); gas states get 1e-3. Newton steps in residual-scaled variables by a
   truncated SVD, then Broyden updates of the same Jacobian; a fresh one only when a
   step fails to reduce the residual even after halving;
3. Newton stops when the states repeat to half the tolerance
   (:func:`.periodic.state_change`); then a plain revolution from the end state: the
   solution is accepted when its :func:`.periodic.cycle_residual` against the previous
   revolution is below ``solver.cycle_tolerance``, exactly the criterion of
   revolution iteration, so both solvers are judged alike and the reported revolution
   is an ordinary one. If the totals (work, mass) of that revolution still moved,
   Newton aims closer and tries again.

Discrete valve modes: the modes at the section are those of the last plain
revolution; every map evaluation starts from them. Steps of 1e-3 of T and rho move
valve events continuously and do not flip the modes at the section (both valves are
shut at 270 deg); a difference revolution that ends in other modes than the base is
retried with a step ten times smaller and kept if it still does. When Newton stalls
(no step reduces the residual with a fresh Jacobian) or a difference revolution
fails, the solver falls back to revolution iteration for the remaining revolutions.

Limits: the map is only as smooth as the integrator makes it. Undamped bearings ring
at up to 6.6 kHz, over a hundred periods per revolution, and at ``rtol = 1e-6`` the
end state of a revolution jumps by about 1e-4 of the vibration amplitude when the
start state moves by 1e-9 (the step sequence changes): that is the cycle tolerance,
so undamped runs need a tighter ``solver.rtol``: 1e-7 under the tabulated curve,
1e-8 on the coupled scene (measured: at 1e-7 Newton stalls there; 68 revolutions at
1e-8, ``src/recipsim/data/cases/hard/bearings_undamped.toml``). With the
``torque_profile`` drive and light or no damping there is no periodic state to find:
the crank speed drifts every revolution by the energy the angle-only torque does not
balance, and the response of the undamped high-frequency modes is so sensitive to
that speed that neither solver settles; use ``constant_speed`` (or a drive with a
restoring torque) for the periodic response of undamped bearings.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from recipsim.errors import SolverError
from recipsim.model.build import Model
from recipsim.physics.mechanics import layout as mlay
from recipsim.physics.thermo import cylinder as cyl
from recipsim.solve.residual import cycle_residual, residual_reference, state_change
from recipsim.solve.revolution import (
    PeriodicSolution,
    Revolution,
    _Tally,
    discharge_enthalpy,
    integrate_revolution,
)

#: Plain revolutions before the first Jacobian when shooting starts from the initial
#: state (the first sets the discharge enthalpy, both damp the fast gas modes).
_PLAIN_FIRST = 2
#: Finite-difference steps relative to the residual reference: gas states and the
#: discharge enthalpy, mechanism states, crank speed.
_FD_STEP_GAS = 1e-3
_FD_STEP_MECHANISM = 0.2
_FD_STEP_SPEED = 1e-4
#: Singular values of the scaled ``dG/dz - I`` below this fraction of the largest are
#: treated as neutral directions (no step along them).
_SVD_CUTOFF = 1e-9
#: Largest Newton step, scaled infinity norm (1 = the state's residual reference).
_MAX_STEP = 4.0
#: Step halvings when the residual grows.
_BACKTRACK = 2
#: Newton stops when the state change over a revolution is below ``_TARGET`` times the
#: cycle tolerance; when the plain revolution that follows still fails the cycle
#: residual, the aim shrinks by ``_TARGET_SHRINK`` (down to ``_TARGET_FLOOR``).
_TARGET = 0.5
_TARGET_SHRINK = 0.2
_TARGET_FLOOR = 1e-3
#: Revolutions of a Newton solve beyond the Jacobian: steps and the final check.
_OVERHEAD = 4


def shooting_unknowns(model: Model, mode: np.ndarray) -> np.ndarray:
    """Indices of the state entries solved for by shooting (see the module docstring).

    Parameters
    ----------
    model : Model
    mode : numpy.ndarray
        Discrete modes at the section.

    Returns
    -------
    numpy.ndarray
        Sorted indices into the state vector.
    """
    idx: list[int] = []
    if model.has_gas:
        idx += [cyl.Y_T, cyl.Y_RHO]
        if model.ipar[cyl.I_VALVES] == cyl.VALVES_REED:
            for i in range(2):
                if mode[i] == 1:  # free reed: lift and velocity are unknowns
                    idx += [cyl.Y_XS + 2 * i, cyl.Y_VS + 2 * i]
    if model.scene != 0:
        m0 = model.mechanism_offset
        speed_unknown = model.free_speed and model.case.options.drive != "torque_profile"
        for i in range(mlay.N_STATE):
            if i == mlay.Y_CRANK_ANGLE or (i == mlay.Y_CRANK_SPEED and not speed_unknown):
                continue
            idx.append(m0 + i)
    return np.array(sorted(idx), dtype=np.int64)


def shooting_cost(model: Model, mode: np.ndarray) -> int:
    """Revolutions a shooting solve is expected to take: one per unknown (the
    Jacobian) plus the Newton steps and the final check."""
    return int(shooting_unknowns(model, mode).size) + int(model.has_gas) + _OVERHEAD


class _RevolutionMap:
    """``z -> G(z)``: one revolution from the unknowns ``z`` at the section.

    ``z`` holds the unknown states, then (gas scenes) the discharge plenum's enthalpy.
    The other states are those of the base state (crank angle, pinned reeds, a fixed
    crank speed); the modes are the base modes.
    """

    def __init__(self, model: Model, tally: _Tally):
        self.model = model
        self.gas = model.has_gas
        self.tally = tally
        self.h = model.period * 1e-4
        self.y_base = model.y0.copy()
        self.mode = model.mode0.copy()
        self.idx = np.zeros(0, dtype=np.int64)
        self.fd_step = np.zeros(0)

    @property
    def size(self) -> int:
        return self.idx.size + int(self.gas)

    def set_base(self, y: np.ndarray, mode: np.ndarray) -> bool:
        """Take the fixed states and modes from ``y``, ``mode``; True if the set of
        unknowns changed (a reed freed or pinned at the section)."""
        self.y_base = y.copy()
        self.mode = mode.copy()
        idx = shooting_unknowns(self.model, mode)
        changed = not np.array_equal(idx, self.idx)
        if changed:
            self.idx = idx
            step = np.full(idx.size, _FD_STEP_GAS)
            if self.model.scene != 0:
                m0 = self.model.mechanism_offset
                step[idx >= m0] = _FD_STEP_MECHANISM
                step[idx == m0 + mlay.Y_CRANK_SPEED] = _FD_STEP_SPEED
            self.fd_step = np.append(step, _FD_STEP_GAS) if self.gas else step
        return changed

    def pack(self, y: np.ndarray) -> np.ndarray:
        """Unknowns of the full state ``y`` with the model's current discharge enthalpy."""
        z = y[self.idx]
        if self.gas:
            z = np.append(z, self.model.discharge.enthalpy)
        return z

    def reference(self, rev: Revolution) -> np.ndarray:
        """Scale of each unknown: the cycle residual's reference (and |h|)."""
        ref = residual_reference(self.model, rev)[self.idx]
        if self.gas:
            ref = np.append(ref, abs(self.model.discharge.enthalpy))
        return ref

    def __call__(self, z: np.ndarray) -> tuple[np.ndarray, Revolution]:
        """Integrate one revolution from ``z``; returns ``G(z)`` and the revolution."""
        model = self.model
        y = self.y_base.copy()
        n = self.idx.size
        y[self.idx] = z[:n]
        if self.gas:
            model.set_discharge_enthalpy(float(z[n]))
        s = model.case.solver
        rev, self.h = integrate_revolution(model, y, self.mode, self.h, s.samples_per_revolution)
        self.tally.add(rev)
        g = rev.y_end[self.idx]
        if self.gas:
            enthalpy = discharge_enthalpy(model, rev)
            g = np.append(g, z[n] if enthalpy is None else enthalpy)
        return g, rev


def _newton_step(a: np.ndarray, f: np.ndarray) -> np.ndarray:
    """Least-norm solution of ``a dz = -f`` by truncated SVD, limited to ``_MAX_STEP``."""
    u, sv, vt = np.linalg.svd(a)
    keep = sv > _SVD_CUTOFF * sv[0]
    dz = -(vt[keep].T @ ((u[:, keep].T @ f) / sv[keep]))
    big = float(np.max(np.abs(dz)))
    if big > _MAX_STEP:
        dz *= _MAX_STEP / big
    return dz


@dataclass
class NewtonResult:
    """Outcome of :func:`newton_fixed_point`.

    Attributes
    ----------
    z, g : numpy.ndarray
        Last iterate and its image ``G(z)``.
    payload : object
        What the map returned with ``g`` for ``z`` (e.g. the revolution).
    converged : bool
        ``accept`` held at ``z``.
    stalled : bool
        Not converged although the budget was not spent: no step reduced the residual
        even with a fresh Jacobian.
    evaluations : int
        Map evaluations, Jacobian columns included.
    iterations : int
        Newton trial steps (each one map evaluation).
    jacobians, jacobian_evaluations : int
        Jacobians built by finite differences and the evaluations they cost.
    jacobian : numpy.ndarray or None
        Last scaled ``dG/dz - I`` (finite differences and Broyden updates), for reuse.
    """

    z: np.ndarray
    g: np.ndarray
    payload: Any
    converged: bool
    stalled: bool = False
    evaluations: int = 0
    iterations: int = 0
    jacobians: int = 0
    jacobian_evaluations: int = 0
    jacobian: np.ndarray | None = None


def newton_fixed_point(
    fun: Callable[[np.ndarray], tuple[np.ndarray, Any]],
    z: np.ndarray,
    first: tuple[np.ndarray, Any],
    ref: np.ndarray,
    fd_step: np.ndarray,
    accept: Callable[[np.ndarray, np.ndarray, Any], bool],
    max_evaluations: int,
    *,
    jacobian: np.ndarray | None = None,
    same_branch: Callable[[Any, Any], bool] | None = None,
    failures: tuple[type[BaseException], ...] = (SolverError,),
) -> NewtonResult:
    """Solve ``G(z) = z`` by Newton-Broyden with a finite-difference Jacobian.

    Works in scaled variables ``z / ref``. The Jacobian of ``G`` is built by forward
    differences (one evaluation per unknown, step ``fd_step * ref``), then updated by
    Broyden's rank-one formula after every accepted step; it is rebuilt only when no
    step reduces the scaled infinity norm of ``F = G(z) - z``. Steps come from a
    truncated SVD of ``dG/dz - I`` (directions with singular values below
    ``_SVD_CUTOFF`` of the largest are not stepped along), at most ``_MAX_STEP`` in the
    scaled infinity norm, halved up to ``_BACKTRACK`` times while the residual grows.

    Parameters
    ----------
    fun : callable
        ``fun(z) -> (G(z), payload)``; may raise one of ``failures`` (a failed
        evaluation: the trial step is halved, a Jacobian column retried smaller).
    z : numpy.ndarray
        Starting point.
    first : (numpy.ndarray, object)
        ``fun(z)``, already evaluated.
    ref : numpy.ndarray
        Scale of each unknown (positive).
    fd_step : numpy.ndarray
        Finite-difference steps relative to ``ref``.
    accept : callable
        ``accept(z, g, payload) -> bool``: convergence test at an evaluated point.
    max_evaluations : int
        Budget of map evaluations.
    jacobian : numpy.ndarray, optional
        Scaled ``dG/dz - I`` to start from (same ``ref``).
    same_branch : callable, optional
        ``same_branch(payload_base, payload_column)``: False when a difference step
        crossed a discontinuity (e.g. other valve modes); the column is retried with
        a step ten times smaller and kept if it still differs.
    failures : tuple of exception types
        Exceptions of ``fun`` that mean a failed evaluation.

    Returns
    -------
    NewtonResult
    """
    g, payload = first
    n = z.size
    a = jacobian
    fresh = False
    out = NewtonResult(z, g, payload, False, jacobian=a)
    while True:
        out.z, out.g, out.payload, out.jacobian = z, g, payload, a
        if accept(z, g, payload):
            out.converged = True
            return out
        if a is None:
            if out.evaluations + n + 1 > max_evaluations:
                return out
            try:
                a = _jacobian(fun, z, g, payload, ref, fd_step, same_branch, failures, out)
            except failures:
                out.stalled = True
                return out
            fresh = True
        f = (g - z) / ref
        norm = float(np.max(np.abs(f)))
        dz = _newton_step(a, f)
        found: tuple[np.ndarray, np.ndarray, Any, np.ndarray] | None = None
        for _ in range(_BACKTRACK + 1):
            if out.evaluations >= max_evaluations:
                return out
            z_new = z + dz * ref
            out.evaluations += 1
            out.iterations += 1
            try:
                g_new, payload_new = fun(z_new)
            except failures:
                dz = 0.5 * dz
                continue
            f_new = (g_new - z_new) / ref
            if float(np.max(np.abs(f_new))) < norm:
                found = (z_new, g_new, payload_new, f_new)
                break
            dz = 0.5 * dz
        if found is None:
            if fresh:
                out.stalled = True
                return out
            a = None  # Broyden's Jacobian went stale: rebuild it here
            continue
        z, g, payload, f_new = found
        # Broyden's rank-one update of the scaled Jacobian of F
        a = a + np.outer(f_new - f - a @ dz, dz) / float(dz @ dz)
        fresh = False


def _jacobian(
    fun: Callable[[np.ndarray], tuple[np.ndarray, Any]],
    z: np.ndarray,
    g: np.ndarray,
    payload: Any,
    ref: np.ndarray,
    fd_step: np.ndarray,
    same_branch: Callable[[Any, Any], bool] | None,
    failures: tuple[type[BaseException], ...],
    out: NewtonResult,
) -> np.ndarray:
    """Scaled ``dG/dz - I`` by forward differences, one evaluation per column."""
    n = z.size
    jac = np.empty((n, n))
    for j in range(n):
        step = fd_step[j] * ref[j]
        g_j: np.ndarray | None = None
        for attempt in range(2):
            zp = z.copy()
            zp[j] += step
            out.evaluations += 1
            out.jacobian_evaluations += 1
            try:
                g_try, payload_j = fun(zp)
            except failures:
                if attempt == 1:
                    raise
                step *= 0.1
                continue
            g_j = g_try
            if same_branch is None or same_branch(payload, payload_j) or attempt == 1:
                break
            step *= 0.1
        assert g_j is not None
        jac[:, j] = (g_j - g) / step
    out.jacobians += 1
    return jac / ref[:, None] * ref[None, :] - np.eye(n)


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
    return _Shooting(model, start, history, tally, t0, jacobian).run()


class _StatesRepeat:
    """Newton's convergence test: the states repeat over the revolution to ``target``."""

    def __init__(self, model: Model, target: float) -> None:
        self.model = model
        self.target = target

    def __call__(self, z: np.ndarray, g: np.ndarray, rev: Revolution) -> bool:
        return state_change(self.model, rev) < self.target


class _Shooting:
    """State of one shooting solve."""

    def __init__(
        self,
        model: Model,
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
        self.tally = _Tally() if tally is None else tally
        self.previous: Revolution | None = start[0] if start is not None else None
        self.h = model.period * 1e-4 if start is None else start[1]
        self.chained = False  # the last revolution started where the previous one ended
        self.newton = 0
        self.jacobians = 0
        self.jacobian_revolutions = 0
        self.method = "shooting"

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
        self.previous = rev
        return rev

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
        fmap = _RevolutionMap(model, self.tally)
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
            jacobian = result.jacobian
            if jacobian is not None:
                self.jacobian = (jacobian, ref)
            if result.stalled:
                self.method = "shooting, fell back to revolutions"
                newton_failed = True
            if result.payload is not rev:
                self.history.append(cycle_residual(model, result.payload, rev))
                rev = result.payload
