"""Anderson acceleration of the revolution iteration on a crank train.

Revolution iteration is the fixed-point iteration ``z <- G(z)`` of the one-revolution map
(:mod:`.shooting`'s unknowns ``z`` at the section: gas T and rho, the free reeds, the
mechanism's states, the discharge plenum's enthalpy). It converges like the map's largest
Floquet multiplier: on the lubricated crank train one slow mode of the bearings' orbit
sets the pace, a multiplier of about -0.39 on the journals (9 revolutions to 1e-4) and
0.81 with the piston's skirt film (the piston's lateral drift: 39 revolutions), while
every other mode has died out after a few revolutions. Shooting would solve for every
mode at the cost of one revolution per unknown (about 30 on the coupled scene).

Anderson mixing (Anderson 1965; Walker & Ni, SIAM J. Numer. Anal. 49, 2011, "type II"
with mixing 1) uses the revolutions already run instead: with ``f = G(z) - z`` and the
differences of the last ``MEMORY`` iterates, ``Delta F gamma ~ f_k`` in least squares,
the next start is ``G(z_k) - Delta G gamma``. On a linear map with one slow mode it is
the exact extrapolation ``z* = z_k + f_k / (1 - mu)`` after one difference; in general it
is GMRES on ``G(z) - z`` (Walker & Ni). It only moves the next revolution's start: each
revolution is integrated from its start as before and convergence is judged exactly as
in plain revolution iteration (the cycle residual of a revolution against the previous
one), so an accelerated solve ends on a revolution as genuine as a plain one.

Scales: each unknown relative to the cycle residual's reference
(:func:`~recipsim.solve.residual.residual_reference`), except the crank speed under a
free-running drive: the rotor's kinetic energy is several times the drive work of a
revolution (13 J against 2 J on the reference compressor), so a speed that is off by a
part in 1e5 moves the revolution's drive work, which the cycle residual also judges, by
7 parts in 1e5. The crank speed is scaled by ``W / (I omega)``, the speed error that
moves the drive work ``W`` by its own size (``I``: the rotor's polar inertia with the
counterweight): unscaled, the least squares would not see it and leave the drive work
converging at the plain rate.

Safeguards: no mixing on the first revolution (from the initial state, far from the
orbit, the map is far from linear); the history restarts when the discrete modes at the
section change (the unknowns change), when the residual grew over the last revolution,
or when the step would be larger than :data:`MAX_GAIN` times the plain step (noise: near
the cycle tolerance the map is only as smooth as the integrator's step sequence makes
it); the least squares drop directions below :data:`RCOND` of the largest singular value.
"""

from __future__ import annotations

import numpy as np

from recipsim.model.build import WorkingModel, scenes
from recipsim.physics.mechanics import layout as mlay
from recipsim.solve.residual import reciprocating_energy, residual_reference
from recipsim.solve.revolution import Revolution, discharge_enthalpy
from recipsim.solve.shooting_map import shooting_unknowns

#: Differences kept: the slow modes of a crank train are one or two (the bearings' orbit,
#: the crank speed under a motor); a longer memory keeps iterates from farther away,
#: where the map is less linear (measured: 3 and 5 took 1-3 more revolutions on the skirt).
MEMORY = 2
#: Singular values of the scaled differences below this fraction of the largest are dropped.
RCOND = 1e-6
#: Largest Anderson step, in multiples of the plain step ``f_k`` (scaled infinity norms):
#: the exact extrapolation of a mode of multiplier ``mu`` is ``mu / (1 - mu)`` plain
#: steps beyond ``G(z_k)``, 19 at ``mu = 0.95``.
MAX_GAIN = 20.0


