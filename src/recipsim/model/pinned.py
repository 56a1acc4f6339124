"""Bearing loads and driving torque of the pinned (rigid) crank train by inverse
dynamics: a case's mechanism data and a pressure table to the compiled
:func:`recipsim.physics.mechanics.pinned.pinned_reactions_array`. Nothing is integrated.
"""

from __future__ import annotations

import numpy as np

from recipsim.case.mechanism_spec import CrankGeometry, MechanismSpec
from recipsim.model.mechanism_parameters import mechanism_parameters
from recipsim.physics.mechanics import layout as lay
from recipsim.physics.mechanics.pinned import (
    N_PIN_OUT,
    PIN_DRIVE_TORQUE,
    PIN_GAS_FORCE,
    PIN_GAS_TORQUE,
    PIN_PISTON_DISPLACEMENT,
    PinnedLoads,
    pinned_reactions_array,
)
from recipsim.physics.mechanics.tabulated import tabulated_pressure

TWO_PI = 2.0 * np.pi


def pinned_loads(
    spec: MechanismSpec,
    geometry: CrankGeometry,
    crank_angle: np.ndarray,
    omega: float,
    *,
    pressure_angles: np.ndarray | None = None,
    pressures: np.ndarray | None = None,
    gas_pressure: np.ndarray | None = None,
    shell_pressure: float = 0.0,
) -> PinnedLoads:
    """Bearing loads and driving torque of the rigid mechanism at constant speed.

    Parameters
    ----------
    spec : MechanismSpec
    geometry : CrankGeometry
    crank_angle : numpy.ndarray
        Crank angles from TDC [rad].
    omega : float
        Crank speed [rad/s].
    pressure_angles, pressures : numpy.ndarray, optional
        Tabulated cylinder pressure [Pa] vs crank angle [rad], interpolated periodically.
    gas_pressure : numpy.ndarray, optional
        Cylinder pressure at each crank angle [Pa] (instead of a table). With neither,
        the cylinder is at the shell pressure.
    shell_pressure : float
        Pressure under the piston [Pa].

    Returns
    -------
    PinnedLoads
    """
    thetas = np.ascontiguousarray(crank_angle, dtype=float)
    if gas_pressure is not None:
        p = np.ascontiguousarray(np.broadcast_to(gas_pressure, thetas.shape), dtype=float)
    elif pressure_angles is not None and pressures is not None:
        pa = np.ascontiguousarray(pressure_angles, dtype=float)
        pp = np.ascontiguousarray(pressures, dtype=float)
        p = np.array([tabulated_pressure(t, pa, pp) for t in thetas])
    else:
        p = np.full(thetas.shape, shell_pressure)
    par = mechanism_parameters(spec, geometry, shell_pressure=shell_pressure, speed=omega)
    out = np.zeros((thetas.shape[0], N_PIN_OUT))
    pinned_reactions_array(thetas, omega, p, par, out)
    forces = out[:, : 3 * lay.N_BEARINGS].reshape(-1, lay.N_BEARINGS, 3).copy()
    return PinnedLoads(
        crank_angle=thetas,
        bearing_force=forces,
        drive_torque=out[:, PIN_DRIVE_TORQUE].copy(),
        gas_torque=out[:, PIN_GAS_TORQUE].copy(),
        gas_force=out[:, PIN_GAS_FORCE].copy(),
        piston_displacement=out[:, PIN_PISTON_DISPLACEMENT].copy(),
    )


def pinned_torque_profile(
    spec: MechanismSpec,
    geometry: CrankGeometry,
    pressure_angles: np.ndarray,
    pressures: np.ndarray,
    shell_pressure: float,
    omega: float,
    n_points: int = 720,
) -> tuple[np.ndarray, np.ndarray]:
    """Driving torque of the pinned mechanism at constant speed, as a periodic table.

    Returns
    -------
    angles, torques : numpy.ndarray
        [rad] (0 ... 2 pi, excluded), [N m]; the paper's input to the flexible run.
    """
    theta = np.linspace(0.0, TWO_PI, n_points, endpoint=False)
    loads = pinned_loads(
        spec,
        geometry,
        theta,
        omega,
        pressure_angles=pressure_angles,
        pressures=pressures,
        shell_pressure=shell_pressure,
    )
    return theta, loads.drive_torque
