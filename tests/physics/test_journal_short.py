"""Short journal bearing (Ocvirk, Guembel film) and asperity contact against closed forms,
an independent quadrature of the film in the inertial frame, and the film's balances."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar, root

from recipsim.physics.mechanics.journal import (
    DEFAULT_CONTACT_FILM,
    DEFAULT_CONTACT_STIFFNESS,
    DEFAULT_FRICTION_COEFFICIENT,
    FILM_ECCENTRICITY_CAP,
    bushing_torque,
    journal_contact,
    short_journal_film,
    short_journal_peak_pressure,
)

# reference eccentric bearing (design.md section 4): R, L, c [m], mu [Pa s], omega [rad/s]
R, L, C, MU = 7e-3, 12e-3, 10e-6, 0.006
OMEGA = 3500 * 2 * math.pi / 60


def film(e, v, wj, wb, r=R, length=L, c=C, mu=MU):
    return np.array(short_journal_film(e[0], e[1], v[0], v[1], wj, wb, r, length, c, mu))


def film_by_quadrature(e, v, wj, wb, r=R, length=L, c=C, mu=MU, n=2**17):
    """Force and journal torque from the short-bearing Reynolds equation written in the
    inertial frame (angle alpha from X, no theta0, no A/B), max(p, 0), trapezoid rule.

    Pressure integrated over the length: p(alpha) = -L^3/(12 h^3) (6 mu (wj + wb) dh/dalpha
    + 12 mu dh/dt), h = c - e.n(alpha). Shear on the journal: mu R (wb - wj)/h over the full
    film, minus (h/2) dp/dx from the positive pressure."""
    a = np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    da = 2 * math.pi / n
    cos, sin = np.cos(a), np.sin(a)
    h = c - e[0] * cos - e[1] * sin
    dh_da = e[0] * sin - e[1] * cos
    dh_dt = -(v[0] * cos + v[1] * sin)
    p = -(length**3) / (12 * h**3) * (6 * mu * (wj + wb) * dh_da + 12 * mu * dh_dt)
    p = np.maximum(p, 0.0)
    fx = -r * np.sum(p * cos) * da
    fy = -r * np.sum(p * sin) * da
    couette = mu * r**3 * length * (wb - wj) * np.sum(1.0 / h) * da
    dp_da = (np.roll(p, -1) - np.roll(p, 1)) / (2 * da)
    pressure_shear = -0.5 * r * np.sum(h * dp_da) * da
    return np.array([fx, fy, couette + pressure_shear]), pressure_shear


def random_states(rng, n, eps_max=0.95):
    """Random (e, v, wj, wb), speeds from squeeze-only to rotation-only (log-uniform)."""
    for _ in range(n):
        eps = rng.uniform(0.0, eps_max)
        phi = rng.uniform(-math.pi, math.pi)
        e = C * eps * np.array([math.cos(phi), math.sin(phi)])
        v = C * OMEGA * 10 ** rng.uniform(-3, 2) * rng.normal(size=2)
        wj, wb = OMEGA * rng.choice([0.0, 1.0]) * rng.uniform(-1, 1, size=2)
        yield e, v, wj, wb


def test_film_against_inertial_frame_quadrature_of_positive_pressure():
    """200 random states (30 % without rotation): force and torque within 1e-6 of the
    quadrature; the quadrature's own error (2^17 points, kinks of max(p, 0)) is ~1e-8."""
    rng = np.random.default_rng(1)
    worst = 0.0
    for e, v, wj, wb in random_states(rng, 200):
        got = film(e, v, wj, wb)
        ref, _ = film_by_quadrature(e, v, wj, wb)
        force_scale = max(np.hypot(ref[0], ref[1]), 1e-300)
        worst = max(worst, np.hypot(*(got[:2] - ref[:2])) / force_scale)
        torque_scale = abs(ref[2]) + R * force_scale * C
        assert abs(got[2] - ref[2]) <= 1e-6 * torque_scale
    assert worst < 1e-6


