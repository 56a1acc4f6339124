"""The undamped runs of the paper's study: periodic response at constant speed, by shooting.

Undamped flexible bearings never settle by running revolutions (Floquet multipliers of
modulus 1); their periodic forced response is found by Newton
(:func:`recipsim.solve.newton.newton_fixed_point`) on the one-revolution map of the
``solve_ivp`` driver :mod:`recipsim.solve.mechanism_ivp`, started at TDC (used by
:func:`recipsim.studies.paper.run_paper_study`).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from scipy.integrate import solve_ivp

from recipsim.case.mechanism_spec import CrankGeometry, MechanismSpec
from recipsim.model.mechanism_parameters import mechanism_parameters
from recipsim.physics.mechanics import layout as lay
from recipsim.physics.mechanics.flexible import flexible_rhs_tabulated
from recipsim.physics.mechanics.flexible_setup import initial_state, state_scales
from recipsim.physics.mechanics.tabulated import tabulated_pressure
from recipsim.solve.mechanism_ivp import MechanismResult, simulate_mechanism
from recipsim.solve.newton import newton_fixed_point

#: Finite-difference step of the undamped shooting, relative to each state's size.
_FD_STEP = 0.2


def undamped_periodic_response(
    spec: MechanismSpec,
    geometry: CrankGeometry,
    pressure_angles: np.ndarray,
    pressures: np.ndarray,
    shell_pressure: float,
    omega: float,
    *,
    rtol: float = 1e-6,
    method: str = "LSODA",
    samples_per_revolution: int = 360,
    periodic_tolerance: float = 1e-3,
    max_revolutions: int = 60,
) -> MechanismResult:
    """Periodic response of the flexible mechanism at constant speed, by shooting.

    See :func:`undamped_periodic` (which also returns the Jacobian, for reuse).
    """
    return undamped_periodic(
        spec,
        geometry,
        pressure_angles,
        pressures,
        shell_pressure,
        omega,
        rtol=rtol,
        method=method,
        samples_per_revolution=samples_per_revolution,
        periodic_tolerance=periodic_tolerance,
        max_revolutions=max_revolutions,
    )[0]


def undamped_periodic(
    spec: MechanismSpec,
    geometry: CrankGeometry,
    pressure_angles: np.ndarray,
    pressures: np.ndarray,
    shell_pressure: float,
    omega: float,
    *,
    rtol: float,
    method: str,
    samples_per_revolution: int,
    periodic_tolerance: float,
    max_revolutions: int,
    jacobian: tuple[np.ndarray, np.ndarray] | None = None,
) -> tuple[MechanismResult, tuple[np.ndarray, np.ndarray] | None]:
    """Periodic response of the flexible mechanism at constant speed, by shooting.

    Newton (:func:`recipsim.solve.newton.newton_fixed_point`) on the map from the
    state at TDC to the state one revolution later (``solve_ivp`` with ``method`` at
    ``rtol``, absolute tolerances ``rtol`` times :func:`state_scales`), over every state
    but the crank angle and speed (prescribed), from the quasi-static pose; finite
    differences of a fifth of each state's size over the revolution (the map is nearly
    linear in the deflections). It works whatever the damping, undamped included,
    unless a forcing harmonic sits exactly on a natural frequency. The reported
    revolution is integrated once more from the periodic state by
    :func:`recipsim.physics.mechanics.simulate_mechanism`, whose periodicity test (the largest
    state change over it relative to the state's size, below ``periodic_tolerance``)
    decides ``converged``.

    Parameters
    ----------
    spec : MechanismSpec
        The mechanism (its bearings' damping as given; zero for the paper's study).
    geometry : CrankGeometry
    pressure_angles, pressures : numpy.ndarray
        Periodic cylinder pressure table [rad], [Pa].
    shell_pressure : float
        [Pa].
    omega : float
        Crank speed [rad/s].
    rtol : float
        Relative tolerance of the integration [-].
    method : str
        ``solve_ivp`` method.
    samples_per_revolution : int
        Samples of the reported revolution.
    periodic_tolerance : float
        Periodicity tolerance [-]; Newton aims at half of it.
    max_revolutions : int
        Revolutions the shooting may integrate (a Jacobian costs 20).

    jacobian : (numpy.ndarray, numpy.ndarray), optional
        Scaled Jacobian and its scales from a run of the same mechanism and speed:
        at constant speed the pressure table only adds a forcing, so the map's linear
        part is the same for every load and the Jacobian carries over.

    Returns
    -------
    MechanismResult
        The periodic revolution; ``revolutions`` and ``nfev`` count the shooting's too.
    (numpy.ndarray, numpy.ndarray) or None
        The Jacobian and its scales, for the next load.

    Raises
    ------
    RuntimeError
        If the reported revolution fails to integrate.
    """
    pa = np.ascontiguousarray(pressure_angles, dtype=float)
    pp = np.ascontiguousarray(pressures, dtype=float)
    par = mechanism_parameters(
        spec, geometry, shell_pressure=shell_pressure, speed=omega, drive="constant_speed"
    )
    scales = state_scales(par)
    period = 2.0 * math.pi / omega
    no_drive = np.zeros(1)
    dydt = np.zeros(lay.N_STATE)
    aux = np.zeros(lay.N_AUX)

    def fun(t: float, state: np.ndarray) -> np.ndarray:
        flexible_rhs_tabulated(t, state, dydt, aux, par, pa, pp, no_drive, no_drive, no_drive)
        return dydt.copy()

    y0 = initial_state(par, 0.0, omega, tabulated_pressure(0.0, pa, pp))
    fixed = (lay.Y_CRANK_ANGLE, lay.Y_CRANK_SPEED)
    idx = np.array([i for i in range(lay.N_STATE) if i not in fixed])
    nfev = 0

    def one_revolution(z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        nonlocal nfev
        y = y0.copy()
        y[idx] = z
        sol = solve_ivp(
            fun,
            (0.0, period),
            y,
            method=method,
            rtol=rtol,
            atol=rtol * scales,
            dense_output=True,
            first_step=1e-5 * period,
        )
        if not sol.success:
            raise RuntimeError(f"integration failed: {sol.message}")
        nfev += sol.nfev
        return sol.y[idx, -1].copy(), sol.sol(np.linspace(0.0, period, 64))

    def change(z: np.ndarray, g: np.ndarray, samples: np.ndarray) -> float:
        # simulate_mechanism's periodicity measure
        size = np.maximum(np.abs(samples).max(axis=1), scales)[idx]
        return float(np.max(np.abs(g - z) / size))

    z = y0[idx]
    g, samples = one_revolution(z)
    ref = np.maximum(np.abs(samples).max(axis=1), scales)[idx] if jacobian is None else jacobian[1]
    result = newton_fixed_point(
        one_revolution,
        z,
        (g, samples),
        ref,
        np.full(idx.size, _FD_STEP),
        lambda zz, gg, smp: change(zz, gg, smp) < 0.5 * periodic_tolerance,
        max(max_revolutions - 1, 0),
        jacobian=None if jacobian is None else jacobian[0],
        failures=(RuntimeError,),
    )
    start = y0.copy()
    start[idx] = result.z
    final = simulate_mechanism(
        spec,
        geometry,
        pa,
        pp,
        shell_pressure,
        omega,
        drive="constant_speed",
        revolutions=1,
        rtol=rtol,
        method=method,
        samples_per_revolution=samples_per_revolution,
        y0=start,
    )
    periodic = replace(
        final,
        revolutions=2 + result.evaluations,
        converged=bool(final.cycle_change < periodic_tolerance),
        nfev=final.nfev + nfev,
    )
    return periodic, None if result.jacobian is None else (result.jacobian, ref)
