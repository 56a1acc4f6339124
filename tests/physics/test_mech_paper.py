"""Limits and the paper's qualitative results (Kurka et al., ISMA 2010, Table 1), with
the reference compressor and the smoothed ideal-cycle test curve (conftest).

Measured RMS loads [N] (primary, secondary, eccentric, pin, piston_top, piston_skirt):
pinned 261.2 / 100.5 / 160.7 / 170.9 / 7.45 / 7.45; damped flexible +1.8 / +4.1 /
+0.4 / +0.2 / +0.2 / +0.2 %; undamped from the unloaded pose +92 / +340 / +86 / +53 /
+252 / +252 % (the paper: +35 / +114 / +21 / +46 / +87 %).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from recipsim.case.mechanism_spec import CrankGeometry, MechanismSpec, scale_bearings, with_damping
from recipsim.model.mechanism_parameters import mechanism_parameters
from recipsim.model.pinned import pinned_loads
from recipsim.physics.mechanics.flexible_setup import initial_state
from recipsim.physics.mechanics.pinned import PinnedLoads
from recipsim.physics.mechanics.tabulated import PressureCurve
from recipsim.solve.mechanism_ivp import MechanismResult, simulate_mechanism


@pytest.fixture(scope="module")
def pinned(
    spec: MechanismSpec,
    geometry: CrankGeometry,
    omega: float,
    curve: PressureCurve,
    revolution_angles: np.ndarray,
    shell_pressure: float,
) -> PinnedLoads:
    return pinned_loads(
        spec,
        geometry,
        revolution_angles,
        omega,
        pressure_angles=curve.crank_angle,
        pressures=curve.pressure,
        shell_pressure=shell_pressure,
    )


def run(
    spec: MechanismSpec,
    geometry: CrankGeometry,
    omega: float,
    curve: PressureCurve,
    shell_pressure: float,
    **kwargs: object,
) -> MechanismResult:
    options: dict = {"rtol": 1e-7, "method": "RK45"}
    options.update(kwargs)
    return simulate_mechanism(
        spec, geometry, curve.crank_angle, curve.pressure, shell_pressure, omega, **options
    )


@pytest.fixture(scope="module")
def damped(
    spec: MechanismSpec,
    geometry: CrankGeometry,
    omega: float,
    curve: PressureCurve,
    shell_pressure: float,
) -> MechanismResult:
    return run(spec, geometry, omega, curve, shell_pressure)


def deviation(result: MechanismResult, pinned: PinnedLoads) -> np.ndarray:
    return np.abs(result.force_rms / pinned.force_rms() - 1.0)


def test_rigid_limit(
    spec: MechanismSpec,
    geometry: CrankGeometry,
    omega: float,
    curve: PressureCurve,
    shell_pressure: float,
    pinned: PinnedLoads,
    damped: MechanismResult,
) -> None:
    """Every stiffness x10, x100, x1000 (damping x sqrt, same damping ratios): the
    RMS and peak loads tend to the pinned ones, within 2 % at x100, and the largest
    deviation shrinks at every step (measured 4.1 %, 0.33 %, 0.031 %, 0.0023 %: about
    1/k, the quasi-static amplification (omega_harmonic / omega_bearing)^2).
    x1000 is stiff (max|lambda| T ~ 2e4): LSODA, which switches to BDF."""
    deviations = [deviation(damped, pinned).max()]
    for factor in (10.0, 100.0, 1000.0):
        method = "LSODA" if factor > 100 else "RK45"
        result = run(
            scale_bearings(spec, factor),
            geometry,
            omega,
            curve,
            shell_pressure,
            method=method,
            rtol=1e-8,
            revolutions=2,
        )
        deviations.append(deviation(result, pinned).max())
        if factor >= 100:
            assert deviations[-1] < 0.02
            peak = np.abs(result.force_peak / pinned.force_peak() - 1.0)
            assert peak.max() < 0.02
    assert all(b < 0.5 * a for a, b in zip(deviations, deviations[1:], strict=False)), deviations


def test_damped_loads_are_close_to_pinned(
    spec: MechanismSpec, damped: MechanismResult, pinned: PinnedLoads
) -> None:
    """The paper's "parametric dissipation": loads within 5 % of pinned (measured
    +4.1 % on the secondary, the most sensitive as it carries the difference of the
    moments; under 2 % elsewhere), a periodic response within 4 revolutions, orbits
    no larger than 1.25x the quasi-static deflection under the peak pinned load, and
    viscous forces an order of magnitude below the elastic ones (paper, section 4.2;
    measured 0.02-0.10)."""
    assert damped.converged and damped.revolutions <= 4
    assert deviation(damped, pinned).max() < 0.05
    assert np.all(damped.force_rms > pinned.force_rms())  # flexibility adds load
    k = np.array([b.stiffness for b in spec.bearings])
    assert np.all(damped.orbit_radius_max < 1.25 * pinned.force_peak() / k)
    elastic = -k[None, :, None] * damped.bearing_displacement
    viscous = damped.bearing_force - elastic
    ratio = np.sqrt((viscous**2).sum(2).mean(0) / (elastic**2).sum(2).mean(0))
    assert np.all(ratio < 0.2) and np.all(ratio > 0.005)
    cols = damped.columns()
    np.testing.assert_allclose(cols["crank_angle [deg]"], np.arange(360.0), atol=1e-9)
    np.testing.assert_allclose(
        cols["bearing_force_primary [N]"], np.linalg.norm(damped.force("primary"), axis=1)
    )


def test_undamped_loads_exceed_pinned_and_orbits_stay_bounded(
    spec: MechanismSpec,
    geometry: CrankGeometry,
    omega: float,
    curve: PressureCurve,
    shell_pressure: float,
    pinned: PinnedLoads,
) -> None:
    """No damping, started like the paper from the unloaded pinned pose: every RMS
    load is at least 10 % above pinned (measured +53 % to +340 %); the free
    vibration neither decays nor grows: the largest orbit of revolution 6 is within
    25 % of that of revolution 3."""
    undamped = with_damping(spec, 0.0)
    par = mechanism_parameters(undamped, geometry, shell_pressure=shell_pressure, speed=omega)
    y0 = initial_state(par, 0.0, omega, static_deflection=False)
    third = run(undamped, geometry, omega, curve, shell_pressure, revolutions=3, y0=y0)
    assert np.all(third.force_rms > 1.1 * pinned.force_rms())
    sixth = run(undamped, geometry, omega, curve, shell_pressure, revolutions=6, y0=y0)
    assert not sixth.converged
    ratio = sixth.orbit_radius_max / third.orbit_radius_max
    assert np.all(ratio < 1.25) and np.all(ratio > 0.5)


def test_torque_profile_drive_reproduces_the_constant_speed_run(
    spec: MechanismSpec,
    geometry: CrankGeometry,
    omega: float,
    curve: PressureCurve,
    shell_pressure: float,
    pinned: PinnedLoads,
    damped: MechanismResult,
) -> None:
    """The paper's set-up: the pinned driving torque drives the flexible model with a
    free crank speed. The speed stays within 0.1 % of nominal (measured -0.02 %: the
    bearings dissipate what the pinned torque does not supply) and the loads match
    the constant-speed run within 0.5 % (RMS) and the pinned ones within 5 %."""
    result = run(
        spec, geometry, omega, curve, shell_pressure, drive="torque_profile", revolutions=3
    )
    assert np.abs(result.crank_speed / omega - 1.0).max() < 1e-3
    assert np.ptp(result.crank_speed) > 0.0
    np.testing.assert_allclose(result.force_rms, damped.force_rms, rtol=5e-3)
    assert deviation(result, pinned).max() < 0.05
    # samples are at equal crank-angle steps over exactly one revolution
    steps = np.diff(result.crank_angle)
    np.testing.assert_allclose(steps, 2 * math.pi / result.crank_angle.size, rtol=1e-6)