def fixed_pi_film(e, v, wj, wb):
    """The fixed (0, pi) film of the multibody literature (mechanics-notes 2.2)."""
    eps = math.hypot(*e) / C
    ur = e / math.hypot(*e)
    ut = np.array([-ur[1], ur[0]])
    eps_dot = v @ ur / C
    phi_dot = v @ ut / (C * eps)
    wedge = 0.5 * (wj + wb) - phi_dot
    k = MU * R * L**3 / C**2
    s = 1 - eps**2
    fr = -k * (2 * eps**2 * wedge / s**2 + math.pi * (1 + 2 * eps**2) * eps_dot / (2 * s**2.5))
    ft = k * (math.pi * eps * wedge / (2 * s**1.5) + 2 * eps * eps_dot / s**2)
    return fr * ur + ft * ut


def test_fixed_pi_film_is_right_only_without_squeeze():
    """Documents the trap: the fixed film equals the quadrature for pure rotation (1e-6)
    but is off by more than 50 % of the force for a squeeze-dominated state."""
    e = np.array([0.6, 0.3]) * C
    ur = e / np.linalg.norm(e)
    rotation_only = fixed_pi_film(e, np.zeros(2), OMEGA, 0.0)
    ref, _ = film_by_quadrature(e, np.zeros(2), OMEGA, 0.0)
    assert np.linalg.norm(rotation_only - ref[:2]) < 1e-6 * np.linalg.norm(ref[:2])
    v = -3.0 * C * OMEGA * ur  # separating fast: the positive film is away from h_min
    trap = fixed_pi_film(e, v, OMEGA, 0.0)
    ref, _ = film_by_quadrature(e, v, OMEGA, 0.0)
    assert np.linalg.norm(trap - ref[:2]) > 0.5 * np.linalg.norm(ref[:2])
    assert np.linalg.norm(film(e, v, OMEGA, 0.0)[:2] - ref[:2]) < 1e-6 * np.linalg.norm(ref[:2])


def test_pure_squeeze_closed_form():
    """No rotation, radial velocity: F = -(mu R L^3/c^2) eps_dot J02 e_r with
    J02 = [(1+2eps^2)(pi +- 2 asin eps) +- 6 eps sqrt(1-eps^2)] / (2 (1-eps^2)^(5/2))
    (+ approaching, - separating), no tangential force; at e = 0 the damper -pi mu R L^3
    v/(2 c^3). Rounding only: 1e-12."""
    k = MU * R * L**3 / C**2
    for eps in (0.0, 0.3, 0.7, 0.95):
        for sign in (1.0, -1.0):
            ur = np.array([math.cos(0.4), math.sin(0.4)])
            e = eps * C * ur
            eps_dot = sign * 50.0
            f = film(e, eps_dot * C * ur, 0.0, 0.0)
            s = math.sqrt(1 - eps**2)
            j02 = (
                (1 + 2 * eps**2) * (math.pi + sign * 2 * math.asin(eps)) + sign * 6 * eps * s
            ) / (2 * s**5)
            expected = -k * eps_dot * j02 * ur
            assert np.allclose(f[:2], expected, rtol=1e-12, atol=1e-12 * abs(expected).max())
    v = np.array([0.02, -0.01])
    f = film(np.zeros(2), v, 0.0, 0.0)
    assert np.allclose(f[:2], -math.pi * MU * R * L**3 * v / (2 * C**3), rtol=1e-12)


def test_half_speed_whirl_carries_no_load():
    """Circular whirl at half the journal speed (fixed bushing): A = B = 0, no force
    (rounding: below 1e-9 of the steady load at the same eps)."""
    for eps in (0.2, 0.6, 0.9):
        e = eps * C * np.array([math.cos(1.1), math.sin(1.1)])
        v = 0.5 * OMEGA * np.array([-e[1], e[0]])
        whirl = film(e, v, OMEGA, 0.0)
        steady = film(e, np.zeros(2), OMEGA, 0.0)
        assert np.hypot(*whirl[:2]) < 1e-9 * np.hypot(*steady[:2])


def steady_load(eps, omega=OMEGA):
    """Closed-form load of a fixed-bushing short bearing (notes 2.2) [N]."""
    return (
        MU * omega * R * L**3 / (4 * C**2) * eps
        * math.sqrt(math.pi**2 * (1 - eps**2) + 16 * eps**2) / (1 - eps**2) ** 2
    )  # fmt: skip