class AndersonMixing:
    """Anderson mixing of the revolution iteration of one solve (module docstring).

    Call :meth:`next_start` after each revolution with the revolution and the state the
    next one would start from (its end); it moves that state, and the model's discharge
    plenum, to the accelerated start.
    """

    def __init__(self, model: WorkingModel) -> None:
        self.model = model
        self.idx = np.zeros(0, dtype=np.int64)
        self.ref = np.ones(0)
        self.starts: list[np.ndarray] = []  # scaled z_k
        self.images: list[np.ndarray] = []  # scaled G(z_k)
        self.enthalpy_start = model.discharge.enthalpy if model.has_gas else 0.0
        self.seen = 0  # revolutions recorded
        self.mixed = 0  # accelerated starts so far

    def _reset(self, rev: Revolution) -> None:
        self.idx = shooting_unknowns(self.model, rev.mode_end)
        ref = residual_reference(self.model, rev)
        speed = self.model.state_index("mechanism_crank_speed")
        ref[speed] = min(ref[speed], _speed_scale(self.model, rev))
        self.ref = np.append(ref[self.idx], max(abs(self.enthalpy_start), 1.0))
        self.starts, self.images = [], []

    def next_start(self, rev: Revolution, y_next: np.ndarray) -> None:
        """Record ``rev`` (its start, end and delivered discharge enthalpy) and move
        ``y_next`` (the next revolution's start, ``rev``'s end) and the discharge plenum's
        enthalpy to the accelerated start, where the history allows it.

        The plenum must hold the enthalpy ``rev`` ran with when this is called (the next
        one is set here, to what ``rev`` delivered or to its accelerated value).
        """
        model = self.model
        h_used = self.enthalpy_start
        h_out = discharge_enthalpy(model, rev)
        h_next = h_used if h_out is None else h_out
        self.seen += 1
        if self.seen == 1:  # from the initial state: the plain step
            self.enthalpy_start = h_next
            return
        modes_same = np.array_equal(rev.mode_start, rev.mode_end)
        if not modes_same or not np.array_equal(shooting_unknowns(model, rev.mode_end), self.idx):
            self._reset(rev)
        idx = self.idx
        z = np.append(rev.y_start[idx], h_used) / self.ref
        g = np.append(rev.y_end[idx], h_next) / self.ref
        if self.images and _norm(g - z) >= _norm(self.images[-1] - self.starts[-1]):
            self.starts, self.images = [], []  # no progress: restart from here
        self.starts = [*self.starts[-MEMORY:], z]
        self.images = [*self.images[-MEMORY:], g]
        start = _anderson(self.starts, self.images) if modes_same else g
        y_next[idx] = start[:-1] * self.ref[:-1]
        self.enthalpy_start = float(start[-1] * self.ref[-1])
        if h_out is not None:
            model.set_discharge_enthalpy(self.enthalpy_start)
        self.mixed += int(start is not g)


def _speed_scale(model: WorkingModel, rev: Revolution) -> float:
    """``W / (I omega)`` [rad/s]: the crank speed error that changes the drive work of
    ``rev`` by its own size (module docstring; ``W`` at least the reciprocating energy
    that floors it in the cycle residual)."""
    mp = mlay.PAR.bundle(model.mechanism_par)
    inertia = mp.rotor_polar_inertia + mp.counterweight_mass * mp.counterweight_radius**2
    end = scenes.named_state(model.scene, rev.y_end)
    work = max(abs(end.drive_work), reciprocating_energy(model))
    omega = abs(end.mechanism_crank_speed)
    return work / (inertia * omega) if inertia * omega > 0.0 else np.inf


def _norm(v: np.ndarray) -> float:
    return float(np.max(np.abs(v))) if v.size else 0.0


def _anderson(starts: list[np.ndarray], images: list[np.ndarray]) -> np.ndarray:
    """The Anderson (type II) start from the scaled iterates ``starts`` and their images
    ``images`` (oldest first); the last image itself if there is no difference yet or the
    step would exceed :data:`MAX_GAIN` plain steps."""
    g = images[-1]
    if len(starts) < 2:
        return g
    f = [gi - zi for zi, gi in zip(starts, images, strict=True)]
    d_f = np.column_stack([f[i + 1] - f[i] for i in range(len(f) - 1)])
    d_g = np.column_stack([images[i + 1] - images[i] for i in range(len(f) - 1)])
    gamma, *_ = np.linalg.lstsq(d_f, f[-1], rcond=RCOND)
    start = g - d_g @ gamma
    if _norm(start - g) > MAX_GAIN * _norm(f[-1]) or not np.all(np.isfinite(start)):
        return g
    return start
