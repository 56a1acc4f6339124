"""Campbell check: the rotor of the flexible model whirls at the frequencies of the
4-DOF gyroscopic rigid rotor on two isotropic springs (mechanics notes section 3.3).

The frequencies are read from the eigenvalues of the finite-difference Jacobian of
``flexible_rhs`` about the centred, spinning rotor, with the eccentric bearing
disconnected (k3 = 0) and no damping, so that the rotor block is exactly decoupled
from rod and piston.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from recipsim.case.mechanism_spec import CrankGeometry, MechanismSpec, RotorSpec, with_damping
from recipsim.model.mechanism_parameters import mechanism_parameters
from recipsim.physics.mechanics import layout as lay
from recipsim.physics.mechanics.flexible import flexible_rhs
from recipsim.physics.mechanics.flexible_setup import initial_state

ROTOR = [lay.Y_ROTOR_X, lay.Y_ROTOR_Y, lay.Y_ROTOR_TILT_X, lay.Y_ROTOR_TILT_Y]
ROTOR_STATES = ROTOR + [lay.N_COORD + i for i in ROTOR]
RPM = 2 * math.pi / 60


def rotor_only(spec: MechanismSpec, rotor: RotorSpec | None = None, k: float | None = None):  # type: ignore[no-untyped-def]
    """Undamped spec with the eccentric disconnected; optionally another rotor and
    equal rotor-bearing stiffness k."""
    bearings = list(with_damping(spec, 0.0).bearings)
    bearings[lay.B_ECCENTRIC] = replace(bearings[lay.B_ECCENTRIC], stiffness=0.0)
    if k is not None:
        for i in (lay.B_PRIMARY, lay.B_SECONDARY):
            bearings[i] = replace(bearings[i], stiffness=k)
    return replace(spec, rotor=rotor or spec.rotor, bearings=tuple(bearings))


def rotor_jacobian(spec: MechanismSpec, geometry: CrankGeometry, speed: float) -> np.ndarray:
    """Central-difference Jacobian of the full RHS at the centred spinning rotor."""
    par = mechanism_parameters(spec, geometry, shell_pressure=1e5, speed=speed)
    y = initial_state(par, 0.3, speed, static_deflection=False)
    n = lay.N_STATE
    jac = np.zeros((n, n))
    fp, fm = np.zeros(n), np.zeros(n)
    aux, table = np.zeros(lay.N_AUX), np.zeros(1)
    scale = np.full(n, 1e-9)
    scale[lay.N_COORD :] = 1e-6
    for j in range(n):
        yp, ym = y.copy(), y.copy()
        yp[j] += scale[j]
        ym[j] -= scale[j]
        flexible_rhs(0.0, yp, fp, aux, par, 1e5, table, table, table)
        flexible_rhs(0.0, ym, fm, aux, par, 1e5, table, table, table)
        jac[:, j] = (fp - fm) / (2 * scale[j])
    return jac


def rotor_modes(jac: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Whirl frequencies [Hz] (ascending) and eigenvectors of the rotor block."""
    others = [i for i in range(lay.N_STATE) if i not in ROTOR_STATES]
    assert np.abs(jac[np.ix_(ROTOR_STATES, others)]).max() == 0.0  # decoupled
    lam, vec = np.linalg.eig(jac[np.ix_(ROTOR_STATES, ROTOR_STATES)])
    keep = lam.imag > 0
    order = np.argsort(lam.imag[keep])
    assert np.abs(lam.real).max() < 1e-6 * np.abs(lam.imag).max()  # undamped
    return lam.imag[keep][order] / (2 * math.pi), vec[:, keep][:, order]


def four_dof_frequencies(rotor: RotorSpec, k1: float, k2: float, speed: float) -> np.ndarray:
    """State-space eigenvalues of M q'' + G q' + K q = 0, q = (x, y, tilt_x, tilt_y),
    written independently of the model: springs at a_i = z_i - z_G act on the axis
    point (x + a beta, y - a alpha); gyroscopic coupling +-I_p Omega on the tilts."""
    m, ip, it = rotor.mass, rotor.polar_inertia, rotor.transverse_inertia
    stiff = np.zeros((4, 4))
    for k, z in ((k1, rotor.primary_z), (k2, rotor.secondary_z)):
        a = z - rotor.centre_of_mass_z
        gx, gy = np.array([1.0, 0, 0, a]), np.array([0, 1.0, -a, 0])
        stiff += k * (np.outer(gx, gx) + np.outer(gy, gy))
    mass = np.diag([m, m, it, it])
    gyro = np.zeros((4, 4))
    gyro[2, 3], gyro[3, 2] = ip * speed, -ip * speed
    a_mat = np.block(
        [
            [np.zeros((4, 4)), np.eye(4)],
            [-np.linalg.solve(mass, stiff), -np.linalg.solve(mass, gyro)],
        ]
    )
    lam = np.linalg.eigvals(a_mat)
    return np.sort(lam.imag[lam.imag > 0]) / (2 * math.pi)


