"""Pinned mechanism: slider-crank kinematics, torque, and Newton-Euler balances."""

from __future__ import annotations

import math

import numpy as np
import pytest

from recipsim.case.mechanism_spec import CrankGeometry, MechanismSpec
from recipsim.model.mechanism_parameters import mechanism_parameters
from recipsim.model.pinned import pinned_loads
from recipsim.physics.kinematics import (
    inertia_torque,
    piston_displacement,
    rod_angle,
    rod_centre_of_mass,
)
from recipsim.physics.mechanics.layout import BEARING_NAMES
from recipsim.physics.mechanics.pinned import (
    N_PIN_OUT,
    PIN_DRIVE_TORQUE,
    PIN_GAS_TORQUE,
    pinned_reactions,
)
from recipsim.physics.mechanics.tabulated import (
    PressureCurve,
    ideal_cycle_indicated_work,
    ideal_cycle_pressure_curve,
)

SHELL_PRESSURE = 1.15e5  # [Pa], as the conftest's shell_pressure

ANGLES = np.linspace(0.0, 2 * math.pi, 37)


def test_slider_crank_kinematics_closed_form_and_finite_differences(
    geometry: CrankGeometry,
) -> None:
    """x, dx/dtheta, d2x/dtheta2 and the rod angle against the geometry and central
    differences (h = 1e-4 rad: truncation ~h^2 x''' ~ 1e-10 m, far below 1e-7 rel)."""
    r, big_l = geometry.crank_radius, geometry.rod_length
    h = 1e-4
    for th in ANGLES:
        x, dx, d2x = piston_displacement(th, r, big_l)
        x_pin = r * math.cos(th) + math.sqrt(big_l**2 - (r * math.sin(th)) ** 2)
        assert x == pytest.approx(r + big_l - x_pin, abs=1e-15)
        xp, xm = piston_displacement(th + h, r, big_l)[0], piston_displacement(th - h, r, big_l)[0]
        assert dx == pytest.approx((xp - xm) / (2 * h), abs=1e-7 * r)
        assert d2x == pytest.approx((xp - 2 * x + xm) / h**2, abs=1e-6 * r)
        phi, dphi, d2phi = rod_angle(th, r, big_l)
        assert math.sin(phi) == pytest.approx(-r / big_l * math.sin(th), abs=1e-15)
        pp, pm = rod_angle(th + h, r, big_l)[0], rod_angle(th - h, r, big_l)[0]
        assert dphi == pytest.approx((pp - pm) / (2 * h), abs=1e-7)
        assert d2phi == pytest.approx((pp - 2 * phi + pm) / h**2, abs=1e-6)
        # rod ends: big end on the crank pin, small end on the piston pin
        gx, gy, *_ = rod_centre_of_mass(th, r, big_l, 0.35)
        assert gx - 0.35 * big_l * math.cos(phi) == pytest.approx(r * math.cos(th), abs=1e-15)
        assert gy - 0.35 * big_l * math.sin(phi) == pytest.approx(r * math.sin(th), abs=1e-15)


def test_torque_is_inertia_torque_minus_gas_torque(
    spec: MechanismSpec, geometry: CrankGeometry, omega: float, curve: PressureCurve
) -> None:
    """Newton-Euler torque = energy-method inertia torque - (p - p_shell) A dx/dtheta.

    The two are derived independently (reactions vs power balance), so they agree to
    round-off: 1e-9 of the torque range."""
    loads = pinned_loads(
        spec,
        geometry,
        ANGLES,
        omega,
        pressure_angles=curve.crank_angle,
        pressures=curve.pressure,
        shell_pressure=SHELL_PRESSURE,
    )
    r, big_l, area = geometry.crank_radius, geometry.rod_length, geometry.piston_area
    p = curve(ANGLES)
    rod, piston = spec.connecting_rod, spec.piston
    scale = np.abs(loads.drive_torque).max()
    for i, th in enumerate(ANGLES):
        dx = piston_displacement(th, r, big_l)[1]
        gas = (p[i] - SHELL_PRESSURE) * area * dx
        assert loads.gas_torque[i] == pytest.approx(gas, abs=1e-9 * scale)
        inertia = inertia_torque(
            th, omega, r, big_l, piston.mass, rod.mass, rod.centre_of_mass_fraction, rod.inertia
        )
        assert loads.drive_torque[i] == pytest.approx(inertia - gas, abs=1e-9 * scale)
        assert loads.piston_displacement[i] == pytest.approx(
            piston_displacement(th, r, big_l)[0], abs=1e-15
        )


