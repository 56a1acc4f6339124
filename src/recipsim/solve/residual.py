"""How far a revolution is from the periodic state: the changes of the states over it,
of its totals from the previous revolution, and its mass and energy closures.

The closures (:func:`closures`) are those of the summary
(``mass_balance_residual``, ``energy_balance_residual``): over one revolution of the
cylinder, what came in less what went out, relative to the suction mass and the
indicated work. On a periodic revolution they vanish up to the integration error; on a
revolution that is not yet periodic they are the change of the cylinder's gas content,
so they also measure periodicity. The state change judges the gas density against the
whole gas in the cylinder, the closure against the gas that passes through it: near zero
delivery (R600a at pressure ratio 21 on a 5.5 % clearance, volumetric efficiency 1.8 %)
the cylinder keeps about 57 times the mass it passes, and a state change of 4.7e-5 left
a mass closure of 2.0e-3 and a volumetric efficiency 0.26 % off. The cycle residual
therefore includes the closures, divided by :data:`CLOSURE_ALLOWANCE`: a converged
revolution closes its balances to ``CLOSURE_ALLOWANCE * solver.cycle_tolerance`` (1e-3
at the default 1e-4). The allowance leaves room for the integration error of the
quadratures at ``rtol = 1e-6`` (closures of the shipped cases: up to 3.6e-4), so on
ordinary points the closures never decide convergence.

Below a volumetric efficiency of about :data:`CLOSURE_FLOOR` the suction mass and the
indicated work shrink towards zero with the delivery and stop being a yardstick: the
closures are then taken relative to ``CLOSURE_FLOOR`` times the swept mass (suction
density times swept volume) and ``CLOSURE_FLOOR`` times ``(p_d - p_s) V_swept``, a bound
on the ideal compressor's work on it.

Each total's change between revolutions is judged against the larger of its two values
and its floor (:func:`revolution_totals`): the drive work's is
:func:`reciprocating_energy`, so that a conservative load (net drive work ~1e-11 J per
revolution, all round-off) is judged on an energy scale of the crank train. Shared by
the revolution iteration (:mod:`.periodic`), shooting (:mod:`.shooting`) and period-n
shooting (:mod:`.subharmonic`).
"""

from __future__ import annotations

import math
from typing import Protocol

import numpy as np

from recipsim.model.build import Model, scenes
from recipsim.physics.mechanics import layout as mlay

__all__ = [
    "CLOSURE_ALLOWANCE",
    "CLOSURE_FLOOR",
    "closures",
    "cycle_residual",
    "reciprocating_energy",
    "residual_reference",
    "revolution_totals",
    "state_change",
]


class Revolution(Protocol):
    """What is read of a revolution (:class:`recipsim.solve.revolution.Revolution`)."""

    y_start: np.ndarray
    y_end: np.ndarray
    mode_start: np.ndarray
    mode_end: np.ndarray
    samples: np.ndarray


#: A revolution is converged when its closures are below this many cycle tolerances.
CLOSURE_ALLOWANCE = 10.0
#: Fraction of the swept mass (and of the ideal work on it) below which the suction mass
#: (the indicated work) no longer sets the closures' scale.
CLOSURE_FLOOR = 1e-2


#: The residual has stalled when its best over the last ``STALL_WINDOW`` revolutions is
#: no better than ``STALL_GAIN`` times its best before them.
STALL_WINDOW = 8
STALL_GAIN = 0.5


def stalled(history: list[float]) -> bool:
    """Whether the cycle residual stopped decaying (see :data:`STALL_WINDOW`)."""
    if len(history) <= STALL_WINDOW:
        return False
    return min(history[-STALL_WINDOW:]) >= STALL_GAIN * min(history[:-STALL_WINDOW])


