"""The cycle residual: how much one revolution changed from the previous one.

The error-controlled states' change over the revolution (:func:`state_change`) and the
change of the revolution's totals from the previous one (suction mass, indicated work,
discharge enthalpy, drive work), each relative to its size (:func:`cycle_residual`).
Shared by the revolution iteration (:mod:`.periodic`) and shooting (:mod:`.shooting`).
"""

from __future__ import annotations

import math

import numpy as np

from recipsim.model.build import Model, scenes
from recipsim.physics.mechanics import layout as mlay
from recipsim.physics.thermo import cylinder as cyl
from recipsim.solve.revolution import Revolution

__all__ = ["cycle_residual", "reciprocating_energy", "residual_reference", "state_change"]


def residual_reference(model: Model, rev: Revolution) -> np.ndarray:
    """Size against which each error-controlled state's change over ``rev`` is judged.

    T and rho: their values at the start; reed lift and velocity: their scales;
    mechanism states: their largest magnitude over the revolution (at least their
    scale). Shape ``(model.n_err,)``; entries of zero scale are quadratures.
    """
    ref = model.scale[: model.n_err].copy()
    if model.has_gas:
        ref[cyl.Y_T] = rev.y_start[cyl.Y_T]
        ref[cyl.Y_RHO] = rev.y_start[cyl.Y_RHO]
    if model.scene != scenes.SCENE_CYLINDER:
        m0 = model.mechanism_offset
        # mechanism states relative to their size over the revolution (at least their scale)
        size = np.abs(rev.samples[:, m0 : m0 + mlay.N_STATE]).max(axis=0)
        ref[m0 : m0 + mlay.N_STATE] = np.maximum(size, ref[m0 : m0 + mlay.N_STATE])
    return ref


def state_change(model: Model, rev: Revolution) -> float:
    """Largest change of an error-controlled state over ``rev`` relative to
    :func:`residual_reference`; at least 1 if the discrete modes differ at its ends."""
    controlled = model.scale[: model.n_err] > 0.0
    d = np.abs(rev.y_end[: model.n_err] - rev.y_start[: model.n_err])
    ref = residual_reference(model, rev)
    res = float(np.max(d[controlled] / ref[controlled]))
    if not np.array_equal(rev.mode_start, rev.mode_end):
        res = max(res, 1.0)
    return res


def cycle_residual(model: Model, rev: Revolution, previous: Revolution | None) -> float:
    """Largest relative change over one revolution (see module docstring).

    :func:`state_change` of ``rev`` and the relative change of its suction mass,
    indicated work, discharge enthalpy and drive work from ``previous`` (at least 1
    without a previous revolution). Each total's change is judged against the larger of
    its two values and its floor (:func:`_revolution_totals`): the drive work's is
    :func:`reciprocating_energy`, so that a conservative load (net drive work ~1e-11 J
    per revolution, all round-off) is judged on an energy scale of the crank train.
    """
    res = state_change(model, rev)
    if previous is None:
        return max(res, 1.0)
    for q, floor in _revolution_totals(model):
        a, b = rev.y_end[q], previous.y_end[q]
        res = max(res, abs(a - b) / max(abs(a), abs(b), floor, 1e-300))
    return res


def reciprocating_energy(model: Model) -> float:
    """Kinetic energy of the piston and rod moving at the crank pin's nominal speed [J].

    ``(m_piston + m_rod) (r omega)^2 / 2``: the energy the inertia torque exchanges with
    the drive and back within each half revolution, the scale of the drive work of a
    revolution that does no net work (0.37 J on the reference compressor at 3500 rpm,
    against a net drive work of 1.7-2.0 J per revolution at its rating: the floor
    changes nothing there). 0 without a mechanism.
    """
    if model.scene == scenes.SCENE_CYLINDER:
        return 0.0
    mp = model.par[scenes.P_MECH : scenes.P_MECH + mlay.N_PAR]
    speed = mp[mlay.P_CRANK_RADIUS] * 2.0 * math.pi / model.period
    return 0.5 * (mp[mlay.P_PISTON_MASS] + mp[mlay.P_ROD_MASS]) * speed * speed


def _revolution_totals(model: Model) -> list[tuple[int, float]]:
    """Quadratures whose change between revolutions the cycle residual checks, each with
    the floor of the size its change is judged against (0: its own values only)."""
    checks = (
        [(q, 0.0) for q in (cyl.Q_MSUC_IN, cyl.Q_WORK, cyl.Q_HDIS_OUT)] if model.has_gas else []
    )
    if model.scene != scenes.SCENE_CYLINDER:
        drive = model.mechanism_offset + mlay.N_STATE + scenes.MQ_DRIVE
        checks.append((drive, reciprocating_energy(model)))
    return checks
