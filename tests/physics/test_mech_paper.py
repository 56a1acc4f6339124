"""Limits and the paper's qualitative results (Kurka et al., ISMA 2010, Table 1), with
the reference compressor and the smoothed ideal-cycle test curve (conftest).

Measured RMS loads [N] (primary, secondary, eccentric, pin, piston_top, piston_skirt):
pinned 261.2 / 100.5 / 160.7 / 170.9 / 7.45 / 7.45; damped flexible +1.8 / +4.1 /
+0.4 / +0.2 / +0.2 / +0.2 %; undamped from the unloaded pose +92 / +340 / +86 / +53 /
+252 / +252 % (the paper: +35 / +114 / +21 / +46 / +87 %).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from recipsim.case.load import Case, load_case
from recipsim.case.mechanism_spec import CrankGeometry, MechanismSpec, scale_bearings, with_damping
from recipsim.model.pinned import pinned_loads
from recipsim.physics.mechanics.layout import BEARING_NAMES
from recipsim.physics.mechanics.pinned import PinnedLoads
from recipsim.physics.mechanics.tabulated import PressureCurve
from recipsim.studies.paper_linear_runs import tdc_start
from recipsim.studies.paper_load_run import LoadRun, solve_load, tabulated_case


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


@pytest.fixture(scope="module")
def case(spec: MechanismSpec, shell_pressure: float, omega: float) -> Case:
    """The reference crank train as a case (``paper_tabulated`` at constant speed)."""
    case = load_case(
        "paper_tabulated",
        {"operating_point.shell_pressure": shell_pressure, "options.drive": "constant_speed"},
    )
    assert repr(case.mechanism) == repr(spec)
    assert case.operating_point.shaft_speed == pytest.approx(omega, rel=1e-15)
    return case


def run(
    case: Case,
    curve: PressureCurve,
    mechanism: MechanismSpec | None = None,
    revolutions: int | None = None,
    unloaded: bool = False,
    **changes: object,
) -> LoadRun:
    """``case`` under ``curve`` (with ``mechanism``), solved by the compiled scene and
    the periodic solver (rtol 1e-7, DOPRI5): until periodic (cycle tolerance 1e-3), or
    exactly ``revolutions`` from the quasi-static pose at 270 deg (or, ``unloaded``, the
    undeflected pose at TDC)."""
    settings: dict[str, object] = {
        "solver.rtol": 1e-7,
        "solver.method": "dopri5",
        "solver.periodic": "revolutions",
        "solver.cycle_tolerance": 1e-3,
        "solver.max_revolutions": 30,
        "solver.samples_per_revolution": 360,
    }
    if revolutions is not None:
        settings["solver.min_revolutions"] = settings["solver.max_revolutions"] = revolutions
    settings.update({f"solver.{k}" if "." not in k else k: v for k, v in changes.items()})
    run_case = tabulated_case(case, curve, settings)
    if mechanism is not None:
        run_case = replace(run_case, mechanism=mechanism)
    return solve_load("gas", run_case, tdc_start(curve, deflected=False) if unloaded else None)


def columns(result: LoadRun, kind: str) -> np.ndarray:
    """(n, 6, 3) ``bearing_<kind>_<name>_x|y|z`` of the cycle table (``force`` [N] or
    ``displacement`` [m]; a case's table has no axial displacement: zero)."""
    unit = "N" if kind == "force" else "m"
    table = result.cycle
    zero = np.zeros(len(table))
    cols = [f"bearing_{kind}_{b}_{a} [{unit}]" for b in BEARING_NAMES for a in "xyz"]
    data = np.stack([table[c].to_numpy() if c in table else zero for c in cols], axis=1)
    return data.reshape(-1, len(BEARING_NAMES), 3)


@pytest.fixture(scope="module")
def damped(case: Case, curve: PressureCurve) -> LoadRun:
    return run(case, curve)


def deviation(result: LoadRun, pinned: PinnedLoads) -> np.ndarray:
    return np.abs(result.force_rms / pinned.force_rms() - 1.0)


def test_rigid_limit(
    spec: MechanismSpec,
    case: Case,
    curve: PressureCurve,
    pinned: PinnedLoads,
    damped: LoadRun,
) -> None:
    """Every stiffness x10, x100, x1000 (damping x sqrt, same damping ratios): the
    RMS and peak loads tend to the pinned ones, within 2 % at x100, and the largest
    deviation shrinks at every step (measured 4.1 %, 0.33 %, 0.031 %, 0.0023 %: about
    1/k, the quasi-static amplification (omega_harmonic / omega_bearing)^2).
    x1000 is stiff (max|lambda| T ~ 2e4): DOPRI5 switching to the Rosenbrock-W step."""
    deviations = [deviation(damped, pinned).max()]
    for factor in (10.0, 100.0, 1000.0):
        method = "dopri5_stiff" if factor > 100 else "dopri5"
        result = run(
            case,
            curve,
            scale_bearings(spec, factor),
            revolutions=2,
            method=method,
            rtol=1e-8,
        )
        deviations.append(deviation(result, pinned).max())
        if factor >= 100:
            assert deviations[-1] < 0.02
            peak = np.abs(result.force_peak / pinned.force_peak() - 1.0)
            assert peak.max() < 0.02
    assert all(b < 0.5 * a for a, b in zip(deviations, deviations[1:], strict=False)), deviations


def test_damped_loads_are_close_to_pinned(
    spec: MechanismSpec, damped: LoadRun, pinned: PinnedLoads
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
    force, displacement = columns(damped, "force"), columns(damped, "displacement")
    elastic = -k[None, :, None] * displacement
    viscous = force - elastic
    ratio = np.sqrt((viscous**2).sum(2).mean(0) / (elastic**2).sum(2).mean(0))
    assert np.all(ratio < 0.2) and np.all(ratio > 0.005)
    cols = damped.cycle
    np.testing.assert_allclose(cols["crank_angle [deg]"], np.arange(360.0), atol=1e-9)
    primary = force[:, BEARING_NAMES.index("primary")]
    np.testing.assert_allclose(cols["bearing_force_primary [N]"], np.linalg.norm(primary, axis=1))


def test_undamped_loads_exceed_pinned_and_orbits_stay_bounded(
    spec: MechanismSpec, case: Case, curve: PressureCurve, pinned: PinnedLoads
) -> None:
    """No damping, started like the paper from the unloaded pinned pose: every RMS
    load is at least 10 % above pinned (measured +53 % to +340 %); the free
    vibration neither decays nor grows: the largest orbit of revolution 6 is within
    25 % of that of revolution 3."""
    undamped = with_damping(spec, 0.0)
    third = run(case, curve, undamped, revolutions=3, unloaded=True)
    assert np.all(third.force_rms > 1.1 * pinned.force_rms())
    sixth = run(case, curve, undamped, revolutions=6, unloaded=True)
    assert not sixth.converged
    ratio = sixth.orbit_radius_max / third.orbit_radius_max
    assert np.all(ratio < 1.25) and np.all(ratio > 0.5)


def test_torque_profile_drive_reproduces_the_constant_speed_run(
    case: Case, curve: PressureCurve, omega: float, pinned: PinnedLoads, damped: LoadRun
) -> None:
    """The paper's set-up: the pinned driving torque drives the flexible model with a
    free crank speed. The speed stays within 0.1 % of nominal (measured -0.02 %: the
    bearings dissipate what the pinned torque does not supply) and the loads match
    the constant-speed run within 0.5 % (RMS) and the pinned ones within 5 %."""
    result = run(case, curve, revolutions=3, **{"options.drive": "torque_profile"})
    speed = result.cycle["crank_speed [rad/s]"].to_numpy()
    assert np.abs(speed / omega - 1.0).max() < 1e-3
    assert np.ptp(speed) > 0.0
    np.testing.assert_allclose(result.force_rms, damped.force_rms, rtol=5e-3)
    assert deviation(result, pinned).max() < 0.05
    # samples are at equal crank-angle steps over exactly one revolution
    angle = np.radians(result.cycle["crank_angle [deg]"].to_numpy())
    steps = np.diff(angle)
    np.testing.assert_allclose(steps, 2 * math.pi / angle.size, rtol=1e-6)