def test_mean_driving_power_is_indicated_power(
    spec: MechanismSpec, geometry: CrankGeometry, omega: float
) -> None:
    """mean(torque) * omega = (-closed integral p dV) / T for the sharp ideal cycle.

    The closed-form work is of the exact curve; the table has 20000 points and the
    mean uses 40000 angles, so interpolation and quadrature errors are ~1e-6 (tolerance
    1e-4). The inertia torque averages to zero over a revolution."""
    r, big_l, area = geometry.crank_radius, geometry.rod_length, geometry.piston_area
    table = ideal_cycle_pressure_curve(r, big_l, n_points=20_000)
    theta = np.linspace(0.0, 2 * math.pi, 40_000, endpoint=False)
    loads = pinned_loads(
        spec,
        geometry,
        theta,
        omega,
        pressure_angles=table.crank_angle,
        pressures=table.pressure,
        shell_pressure=SHELL_PRESSURE,
    )
    work = ideal_cycle_indicated_work(r, area)
    period = 2 * math.pi / omega
    assert loads.drive_torque.mean() * omega == pytest.approx(work / period, rel=1e-4)
    no_gas = pinned_loads(spec, geometry, theta, omega, shell_pressure=SHELL_PRESSURE)
    assert abs(no_gas.drive_torque.mean()) < 1e-9 * np.abs(no_gas.drive_torque).max()


def test_reactions_satisfy_newton_euler_body_by_body_and_globally(
    spec: MechanismSpec, geometry: CrankGeometry, omega: float, curve: PressureCurve
) -> None:
    """Forces and moments on rotor, rod, piston and on the whole mechanism balance the
    kinematic accelerations (tolerance 1e-9 of the largest force / moment)."""
    loads = pinned_loads(
        spec,
        geometry,
        ANGLES,
        omega,
        pressure_angles=curve.crank_angle,
        pressures=curve.pressure,
        shell_pressure=SHELL_PRESSURE,
    )
    r, big_l = geometry.crank_radius, geometry.rod_length
    rod, piston, rotor = spec.connecting_rod, spec.piston, spec.rotor
    a = rod.centre_of_mass_fraction
    z1, z2 = rotor.primary_z, rotor.secondary_z
    top = spec.bearing("piston_top").position_from_crown
    skirt = spec.bearing("piston_skirt").position_from_crown
    assert top is not None and skirt is not None
    f = {name: loads.force(name) for name in BEARING_NAMES}
    tol_f = 1e-9 * np.abs(loads.bearing_force).max()
    tol_m = tol_f * 0.1
    w2 = omega**2
    for i, th in enumerate(ANGLES):
        x, dx, d2x = piston_displacement(th, r, big_l)
        phi, dphi, d2phi = rod_angle(th, r, big_l)
        gx, gy, _, _, d2gx, d2gy = rod_centre_of_mass(th, r, big_l, a)
        gas = loads.gas_force[i]
        # rotor: no acceleration of its centre of mass, no moment about X, Y, torque on Z
        s = f["primary"][i] + f["secondary"][i] + f["eccentric"][i]
        np.testing.assert_allclose(s, 0.0, atol=tol_f)
        mx = -z1 * f["primary"][i, 1] - z2 * f["secondary"][i, 1]
        my = z1 * f["primary"][i, 0] + z2 * f["secondary"][i, 0]
        mz = r * math.cos(th) * f["eccentric"][i, 1] - r * math.sin(th) * f["eccentric"][i, 0]
        assert abs(mx) < tol_m and abs(my) < tol_m
        assert loads.drive_torque[i] + mz == pytest.approx(0.0, abs=tol_m)
        # rod: -F_eccentric - F_pin = m a_G ; moment about G = I phi''
        e = -f["eccentric"][i] - f["pin"][i]
        np.testing.assert_allclose(e[:2], rod.mass * w2 * np.array([d2gx, d2gy]), atol=tol_f)
        big = np.array([r * math.cos(th) - gx, r * math.sin(th) - gy])
        small = np.array([r + big_l - x - gx, -gy])
        fe, fpin = -f["eccentric"][i], -f["pin"][i]
        m_rod = big[0] * fe[1] - big[1] * fe[0] + small[0] * fpin[1] - small[1] * fpin[0]
        assert m_rod == pytest.approx(rod.inertia * w2 * d2phi, abs=tol_m)
        # piston: X and Y balance, moment about the pin zero
        fp = f["pin"][i] + f["piston_top"][i] + f["piston_skirt"][i]
        assert fp[0] + gas == pytest.approx(-piston.mass * w2 * d2x, abs=tol_f)
        assert fp[1] == pytest.approx(0.0, abs=tol_f)
        u_top, u_skirt = piston.pin_offset_from_crown - top, piston.pin_offset_from_crown - skirt
        m_pin = u_top * f["piston_top"][i, 1] + u_skirt * f["piston_skirt"][i, 1]
        assert m_pin == pytest.approx(0.0, abs=tol_m)
        # whole mechanism, moment about the spin axis: torque + external moments
        # = d/dt of the angular momentum of rod and piston (the piston stays on X)
        x_top = r + big_l - x + piston.pin_offset_from_crown - top
        x_skirt = r + big_l - x + piston.pin_offset_from_crown - skirt
        external = x_top * f["piston_top"][i, 1] + x_skirt * f["piston_skirt"][i, 1]
        dh = rod.mass * w2 * (gx * d2gy - gy * d2gx) + rod.inertia * w2 * d2phi
        assert loads.drive_torque[i] + external == pytest.approx(dh, abs=tol_m)
    # no gravity: every Z component is zero
    assert np.all(loads.bearing_force[:, :, 2] == 0.0)
    # the reference geometry splits the eccentric load 1.625 / 0.625 (design notes)
    ratio = np.linalg.norm(f["primary"], axis=1) / np.linalg.norm(f["eccentric"], axis=1)
    np.testing.assert_allclose(ratio, (z2 - 0.0) / (z2 - z1), rtol=1e-12)