def test_static_load_eccentricity_and_attitude_against_sommerfeld():
    """For loads 20 N .. 5 kN: eps from the film (root in eps) against the load formula and
    Friswell's quartic, attitude angle against tan psi = pi sqrt(1-eps^2)/(4 eps);
    1e-6 relative (the roots are converged to 1e-14)."""
    for load in (20.0, 200.0, 600.0, 5000.0):

        def residual(eps, load=load):
            return np.hypot(*film(np.array([eps * C, 0.0]), np.zeros(2), OMEGA, 0.0)[:2]) - load

        eps = brentq(residual, 1e-9, FILM_ECCENTRICITY_CAP, xtol=1e-15, rtol=1e-15)
        assert steady_load(eps) == pytest.approx(load, rel=1e-6)
        ss = 2 * R * OMEGA * MU * L**3 / (8 * C**2 * load)
        roots = np.roots([1, -4, 6 - ss**2 * (16 - math.pi**2), -(4 + math.pi**2 * ss**2), 1])
        x = [r.real for r in roots if abs(r.imag) < 1e-12 and 0 < r.real < 1]
        assert len(x) == 1
        assert eps == pytest.approx(math.sqrt(x[0]), rel=1e-6)
        fx, fy, _ = film(np.array([eps * C, 0.0]), np.zeros(2), OMEGA, 0.0)
        # the load on the journal is -F; e (along X) leads it by psi in the spin direction
        psi = -math.atan2(-fy, -fx)
        assert psi == pytest.approx(
            math.atan(math.pi * math.sqrt(1 - eps**2) / (4 * eps)), rel=1e-6
        )


# ROSS/Friswell textbook case (mechanics-notes 3.1): W = 525 N on -y, ccw spin
ROSS = dict(r=0.05, length=0.03, c=1e-4, mu=0.1)
ROSS_OMEGA = 1500 * 2 * math.pi / 60
ROSS_K = np.array([[12807959.6, 16393593.3], [-25060393.3, 8815302.7]])
ROSS_C = np.array([[232896.93, -81924.37], [-81924.37, 294911.62]])


def friswell_coefficients(eps, load, c, omega):
    """Friswell et al. (2010) p. 177 short-bearing K, C (as ROSS's CylindricalBearing)."""
    s2 = 1 - eps**2
    pi2 = math.pi**2
    h0 = (pi2 * s2 + 16 * eps**2) ** -1.5
    q = pi2 * (1 + 2 * eps**2) - 16 * eps**2
    a = h0 * np.array([
        [4 * (pi2 * (2 - eps**2) + 16 * eps**2),
         math.pi * (pi2 * s2**2 - 16 * eps**4) / (eps * math.sqrt(s2))],
        [-math.pi * (pi2 * s2 * (1 + 2 * eps**2) + 32 * eps**2 * (1 + eps**2))
         / (eps * math.sqrt(s2)),
         4 * (pi2 * (1 + 2 * eps**2) + 32 * eps**2 * (1 + eps**2) / s2)],
    ])  # fmt: skip
    b = h0 * np.array([
        [2 * math.pi * math.sqrt(s2) * q / eps, -8 * q],
        [-8 * q, 2 * math.pi * (pi2 * s2**2 + 48 * eps**2) / (eps * math.sqrt(s2))],
    ])  # fmt: skip
    return load / c * a, load / (c * omega) * b