@pytest.mark.parametrize("rpm", [0.0, 3500.0, 30000.0])
def test_reference_rotor_matches_the_four_dof_model(
    spec: MechanismSpec, geometry: CrankGeometry, rpm: float
) -> None:
    """Reference compressor rotor (coupled: k1 a1 + k2 a2 != 0), 0 / 3500 / 30000 rpm:
    the 4 whirl frequencies agree to 1e-6 (the Jacobian is exact up to rounding)."""
    model = rotor_only(spec)
    freq, _ = rotor_modes(rotor_jacobian(model, geometry, rpm * RPM))
    k1, k2 = spec.bearing("primary").stiffness, spec.bearing("secondary").stiffness
    ref = four_dof_frequencies(spec.rotor, k1, k2, rpm * RPM)
    np.testing.assert_allclose(freq, ref, rtol=1e-6)
    if rpm > 0:  # the gyroscopic split is visible
        assert ref[1] - ref[0] > 1e-3 * ref[0]


STEEL = RotorSpec(
    mass=122.679,
    polar_inertia=0.61340,
    transverse_inertia=2.86251,
    centre_of_mass_z=-0.30,
    primary_z=-0.05,
    secondary_z=-0.55,
)
#: Steel cylinder L = 0.5 m, D = 0.2 m on 1 MN/m at +-0.25 m (mechanics notes 3.3,
#: verified there): translation, backward, forward whirl [Hz].
STEEL_TABLE = {
    0.0: (20.3212, 33.2584, 33.2584),
    2000.0: (20.3212, 29.8782, 37.0210),
    4000.0: (20.3212, 26.8739, 41.1596),
    8000.0: (20.3212, 21.9110, 50.4824),
}


@pytest.mark.parametrize("rpm", sorted(STEEL_TABLE))
def test_symmetric_rotor_matches_table_and_closed_form(
    spec: MechanismSpec, geometry: CrankGeometry, rpm: float
) -> None:
    """Symmetric rotor (kc = 0): translation sqrt(kt/m) whatever the speed, conical
    whirl from It w^2 -+ Ip W w - kr = 0; the tabulated values are rounded to 1e-4 Hz
    (tolerance 1e-5 relative); the closed form holds to 1e-7; the forward (higher)
    conical mode whirls in the spin direction, the backward one against it."""
    freq, vec = rotor_modes(rotor_jacobian(rotor_only(spec, STEEL, 1e6), geometry, rpm * RPM))
    translation, backward, forward = STEEL_TABLE[rpm]
    is_translation = np.abs(freq / translation - 1) < 1e-5
    assert is_translation.sum() == 2  # x and y translation, speed independent
    conical = [f for f, t in zip(freq, is_translation, strict=True) if not t]
    assert sorted(conical) == pytest.approx(sorted([backward, forward]), rel=1e-5)
    big_omega = rpm * RPM
    kr = 2 * 1e6 * 0.25**2
    ip, it = STEEL.polar_inertia, STEEL.transverse_inertia
    root = math.sqrt((ip * big_omega) ** 2 + 4 * it * kr)
    closed = [(-ip * big_omega + root) / (2 * it), (ip * big_omega + root) / (2 * it)]
    assert sorted(conical) == pytest.approx([w / (2 * math.pi) for w in closed], rel=1e-7)
    if rpm > 0:
        for f, v, t in zip(freq, vec.T, is_translation, strict=True):
            if t:
                continue
            # axis tip above the centre of mass moves by (beta, -alpha); for lambda = i w
            # a counter-clockwise (forward) whirl has Im(conj(u) w) < 0
            u, w = v[3], -v[2]
            forward_whirl = np.imag(np.conj(u) * w) < 0
            assert forward_whirl == (f == max(conical))