def test_crank_acceleration_enters_through_the_power_balance(
    spec: MechanismSpec, geometry: CrankGeometry
) -> None:
    """With a crank acceleration alpha the torque satisfies
    tau omega + (p - p_shell) A dx/dtheta omega = d/dt [ (J(theta) + I_polar) omega^2 / 2 ]
    (driving power plus the gas force's power on the piston),
    J = m_p x'^2 + m_r |G'|^2 + I_r phi'^2 (energy method; tolerance 1e-9)."""
    par = mechanism_parameters(spec, geometry, shell_pressure=SHELL_PRESSURE)
    r, big_l = geometry.crank_radius, geometry.rod_length
    rod, piston = spec.connecting_rod, spec.piston
    out = np.zeros(N_PIN_OUT)
    omega, alpha, p = 300.0, 2.0e4, 8e5
    for th in ANGLES:
        pinned_reactions(th, omega, alpha, p, par, out)
        _, dx, d2x = piston_displacement(th, r, big_l)
        _, _, dgx, dgy, d2gx, d2gy = rod_centre_of_mass(th, r, big_l, rod.centre_of_mass_fraction)
        _, dphi, d2phi = rod_angle(th, r, big_l)
        j = piston.mass * dx**2 + rod.mass * (dgx**2 + dgy**2) + rod.inertia * dphi**2
        dj = 2 * (piston.mass * dx * d2x + rod.mass * (dgx * d2gx + dgy * d2gy))
        dj += 2 * rod.inertia * dphi * d2phi
        ke_rate = (j + spec.rotor.polar_inertia) * omega * alpha + 0.5 * dj * omega**3
        power = (out[PIN_DRIVE_TORQUE] + out[PIN_GAS_TORQUE]) * omega
        assert power == pytest.approx(ke_rate, abs=1e-9 * abs(ke_rate) + 1e-9)


def test_piston_side_force_split_follows_the_lever_arms(
    spec: MechanismSpec, geometry: CrankGeometry, omega: float
) -> None:
    """Pin at the middle of the Gauss points: top and skirt carry half the side force
    each; moving the pin towards the crown loads the top bearing more."""
    from dataclasses import replace

    loads = pinned_loads(spec, geometry, ANGLES, omega)
    np.testing.assert_allclose(
        loads.force("piston_top"), loads.force("piston_skirt"), rtol=1e-12, atol=1e-12
    )
    np.testing.assert_allclose(
        2 * loads.force("piston_top")[:, 1], -loads.force("pin")[:, 1], rtol=1e-12, atol=1e-9
    )
    high_pin = replace(spec, piston=replace(spec.piston, pin_offset_from_crown=0.006))
    shifted = pinned_loads(high_pin, geometry, ANGLES, omega)
    top = np.abs(shifted.force("piston_top")[:, 1])
    skirt = np.abs(shifted.force("piston_skirt")[:, 1])
    assert np.all(top[1:-1] >= skirt[1:-1])
    assert top.sum() > 1.5 * skirt.sum()
