"""The one-revolution map of shooting (:mod:`.shooting`): its unknowns at the section,
its cost in revolutions, and ``z -> G(z)`` (:class:`RevolutionMap`, which
:mod:`.subharmonic` chains over n revolutions). The unknowns and why are in
:mod:`.shooting`'s docstring.
"""

from __future__ import annotations

import numpy as np

from recipsim.model.build import Model, WorkingModel, scenes
from recipsim.physics.mechanics import layout as mlay
from recipsim.physics.mechanics.drives import DRIVES
from recipsim.physics.thermo.valve_models import VALVE_MODELS
from recipsim.solve.revolution import (
    Revolution,
    _Tally,
    discharge_enthalpy,
    integrate_revolution,
    residual_reference,
)

#: Finite-difference steps relative to the residual reference: gas states and the
#: discharge enthalpy, mechanism states, crank speed.
_FD_STEP_GAS = 1e-3
_FD_STEP_MECHANISM = 0.2
_FD_STEP_SPEED = 1e-4
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
        idx += [model.state_index("gas_temperature"), model.state_index("gas_density")]
        if VALVE_MODELS.by_code(int(scenes.IPAR.bundle(model.ipar).valves)).moves_reeds:
            for i, reed in enumerate(("suction", "discharge")):
                if mode[i] == 1:  # free reed: lift and velocity are unknowns
                    idx += [model.state_index(f"{reed}_valve_{s}") for s in ("lift", "velocity")]
    if model.scene != 0:
        speed_unknown = model.free_speed and DRIVES[model.case.options.drive].motor_curve
        fixed = {"crank_angle"} if speed_unknown else {"crank_angle", "crank_speed"}
        idx += [
            model.state_index("mechanism_" + e.name)
            for e in mlay.STATES.entries
            if e.name not in fixed
        ]
    return np.array(sorted(idx), dtype=np.int64)


def shooting_cost(model: Model, mode: np.ndarray) -> int:
    """Revolutions a shooting solve is expected to take: one per unknown (the
    Jacobian) plus the Newton steps and the final check."""
    return int(shooting_unknowns(model, mode).size) + int(model.has_gas) + _OVERHEAD


class RevolutionMap:
    """``z -> G(z)``: one revolution from the unknowns ``z`` at the section.

    ``z`` holds the unknown states, then (gas scenes) the discharge plenum's enthalpy.
    The other states are those of the base state (crank angle, pinned reeds, a fixed
    crank speed); the modes are the base modes.
    """

    def __init__(self, model: WorkingModel, tally: _Tally):
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
                step[idx == self.model.state_index("mechanism_crank_speed")] = _FD_STEP_SPEED
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