def test_ross_friswell_textbook_case():
    """Equilibrium eps0 = 0.266297509005 and position (0.2512, -0.0884) c, then K and C by
    central differences (1e-10 m, 1e-7 m/s: truncation ~1e-9) against ROSS's printed
    numbers (9 digits: 1e-7) and Friswell's closed forms (1e-6)."""
    load = 525.0

    def residual(q):
        f = film(q * ROSS["c"], np.zeros(2), ROSS_OMEGA, 0.0, **ROSS)
        return f[:2] / load - np.array([0.0, 1.0])

    sol = root(residual, np.array([0.25, -0.1]), tol=1e-15)
    e0 = sol.x * ROSS["c"]
    eps0 = np.hypot(*e0) / ROSS["c"]
    assert eps0 == pytest.approx(0.266297509005, rel=1e-9)
    assert sol.x == pytest.approx([0.2512, -0.0884], abs=1e-4)
    k = np.zeros((2, 2))
    c = np.zeros((2, 2))
    for j in range(2):
        dq = np.zeros(2)
        dq[j] = 1e-10
        k[:, j] = -(film(e0 + dq, np.zeros(2), ROSS_OMEGA, 0, **ROSS)[:2]
                    - film(e0 - dq, np.zeros(2), ROSS_OMEGA, 0, **ROSS)[:2]) / 2e-10  # fmt: skip
        c[:, j] = -(film(e0, dq * 1e3, ROSS_OMEGA, 0, **ROSS)[:2]
                    - film(e0, -dq * 1e3, ROSS_OMEGA, 0, **ROSS)[:2]) / 2e-7  # fmt: skip
    assert np.allclose(k, ROSS_K, rtol=1e-7, atol=0.0)
    assert np.allclose(c, ROSS_C, rtol=1e-7, atol=0.0)
    k_f, c_f = friswell_coefficients(eps0, load, ROSS["c"], ROSS_OMEGA)
    assert np.allclose(k, k_f, rtol=1e-6, atol=0.0)
    assert np.allclose(c, c_f, rtol=1e-6, atol=0.0)


def test_petroff_moment_balance_and_dissipation():
    """Petroff exactly at e = 0 (any translation speed); on random states the bushing
    torque from an independent quadrature of the bushing's shear satisfies T_j + T_b +
    (e x F) = 0 (1e-6 of the largest term), and the power taken from the bodies is >= 0."""
    for wj, wb in ((OMEGA, 0.0), (OMEGA, -0.3 * OMEGA), (0.0, 0.5 * OMEGA)):
        t = film(np.zeros(2), np.array([0.01, 0.02]), wj, wb)[2]
        assert t == -2 * math.pi * MU * R**3 * L * (wj - wb) / C  # Petroff, bit for bit
    rng = np.random.default_rng(2)
    for e, v, wj, wb in random_states(rng, 100):
        fx, fy, tj = film(e, v, wj, wb)
        tb = bushing_torque(e[0], e[1], fx, fy, tj)
        # the bushing's shear: Couette opposite, pressure-gradient part the same sign
        ref, pressure_shear = film_by_quadrature(e, v, wj, wb)
        tb_quadrature = -(ref[2] - pressure_shear) + pressure_shear
        moment = e[0] * fy - e[1] * fx
        scale = abs(tj) + abs(moment) + 1e-30
        assert abs(tb - tb_quadrature) < 1e-6 * scale
        assert abs(tj + tb_quadrature + moment) < 1e-6 * scale
        power = -(fx * v[0] + fy * v[1] + tj * wj + tb * wb)
        assert power >= -1e-12 * (abs(tj * wj) + abs(tb * wb) + abs(fx * v[0]) + abs(fy * v[1]))


def test_peak_pressure_against_dense_maximisation():
    """Largest mid-plane pressure against a 2^16-point scan refined by a bounded scalar
    maximisation of the inertial-frame pressure (1e-8)."""
    rng = np.random.default_rng(3)
    for e, v, wj, wb in random_states(rng, 40):
        got = short_journal_peak_pressure(e[0], e[1], v[0], v[1], wj, wb, R, L, C, MU)

        def p_mid(a, e=e, v=v, wj=wj, wb=wb):
            h = C - e[0] * math.cos(a) - e[1] * math.sin(a)
            dh_da = e[0] * math.sin(a) - e[1] * math.cos(a)
            dh_dt = -(v[0] * math.cos(a) + v[1] * math.sin(a))
            return -(L**2) / (8 * h**3) * (6 * MU * (wj + wb) * dh_da + 12 * MU * dh_dt)

        a = np.linspace(0, 2 * math.pi, 2**16, endpoint=False)
        values = np.array([p_mid(x) for x in a[::16]])
        best = a[::16][np.argmax(values)]
        refined = minimize_scalar(
            lambda x: -p_mid(x), bounds=(best - 1e-3 * 16, best + 1e-3 * 16),
            method="bounded", options={"xatol": 1e-12},
        )  # fmt: skip
        expected = max(-refined.fun, values.max(), 0.0)
        assert got == pytest.approx(expected, rel=1e-8)