def residual_reference(model: Model, rev: Revolution) -> np.ndarray:
    """Size against which each error-controlled state's change over ``rev`` is judged.

    T and rho: their values at the start; reed lift and velocity: their scales;
    mechanism states: their largest magnitude over the revolution (at least their
    scale). Shape ``(model.n_err,)``; entries of zero scale are quadratures.
    """
    ref = model.scale[: model.n_err].copy()
    if model.has_gas:
        model.gas_state(ref)[:] = model.gas_state(rev.y_start)
    if model.scene != scenes.SCENE_CYLINDER:
        # mechanism states relative to their size over the revolution (at least their scale)
        size = np.abs(model.mechanism_state(rev.samples)).max(axis=0)
        mech = model.mechanism_state(ref)
        mech[:] = np.maximum(size, mech)
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


def closures(model: Model, y_end: np.ndarray) -> tuple[float, float]:
    """Mass and energy closures of a revolution whose quadratures are in ``y_end``.

    Mass: (suction - discharge - leakage mass) over the suction mass; energy: (indicated
    work - (enthalpy out - enthalpy in - heat in)) over the indicated work; each scale at
    least :data:`CLOSURE_FLOOR` times the swept mass or ``(p_d - p_s) V_swept`` (module
    docstring). (0, 0) for a scene without gas.
    """
    if not model.has_gas:
        return 0.0, 0.0
    y = scenes.named_state(model.scene, y_end)
    m_suc = y.suction_mass_in - y.suction_mass_out
    m_dis = y.discharge_mass_out - y.discharge_mass_in
    m_leak = y.leakage_mass_out - y.leakage_mass_in
    work = y.work_on_gas
    h_out = (y.discharge_enthalpy_out - y.discharge_enthalpy_in) + (
        y.leakage_enthalpy_out - y.leakage_enthalpy_in
    )
    h_in = y.suction_enthalpy_in - y.suction_enthalpy_out
    op = model.case.operating_point
    swept = model.case.geometry.swept_volume
    m_scale = max(m_suc, CLOSURE_FLOOR * model.compressor_inlet.density * swept)
    w_scale = max(work, CLOSURE_FLOOR * (op.discharge_pressure - op.suction_pressure) * swept)
    mass = (m_suc - m_dis - m_leak) / m_scale
    energy = (work - (h_out - h_in - y.heat_to_gas)) / w_scale
    return float(mass), float(energy)


def cycle_residual(model: Model, rev: Revolution, previous: Revolution | None) -> float:
    """Largest relative change over one revolution (see the module docstring).

    :func:`state_change` of ``rev``, the relative change of its suction mass, indicated
    work, discharge enthalpy and drive work from ``previous`` (at least 1 without a
    previous revolution), each judged against the larger of its two values and its floor
    (:func:`revolution_totals`; the drive work's is :func:`reciprocating_energy`), and
    its :func:`closures` over :data:`CLOSURE_ALLOWANCE`.
    """
    res = state_change(model, rev)
    if previous is None:
        return max(res, 1.0)
    for q, floor in revolution_totals(model):
        a, b = rev.y_end[q], previous.y_end[q]
        res = max(res, abs(a - b) / max(abs(a), abs(b), floor, 1e-300))
    mass, energy = closures(model, rev.y_end)
    return max(res, abs(mass) / CLOSURE_ALLOWANCE, abs(energy) / CLOSURE_ALLOWANCE)


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
    mp = mlay.PAR.bundle(model.mechanism_par)
    speed = mp.crank_radius * 2.0 * math.pi / model.period
    return 0.5 * (mp.piston_mass + mp.rod_mass) * speed * speed


def revolution_totals(model: Model) -> list[tuple[int, float]]:
    """Quadratures whose change between revolutions the cycle residual checks, each with
    the floor of the size its change is judged against (0: its own values only)."""
    gas = ("suction_mass_in", "work_on_gas", "discharge_enthalpy_out") if model.has_gas else ()
    checks = [(model.state_index(name), 0.0) for name in gas]
    if model.scene != scenes.SCENE_CYLINDER:
        checks.append((model.state_index("drive_work"), reciprocating_energy(model)))
    return checks
