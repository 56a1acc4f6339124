"""Flexible mechanism: compiled right-hand side, initial state, accessors, energy."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from numba import njit
from numba.core.runtime import _nrt_python as nrt
from numba.core.runtime import rtsys
from scipy.integrate import solve_ivp

from recipsim.case.mechanism_spec import CrankGeometry, MechanismSpec, with_damping
from recipsim.model.mechanism_parameters import mechanism_parameters
from recipsim.physics.kinematics import piston_displacement
from recipsim.physics.mechanics import layout as lay
from recipsim.physics.mechanics.flexible import (
    flexible_outputs,
    flexible_rhs,
    flexible_rhs_tabulated,
)
from recipsim.physics.mechanics.flexible_setup import initial_state, state_scales
from recipsim.physics.mechanics.pinned import N_PIN_OUT, pinned_reactions
from recipsim.physics.mechanics.piston_pose import (
    piston_axial_displacement,
    piston_lateral_offset,
    piston_tilt,
)
from recipsim.physics.mechanics.tabulated import PressureCurve

NO_TABLE = np.zeros(1)


@njit
def _call_rhs_many(n, y, dydt, aux, par, pa, pp, da, dt, bt):  # type: ignore[no-untyped-def]
    for _ in range(n):
        flexible_rhs_tabulated(0.0, y, dydt, aux, par, pa, pp, da, dt, bt)


def test_rhs_is_compiled_and_allocation_free(
    spec: MechanismSpec, geometry: CrankGeometry, omega: float, curve: PressureCurve
) -> None:
    """The RHS runs in nopython mode and makes no heap allocation: the runtime's
    allocation counter moves the same for 1 and for 5000 calls from compiled code."""
    par = mechanism_parameters(spec, geometry, shell_pressure=1.15e5, speed=omega)
    y = initial_state(par, 0.4, omega, 8e5)
    dydt, aux = np.zeros(lay.N_STATE), np.zeros(lay.N_AUX)
    args = (y, dydt, aux, par, curve.crank_angle, curve.pressure, NO_TABLE, NO_TABLE, NO_TABLE)
    _call_rhs_many(1, *args)  # compile
    counts = []
    enabled = nrt.memsys_stats_enabled()
    nrt.memsys_enable_stats()
    for n in (1, 5000):
        before = rtsys.get_allocation_stats().alloc
        _call_rhs_many(n, *args)
        counts.append(rtsys.get_allocation_stats().alloc - before)
    if not enabled:
        nrt.memsys_disable_stats()
    assert counts[0] == counts[1]
    flexible_rhs_tabulated(0.0, *args)  # from Python too: a nopython signature exists
    assert flexible_rhs_tabulated.nopython_signatures
    assert np.all(np.isfinite(dydt)) and np.all(np.isfinite(aux))


def test_parameters_are_arguments_not_frozen_globals(
    spec: MechanismSpec, geometry: CrankGeometry, omega: float
) -> None:
    """Two parameter arrays in one process give different answers (numba's cache
    would freeze module-level arrays)."""
    par_a = mechanism_parameters(spec, geometry, speed=omega)
    heavy = replace(spec, rotor=replace(spec.rotor, mass=2 * spec.rotor.mass))
    par_b = mechanism_parameters(heavy, geometry, speed=omega)
    y = initial_state(par_a, 0.4, omega, 8e5)
    out = []
    for par in (par_a, par_b):
        dydt, aux = np.zeros(lay.N_STATE), np.zeros(lay.N_AUX)
        flexible_rhs(0.0, y, dydt, aux, par, 8e5, NO_TABLE, NO_TABLE, NO_TABLE)
        out.append(dydt[lay.Y_ROTOR_VX])
    assert out[0] == pytest.approx(2 * out[1], rel=1e-12)


@pytest.mark.parametrize("theta", [0.0, 0.7, 2.0, 3.5, 5.5])
def test_initial_state_carries_the_pinned_reactions(
    spec: MechanismSpec, geometry: CrankGeometry, omega: float, theta: float
) -> None:
    """The quasi-static start deflects every bearing by -F_pinned / k: the elastic
    forces equal the pinned reactions to 1e-6 of the largest (small-tilt
    approximations in the placement are second order)."""
    undamped = with_damping(spec, 0.0)
    par = mechanism_parameters(undamped, geometry, shell_pressure=1.15e5, speed=omega)
    p = 12e5
    y = initial_state(par, theta, omega, p)
    aux = np.zeros(lay.N_AUX)
    flexible_outputs(0.0, y, aux, par, p, NO_TABLE, NO_TABLE, NO_TABLE)
    ref = np.zeros(N_PIN_OUT)
    pinned_reactions(theta, omega, 0.0, p, par, ref)
    forces = aux[lay.A_BEARING_FORCE : lay.A_BEARING_FORCE + 18]
    scale = np.abs(ref[:18]).max()
    np.testing.assert_allclose(forces, ref[:18], atol=1e-6 * scale)
    # and without deflection nothing is loaded
    y0 = initial_state(par, theta, omega, p, static_deflection=False)
    flexible_outputs(0.0, y0, aux, par, p, NO_TABLE, NO_TABLE, NO_TABLE)
    assert np.abs(aux[lay.A_BEARING_FORCE : lay.A_BEARING_FORCE + 18]).max() < 1e-9 * scale


def test_state_accessors_and_piston_outputs(
    spec: MechanismSpec, geometry: CrankGeometry, omega: float
) -> None:
    """On the rigid pose the piston reads the slider-crank x, dx/dt; lateral offset and
    tilt follow the states; aux agrees with the accessors."""
    par = mechanism_parameters(spec, geometry, speed=omega)
    r, big_l = geometry.crank_radius, geometry.rod_length
    for th in (0.0, 1.0, 2.5, 4.0):
        y = initial_state(par, th, omega, static_deflection=False)
        x, v = piston_axial_displacement(y, par)
        xk, dxk, _ = piston_displacement(th, r, big_l)
        assert x == pytest.approx(xk, abs=1e-15)
        assert v == pytest.approx(dxk * omega, rel=1e-12, abs=1e-12)
    y = initial_state(par, 1.0, omega, static_deflection=False)
    y[lay.Y_PISTON_Y] = 3e-6
    y[lay.Y_PISTON_TILT] = 2e-4
    y[lay.Y_PISTON_DX] = -1e-6
    u_crown = spec.piston.centre_of_mass_from_crown
    assert piston_lateral_offset(y, par, 0.0) == pytest.approx(3e-6 + u_crown * math.sin(2e-4))
    assert piston_lateral_offset(y, par, spec.piston.length) == pytest.approx(
        3e-6 + (u_crown - spec.piston.length) * math.sin(2e-4)
    )
    assert piston_tilt(y) == 2e-4
    aux = np.zeros(lay.N_AUX)
    flexible_outputs(0.0, y, aux, par, 1.15e5, NO_TABLE, NO_TABLE, NO_TABLE)
    x, v = piston_axial_displacement(y, par)
    assert aux[lay.A_PISTON_DISPLACEMENT] == pytest.approx(x, abs=1e-15)
    assert aux[lay.A_PISTON_SPEED] == pytest.approx(v, rel=1e-12)
    drop = u_crown * (1.0 - math.cos(2e-4))  # the tilted crown centre moves down
    assert x == pytest.approx(piston_displacement(1.0, r, big_l)[0] + 1e-6 + drop, abs=1e-15)
    assert aux[lay.A_PISTON_LATERAL] == 3e-6 and aux[lay.A_PISTON_TILT] == 2e-4


def _integrate_with_work(
    par: np.ndarray,
    y0: np.ndarray,
    t_end: float,
    curve: PressureCurve,
    drive_angles: np.ndarray,
    drive_torques: np.ndarray,
    rtol: float,
) -> tuple[np.ndarray, np.ndarray]:
    """Integrate the RHS plus W' = P_drive + P_gas - P_bearings; return (t, aux rows)
    at 400 instants, with W appended as the last column."""
    dydt, aux = np.zeros(lay.N_STATE), np.zeros(lay.N_AUX)
    pa, pp = curve.crank_angle, curve.pressure

    def fun(t: float, z: np.ndarray) -> np.ndarray:
        flexible_rhs_tabulated(
            t, z[:-1], dydt, aux, par, pa, pp, drive_angles, drive_torques, NO_TABLE
        )
        power = aux[lay.A_DRIVE_POWER] + aux[lay.A_GAS_POWER] - aux[lay.A_BEARING_POWER]
        return np.append(dydt, power)

    atol = np.append(rtol * state_scales(par), rtol * 1e-3)
    t_eval = np.linspace(0.0, t_end, 400)
    sol = solve_ivp(
        fun,
        (0.0, t_end),
        np.append(y0, 0.0),
        "DOP853",
        t_eval=t_eval,
        rtol=rtol,
        atol=atol,
        first_step=1e-6 * t_end,
    )
    assert sol.success
    rows = []
    for k in range(sol.t.size):
        fun(sol.t[k], sol.y[:, k])
        rows.append(np.append(aux.copy(), sol.y[-1, k]))
    return sol.t, np.array(rows)


def _energy(rows: np.ndarray) -> np.ndarray:
    return (
        rows[:, lay.A_KINETIC_ENERGY_ROTOR]
        + rows[:, lay.A_KINETIC_ENERGY_ROD]
        + rows[:, lay.A_KINETIC_ENERGY_PISTON]
        + rows[:, lay.A_SPRING_ENERGY]
    )


def test_free_undamped_mechanism_conserves_energy(
    spec: MechanismSpec, geometry: CrankGeometry, omega: float
) -> None:
    """No damping, no gas load, spin free (zero drive torque): kinetic + spring energy
    is constant over 4 revolutions while energy flows between the spin (the crank
    speed swings by ~1 %), the rod and piston motion and the springs.

    Measured drift at rtol 1e-10 (DOP853): 2e-13 J against 0.3 J of energy exchanged;
    the tolerance, 1e-9 of the exchanged energy, leaves a factor 1000 for platforms."""
    undamped = with_damping(spec, 0.0)
    par = mechanism_parameters(
        undamped, geometry, shell_pressure=1.15e5, speed=omega, drive="torque_profile"
    )
    flat = PressureCurve(np.array([0.0, 2.0, 4.0]), np.full(3, 1.15e5))
    y0 = initial_state(par, 0.0, omega, 1.15e5)
    y0[lay.Y_ROTOR_VX] = 0.02  # kick the rotor so that every mode swings
    zero = (np.array([0.0]), np.array([0.0]))
    t, rows = _integrate_with_work(par, y0, 4 * 2 * math.pi / omega, flat, *zero, rtol=1e-10)
    energy = _energy(rows)
    exchanged = np.ptp(rows[:, lay.A_KINETIC_ENERGY_ROTOR])
    assert exchanged > 1e-2  # the test exercises something
    assert np.ptp(rows[:, lay.A_SPRING_ENERGY]) > 1e-4
    assert np.abs(energy - energy[0]).max() < 1e-9 * exchanged
    speed = rows[:, lay.A_CRANK_SPEED]
    assert np.ptp(speed) > 1e-3 * omega  # the spin is really free


def test_energy_balance_with_damping_gas_and_drive(
    spec: MechanismSpec, geometry: CrankGeometry, omega: float, curve: PressureCurve
) -> None:
    """KE(t) - KE(0) = integral of (drive power + gas power - bearing power), with
    every term active (constant speed drive, gas, damping), over two revolutions.
    Kinetic energy only: the bearing power includes the springs' energy rate. Checks
    the torque, gas power and bearing power outputs against the motion. Measured
    residual 5e-14 J on a 34 J throughput; tolerance 1e-9 of the throughput."""
    par = mechanism_parameters(spec, geometry, shell_pressure=1.15e5, speed=omega)
    y0 = initial_state(par, 0.0, omega, curve(0.0)[0])
    t, rows = _integrate_with_work(
        par, y0, 2 * 2 * math.pi / omega, curve, NO_TABLE, NO_TABLE, rtol=1e-10
    )
    work = rows[:, -1]
    throughput = np.abs(np.diff(work)).sum() + np.abs(rows[:, lay.A_GAS_POWER]).max() * t[-1]
    assert np.abs(rows[:, lay.A_DRIVE_TORQUE]).max() > 1.0
    residual = (_energy_kinetic(rows) - _energy_kinetic(rows)[0]) - work
    assert np.abs(residual).max() < 1e-9 * throughput
    assert np.ptp(work) > 0.1  # real energy flows


def _energy_kinetic(rows: np.ndarray) -> np.ndarray:
    return (
        rows[:, lay.A_KINETIC_ENERGY_ROTOR]
        + rows[:, lay.A_KINETIC_ENERGY_ROD]
        + rows[:, lay.A_KINETIC_ENERGY_PISTON]
    )