def test_film_is_finite_and_continuous_at_and_beyond_the_cap():
    """At eps >= FILM_ECCENTRICITY_CAP the film is evaluated at the cap: finite for
    eps = 1 and 2, equal on both sides of the cap to 1e-6."""
    u = np.array([0.6, 0.8])
    v = np.array([0.01, -0.02])
    below = film(u * C * (FILM_ECCENTRICITY_CAP - 1e-12), v, OMEGA, 0.0)
    above = film(u * C * (FILM_ECCENTRICITY_CAP + 1e-12), v, OMEGA, 0.0)
    assert np.allclose(below, above, rtol=1e-6)
    for eps in (1.0, 2.0):
        assert np.all(np.isfinite(film(u * C * eps, v, OMEGA, 0.0)))


def contact(e, v, wj, wb, **kw):
    args = dict(
        contact_film=DEFAULT_CONTACT_FILM,
        contact_stiffness=DEFAULT_CONTACT_STIFFNESS,
        friction_coefficient=DEFAULT_FRICTION_COEFFICIENT,
    )
    args.update(kw)
    return np.array(
        journal_contact(e[0], e[1], v[0], v[1], wj, wb, R, C, args["contact_film"],
                        args["contact_stiffness"], args["friction_coefficient"])
    )  # fmt: skip


def test_contact_holds_5kN_inside_the_clearance_and_starts_continuously():
    """A 5 kN static load (no rotation, no film) is carried at |e| < c by the contact
    alone; at the onset h_min = contact_film the force is 0 and grows as k times the
    penetration (continuous: 1e-6 m of penetration gives k * 1e-6 within 1 %)."""
    u = np.array([math.cos(2.0), math.sin(2.0)])
    onset = C - DEFAULT_CONTACT_FILM

    def residual(r):
        return np.hypot(*contact(r * u, np.zeros(2), 0.0, 0.0)[:2]) - 5000.0

    r = brentq(residual, onset, 2 * C, xtol=1e-16)
    assert r < C
    assert C - r > 0.25 * DEFAULT_CONTACT_FILM
    assert np.all(contact((onset - 1e-12) * u, np.ones(2), OMEGA, 0.0) == 0.0)
    tiny = np.hypot(*contact((onset + 1e-13) * u, np.zeros(2), 0.0, 0.0)[:2])
    assert tiny == pytest.approx(DEFAULT_CONTACT_STIFFNESS * 1e-13, rel=1e-2)


def test_contact_friction_opposes_sliding_and_dissipates():
    """Friction is mu N against the slip at fast sliding (1e-6), the moment balance holds
    for the contact too, and the friction power is >= 0 on random states."""
    u = np.array([0.0, -1.0])
    e = (C - 0.5 * DEFAULT_CONTACT_FILM) * u
    fx, fy, tj = contact(e, np.zeros(2), OMEGA, 0.0)
    normal = DEFAULT_CONTACT_STIFFNESS * 0.5 * DEFAULT_CONTACT_FILM
    ut = np.array([-u[1], u[0]])
    friction = np.array([fx, fy]) @ ut
    assert friction == pytest.approx(-DEFAULT_FRICTION_COEFFICIENT * normal, rel=1e-6)
    assert tj == pytest.approx(R * friction, rel=1e-12)
    rng = np.random.default_rng(4)
    for _ in range(100):
        phi = rng.uniform(-math.pi, math.pi)
        e = (C - rng.uniform(0, DEFAULT_CONTACT_FILM)) * np.array([math.cos(phi), math.sin(phi)])
        v = rng.normal(size=2) * 0.05
        wj, wb = rng.uniform(-OMEGA, OMEGA, size=2)
        fx, fy, tj = contact(e, v, wj, wb)
        tb = bushing_torque(e[0], e[1], fx, fy, tj)
        # the normal force stores energy; only the friction part must dissipate
        normal_part = np.array([fx, fy]) @ e / np.hypot(*e) * (v @ e) / np.hypot(*e)
        friction_power = -(fx * v[0] + fy * v[1] - normal_part + tj * wj + tb * wb)
        assert friction_power >= -1e-9 * abs(tj * OMEGA)
