"""Flexible mechanism: rotor, connecting rod and piston on visco-elastic bearings.

Bodies and degrees of freedom (state layout in :mod:`.layout`):

- rotor + crankshaft (axisymmetric, balanced): centre of mass X, Y; tilts about X
  and Y (Cardan angles, :mod:`.bodies`); spin = crank angle. Its axial position is
  held by the (unmodelled) thrust bearing. Newton-Euler in the tilted, non-spinning
  frame, gyroscopic terms included, exact for finite tilts;
- connecting rod: planar, X, Y and rotation about Z;
- piston: axial X, lateral Y and tilt about the pin axis Z (secondary motion).

Bearings (numbered as in the paper) tie markers of the bodies together and to the
housing through the bearing law (:mod:`.bearings`): 1 primary and 2 secondary (rotor
axis at ``primary_z``, ``secondary_z`` to the housing), 3 eccentric (crank pin to
big end), 4 pin (piston pin to small end), 5 piston_top and 6 piston_skirt (piston
axis points to the bore axis, lateral only). No constraint equations: every body is
held by its bearings only. The gas force ``-(p - p_shell) A_p`` acts at the crown
along the piston axis.

Drives (``par[P_DRIVE]``): ``constant_speed`` prescribes the spin (crank speed state
constant, zero crank acceleration) and returns the torque about the rotor axis that
does it; ``torque_profile`` applies a periodic table of torque vs crank angle and
the crank speed is free; ``induction_motor`` applies the motor's torque at the rotor's
spin rate (:mod:`recipsim.physics.motor`), the crank speed is free.

All compiled functions take every parameter as an argument and do not allocate in
the right-hand side.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from recipsim.physics.kinematics import piston_displacement, rod_angle, rod_centre_of_mass
from recipsim.physics.mechanics import layout as lay
from recipsim.physics.mechanics.bearings import bearing_force, bearing_spring_energy
from recipsim.physics.mechanics.bodies import planar_marker, rotor_marker, rotor_moment
from recipsim.physics.mechanics.pinned import N_PIN_OUT, pinned_reactions
from recipsim.physics.mechanics.tabulated import periodic_linear_interpolation, tabulated_pressure
from recipsim.physics.motor import induction_motor_torque

_ROW = lay.P_BEARINGS
_NB = lay.N_BEARING_PAR


@njit(cache=True)
def _bearing(
    i: int,
    par: np.ndarray,
    aux: np.ndarray,
    ex: float,
    ey: float,
    vx: float,
    vy: float,
    spin_journal: float,
    spin_bushing: float,
) -> tuple[float, float, float, float]:
    """Evaluate bearing ``i`` (relative motion in X-Y), record it in ``aux``.

    Returns fx, fy (force on the journal), the power absorbed [W] and the spring energy.
    """
    row = _ROW + i * _NB
    fx, fy, fz = bearing_force(par, row, ex, ey, 0.0, vx, vy, 0.0, spin_journal, spin_bushing)
    axis = int(par[row + lay.BP_AXIS])
    if axis == lay.AXIS_X:
        ex = 0.0
        vx = 0.0
    base = lay.A_BEARING_FORCE + 3 * i
    aux[base] = fx
    aux[base + 1] = fy
    aux[base + 2] = fz
    base = lay.A_BEARING_DISPLACEMENT + 3 * i
    aux[base] = ex
    aux[base + 1] = ey
    aux[base + 2] = 0.0
    power = -(fx * vx + fy * vy)
    energy = bearing_spring_energy(par, row, ex, ey, 0.0)
    return fx, fy, power, energy


@njit(cache=True)
def flexible_rhs(
    t: float,
    y: np.ndarray,
    dydt: np.ndarray,
    aux: np.ndarray,
    par: np.ndarray,
    gas_pressure: float,
    drive_angles: np.ndarray,
    drive_torques: np.ndarray,
) -> None:
    """Right-hand side of the flexible mechanism, ``dy/dt = f(t, y)``.

    Parameters
    ----------
    t : float
        Time [s] (the model is autonomous; kept for the integrator interface).
    y : numpy.ndarray
        State, shape ``(N_STATE,)`` (layout in :mod:`.layout`).
    dydt : numpy.ndarray
        Output, shape ``(N_STATE,)``, overwritten.
    aux : numpy.ndarray
        Output, shape ``(N_AUX,)``, overwritten: bearing forces and displacements,
        driving torque, gas force, energies and powers, piston position (``A_*``).
    par : numpy.ndarray
        Parameter array (:func:`.parameters.mechanism_parameters`).
    gas_pressure : float
        Cylinder pressure at this instant [Pa].
    drive_angles, drive_torques : numpy.ndarray
        Periodic driving-torque table, crank angle [rad] (increasing, span < 2 pi) and
        torque [N m]; read only by the ``torque_profile`` drive (pass any 1-element
        arrays otherwise).
    """
    r = par[lay.P_CRANK_RADIUS]
    big_l = par[lay.P_ROD_LENGTH]
    th = y[lay.Y_CRANK_ANGLE]
    thd = y[lay.Y_CRANK_SPEED]
    cth = math.cos(th)
    sth = math.sin(th)

    # ---------------------------------------------------------------- rotor
    xg = y[lay.Y_ROTOR_X]
    yg = y[lay.Y_ROTOR_Y]
    vxg = y[lay.Y_ROTOR_VX]
    vyg = y[lay.Y_ROTOR_VY]
    al = y[lay.Y_ROTOR_TILT_X]
    be = y[lay.Y_ROTOR_TILT_Y]
    ald = y[lay.Y_ROTOR_TILT_X_RATE]
    bed = y[lay.Y_ROTOR_TILT_Y_RATE]
    ca = math.cos(al)
    sa = math.sin(al)
    cb = math.cos(be)
    sb = math.sin(be)
    wx = ald * cb
    wy = bed
    wz = ald * sb + thd  # spin rate about the rotor axis
    zg = par[lay.P_ROTOR_COM_Z]
    h1 = par[lay.P_PRIMARY_Z] - zg
    h2 = par[lay.P_SECONDARY_Z] - zg
    rex = r * cth
    rey = r * sth
    rez = -zg
    p1x, p1y, v1x, v1y = rotor_marker(xg, yg, vxg, vyg, ca, sa, cb, sb, wx, wy, wz, 0.0, 0.0, h1)
    p2x, p2y, v2x, v2y = rotor_marker(xg, yg, vxg, vyg, ca, sa, cb, sb, wx, wy, wz, 0.0, 0.0, h2)
    pex, pey, vex, vey = rotor_marker(xg, yg, vxg, vyg, ca, sa, cb, sb, wx, wy, wz, rex, rey, rez)

    # ------------------------------------------------------------------ rod
    a = par[lay.P_ROD_COM_FRACTION]
    phi0, dphi, d2phi = rod_angle(th, r, big_l)
    gx, gy, dgx, dgy, d2gx, d2gy = rod_centre_of_mass(th, r, big_l, a)
    xc = gx + y[lay.Y_ROD_DX]
    yc = gy + y[lay.Y_ROD_DY]
    phi = phi0 + y[lay.Y_ROD_DANGLE]
    vxc = dgx * thd + y[lay.Y_ROD_DVX]
    vyc = dgy * thd + y[lay.Y_ROD_DVY]
    phid = dphi * thd + y[lay.Y_ROD_DANGLE_RATE]
    cph = math.cos(phi)
    sph = math.sin(phi)
    bx = -a * big_l * cph  # big end relative to the rod centre of mass
    by = -a * big_l * sph
    sx = (1.0 - a) * big_l * cph  # small end
    sy = (1.0 - a) * big_l * sph
    pbx, pby, vbx, vby = planar_marker(xc, yc, vxc, vyc, phid, bx, by)
    psx, psy, vsx, vsy = planar_marker(xc, yc, vxc, vyc, phid, sx, sy)

    # --------------------------------------------------------------- piston
    xd, dxd, d2xd = piston_displacement(th, r, big_l)
    u_pin = par[lay.P_PISTON_PIN_U]
    u_top = par[lay.P_PISTON_TOP_U]
    u_skirt = par[lay.P_PISTON_SKIRT_U]
    u_crown = par[lay.P_PISTON_CROWN_U]
    xp = r + big_l - xd - u_pin + y[lay.Y_PISTON_DX]
    vxp = -dxd * thd + y[lay.Y_PISTON_DVX]
    yp = y[lay.Y_PISTON_Y]
    vyp = y[lay.Y_PISTON_VY]
    gam = y[lay.Y_PISTON_TILT]
    gamd = y[lay.Y_PISTON_TILT_RATE]
    cg = math.cos(gam)
    sg = math.sin(gam)
    ppx, ppy, vpx, vpy = planar_marker(xp, yp, vxp, vyp, gamd, u_pin * cg, u_pin * sg)
    _, p5y, _, v5y = planar_marker(xp, yp, vxp, vyp, gamd, u_top * cg, u_top * sg)
    _, p6y, _, v6y = planar_marker(xp, yp, vxp, vyp, gamd, u_skirt * cg, u_skirt * sg)

    # ------------------------------------------------------------- bearings
    f1x, f1y, w1, e1 = _bearing(lay.B_PRIMARY, par, aux, p1x, p1y, v1x, v1y, wz, 0.0)
    f2x, f2y, w2, e2 = _bearing(lay.B_SECONDARY, par, aux, p2x, p2y, v2x, v2y, wz, 0.0)
    f3x, f3y, w3, e3 = _bearing(
        lay.B_ECCENTRIC, par, aux, pex - pbx, pey - pby, vex - vbx, vey - vby, wz, phid
    )
    f4x, f4y, w4, e4 = _bearing(
        lay.B_PIN, par, aux, ppx - psx, ppy - psy, vpx - vsx, vpy - vsy, gamd, phid
    )
    f5x, f5y, w5, e5 = _bearing(lay.B_PISTON_TOP, par, aux, 0.0, p5y, 0.0, v5y, 0.0, 0.0)
    f6x, f6y, w6, e6 = _bearing(lay.B_PISTON_SKIRT, par, aux, 0.0, p6y, 0.0, v6y, 0.0, 0.0)

    # ------------------------------------------------- rotor Newton-Euler
    m_r = par[lay.P_ROTOR_MASS]
    i_p = par[lay.P_ROTOR_POLAR_INERTIA]
    i_t = par[lay.P_ROTOR_TRANSVERSE_INERTIA]
    m1x, m1y, m1z = rotor_moment(ca, sa, cb, sb, 0.0, 0.0, h1, f1x, f1y)
    m2x, m2y, m2z = rotor_moment(ca, sa, cb, sb, 0.0, 0.0, h2, f2x, f2y)
    m3x, m3y, m3z = rotor_moment(ca, sa, cb, sb, rex, rey, rez, f3x, f3y)
    mx = m1x + m2x + m3x
    my = m1y + m2y + m3y
    mz = m1z + m2z + m3z
    # Euler in the tilted frame: I dw/dt + W x (I w) = M, W = (wx, wy, ald sb)
    pdot = (mx - bed * (i_p * wz - i_t * ald * sb)) / i_t
    aldd = (pdot + ald * bed * sb) / cb
    bedd = (my - wx * (i_t * ald * sb - i_p * wz)) / i_t
    drive = int(par[lay.P_DRIVE])
    if drive == lay.DRIVE_CONSTANT_SPEED:
        thdd = 0.0
        torque = i_p * (aldd * sb + ald * bed * cb) - mz
    else:
        if drive == lay.DRIVE_INDUCTION_MOTOR:
            torque = induction_motor_torque(
                wz,
                par[lay.P_MOTOR_SYNC_SPEED],
                par[lay.P_MOTOR_BREAKDOWN_TORQUE],
                par[lay.P_MOTOR_BREAKDOWN_SLIP],
                par[lay.P_MOTOR_BACKWARD_RATIO],
            )
        else:
            torque = periodic_linear_interpolation(th, drive_angles, drive_torques)
        thdd = (mz + torque) / i_p - aldd * sb - ald * bed * cb

    # ---------------------------------------------------- rod Newton-Euler
    m_c = par[lay.P_ROD_MASS]
    fxc = -f3x - f4x
    fyc = -f3y - f4y
    mc = bx * (-f3y) - by * (-f3x) + sx * (-f4y) - sy * (-f4x)
    phidd = mc / par[lay.P_ROD_INERTIA]

    # ------------------------------------------------- piston Newton-Euler
    m_p = par[lay.P_PISTON_MASS]
    gas = -(gas_pressure - par[lay.P_SHELL_PRESSURE]) * par[lay.P_PISTON_AREA]
    fxp = f4x + f5x + f6x + gas * cg
    fyp = f4y + f5y + f6y + gas * sg
    mp = u_pin * (cg * f4y - sg * f4x) + u_top * (cg * f5y - sg * f5x)
    mp += u_skirt * (cg * f6y - sg * f6x)
    gamdd = mp / par[lay.P_PISTON_INERTIA]

    # ------------------------------------------------------------ derivatives
    for i in range(lay.N_COORD):
        dydt[i] = y[lay.N_COORD + i]
    dydt[lay.Y_ROTOR_VX] = (f1x + f2x + f3x) / m_r
    dydt[lay.Y_ROTOR_VY] = (f1y + f2y + f3y) / m_r
    dydt[lay.Y_ROTOR_TILT_X_RATE] = aldd
    dydt[lay.Y_ROTOR_TILT_Y_RATE] = bedd
    dydt[lay.Y_CRANK_SPEED] = thdd
    th2 = thd * thd
    dydt[lay.Y_ROD_DVX] = fxc / m_c - d2gx * th2 - dgx * thdd
    dydt[lay.Y_ROD_DVY] = fyc / m_c - d2gy * th2 - dgy * thdd
    dydt[lay.Y_ROD_DANGLE_RATE] = phidd - d2phi * th2 - dphi * thdd
    dydt[lay.Y_PISTON_DVX] = fxp / m_p + d2xd * th2 + dxd * thdd
    dydt[lay.Y_PISTON_VY] = fyp / m_p
    dydt[lay.Y_PISTON_TILT_RATE] = gamdd

    # ---------------------------------------------------------------- outputs
    aux[lay.A_DRIVE_TORQUE] = torque
    aux[lay.A_GAS_FORCE] = gas
    aux[lay.A_KINETIC_ENERGY_ROTOR] = 0.5 * (
        m_r * (vxg * vxg + vyg * vyg) + i_t * (wx * wx + wy * wy) + i_p * wz * wz
    )
    aux[lay.A_KINETIC_ENERGY_ROD] = 0.5 * (
        m_c * (vxc * vxc + vyc * vyc) + par[lay.P_ROD_INERTIA] * phid * phid
    )
    aux[lay.A_KINETIC_ENERGY_PISTON] = 0.5 * (
        m_p * (vxp * vxp + vyp * vyp) + par[lay.P_PISTON_INERTIA] * gamd * gamd
    )
    aux[lay.A_SPRING_ENERGY] = e1 + e2 + e3 + e4 + e5 + e6
    aux[lay.A_BEARING_POWER] = w1 + w2 + w3 + w4 + w5 + w6
    aux[lay.A_DRIVE_POWER] = torque * wz
    aux[lay.A_GAS_POWER] = gas * (cg * vxp + sg * vyp)
    x_crown = xp + u_crown * cg
    aux[lay.A_PISTON_DISPLACEMENT] = r + big_l + par[lay.P_PIN_FROM_CROWN] - x_crown
    aux[lay.A_PISTON_SPEED] = -(vxp - u_crown * sg * gamd)
    aux[lay.A_PISTON_LATERAL] = yp
    aux[lay.A_PISTON_TILT] = gam
    aux[lay.A_CRANK_ANGLE] = th
    aux[lay.A_CRANK_SPEED] = thd


@njit(cache=True)
def flexible_rhs_tabulated(
    t: float,
    y: np.ndarray,
    dydt: np.ndarray,
    aux: np.ndarray,
    par: np.ndarray,
    pressure_angles: np.ndarray,
    pressures: np.ndarray,
    drive_angles: np.ndarray,
    drive_torques: np.ndarray,
) -> None:
    """:func:`flexible_rhs` with the cylinder pressure from a periodic p(theta) table.

    ``pressure_angles`` [rad] and ``pressures`` [Pa] as in
    :func:`recipsim.physics.mechanics.tabulated.tabulated_pressure`, read at the crank-angle
    state.
    """
    p = tabulated_pressure(y[lay.Y_CRANK_ANGLE], pressure_angles, pressures)
    flexible_rhs(t, y, dydt, aux, par, p, drive_angles, drive_torques)


@njit(cache=True)
def flexible_outputs(
    t: float,
    y: np.ndarray,
    aux: np.ndarray,
    par: np.ndarray,
    gas_pressure: float,
    drive_angles: np.ndarray,
    drive_torques: np.ndarray,
) -> None:
    """Write the outputs (``aux`` layout ``A_*`` of :mod:`.layout`) for one state.

    Same arguments as :func:`flexible_rhs` without ``dydt`` (a scratch array is
    allocated here: this is for post-processing, not the integrator's hot path).
    """
    scratch = np.empty(lay.N_STATE)
    flexible_rhs(t, y, scratch, aux, par, gas_pressure, drive_angles, drive_torques)


@njit(cache=True)
def flexible_output_history(
    t: np.ndarray,
    ys: np.ndarray,
    par: np.ndarray,
    gas_pressures: np.ndarray,
    drive_angles: np.ndarray,
    drive_torques: np.ndarray,
    out: np.ndarray,
) -> None:
    """:func:`flexible_outputs` for a history: ``ys`` (n, N_STATE) -> ``out`` (n, N_AUX)."""
    scratch = np.empty(lay.N_STATE)
    for i in range(t.shape[0]):
        flexible_rhs(
            t[i], ys[i], scratch, out[i], par, gas_pressures[i], drive_angles, drive_torques
        )


# ------------------------------------------------------------ state accessors


@njit(cache=True)
def piston_axial_displacement(y: np.ndarray, par: np.ndarray) -> tuple[float, float]:
    """Crown displacement from its rigid TDC position and its rate.

    The cylinder volume is ``V_clearance + A_p * x`` with this ``x``; it equals the
    slider-crank displacement when the bearings are rigid.

    Returns
    -------
    x, dx_dt : float
        [m], [m/s].
    """
    r = par[lay.P_CRANK_RADIUS]
    big_l = par[lay.P_ROD_LENGTH]
    th = y[lay.Y_CRANK_ANGLE]
    xd, dxd, _ = piston_displacement(th, r, big_l)
    u_crown = par[lay.P_PISTON_CROWN_U]
    gam = y[lay.Y_PISTON_TILT]
    # crown X = (r + L - x_kin - u_pin + dX) + u_crown cos(gam); u_crown - u_pin = pin offset
    x = xd - y[lay.Y_PISTON_DX] + u_crown * (1.0 - math.cos(gam))
    dx = dxd * y[lay.Y_CRANK_SPEED] - y[lay.Y_PISTON_DVX]
    dx += u_crown * math.sin(gam) * y[lay.Y_PISTON_TILT_RATE]
    return x, dx


@njit(cache=True)
def piston_lateral_offset(y: np.ndarray, par: np.ndarray, from_crown: float) -> float:
    """Lateral (Y) offset of the piston axis from the bore axis [m].

    Parameters
    ----------
    y : numpy.ndarray
        State.
    par : numpy.ndarray
        Parameters.
    from_crown : float
        Axial station below the crown [m] (0: crown, piston length: skirt end).
    """
    u = par[lay.P_PISTON_CROWN_U] - from_crown
    return y[lay.Y_PISTON_Y] + u * math.sin(y[lay.Y_PISTON_TILT])


@njit(cache=True)
def piston_tilt(y: np.ndarray) -> float:
    """Piston tilt about the pin axis Z [rad] (positive: crown towards +Y)."""
    return y[lay.Y_PISTON_TILT]


# ------------------------------------------------------------ initial state


def initial_state(
    par: np.ndarray,
    theta: float,
    omega: float,
    gas_pressure: float | None = None,
    *,
    static_deflection: bool = True,
) -> np.ndarray:
    """State with the bodies at their pinned positions at crank angle ``theta``.

    With ``static_deflection`` each bearing is deflected by its pinned reaction at
    ``theta`` over its stiffness (the quasi-static pose, which shortens the start-up
    transient); velocities are the rigid ones (deflection rates zero).

    Parameters
    ----------
    par : numpy.ndarray
        Parameter array.
    theta : float
        Crank angle [rad].
    omega : float
        Crank speed [rad/s].
    gas_pressure : float, optional
        Cylinder pressure for the static deflection [Pa]; default the shell pressure.
    static_deflection : bool

    Returns
    -------
    numpy.ndarray
        Shape ``(N_STATE,)``.
    """
    y = np.zeros(lay.N_STATE)
    y[lay.Y_CRANK_ANGLE] = theta
    y[lay.Y_CRANK_SPEED] = omega
    if not static_deflection:
        return y
    if gas_pressure is None:
        gas_pressure = float(par[lay.P_SHELL_PRESSURE])
    out = np.zeros(N_PIN_OUT)
    pinned_reactions(theta, omega, 0.0, gas_pressure, par, out)

    def deflection(i: int) -> np.ndarray:
        k = par[_ROW + i * _NB + lay.BP_STIFFNESS]
        f = out[3 * i : 3 * i + 2]
        return -f / k if k > 0.0 else np.zeros(2)

    r, big_l = par[lay.P_CRANK_RADIUS], par[lay.P_ROD_LENGTH]
    zg = par[lay.P_ROTOR_COM_Z]
    h1, h2 = par[lay.P_PRIMARY_Z] - zg, par[lay.P_SECONDARY_Z] - zg
    e1, e2 = deflection(lay.B_PRIMARY), deflection(lay.B_SECONDARY)
    # marker at height h: (x_g + h sin(beta), y_g - h sin(alpha) cos(beta)), small tilts
    beta = (e1[0] - e2[0]) / (h1 - h2)
    alpha = -(e1[1] - e2[1]) / (h1 - h2)
    y[lay.Y_ROTOR_TILT_X] = alpha
    y[lay.Y_ROTOR_TILT_Y] = beta
    y[lay.Y_ROTOR_X] = e1[0] - h1 * math.sin(beta)
    y[lay.Y_ROTOR_Y] = e1[1] + h1 * math.sin(alpha) * math.cos(beta)
    ca, sa, cb, sb = math.cos(alpha), math.sin(alpha), math.cos(beta), math.sin(beta)
    pex, pey, _, _ = rotor_marker(
        y[0], y[1], 0.0, 0.0, ca, sa, cb, sb, 0.0, 0.0, 0.0,
        r * math.cos(theta), r * math.sin(theta), -zg,
    )  # fmt: skip
    e3 = deflection(lay.B_ECCENTRIC)
    big_end = np.array([pex, pey]) - e3

    u_pin = par[lay.P_PISTON_PIN_U]
    u_top, u_skirt = par[lay.P_PISTON_TOP_U], par[lay.P_PISTON_SKIRT_U]
    e5, e6 = deflection(lay.B_PISTON_TOP)[1], deflection(lay.B_PISTON_SKIRT)[1]
    gam = math.asin((e5 - e6) / (u_top - u_skirt))
    yp = e5 - u_top * math.sin(gam)
    e4 = deflection(lay.B_PIN)
    small_y = yp + u_pin * math.sin(gam) - e4[1]
    sphi = (small_y - big_end[1]) / big_l
    phi = math.asin(sphi)
    small_x = big_end[0] + big_l * math.cos(phi)
    pin_x = small_x + e4[0]
    xp = pin_x - u_pin * math.cos(gam)

    a = par[lay.P_ROD_COM_FRACTION]
    phi0, _, _ = rod_angle(theta, r, big_l)
    gx, gy, _, _, _, _ = rod_centre_of_mass(theta, r, big_l, a)
    xd, _, _ = piston_displacement(theta, r, big_l)
    y[lay.Y_ROD_DX] = big_end[0] + a * big_l * math.cos(phi) - gx
    y[lay.Y_ROD_DY] = big_end[1] + a * big_l * math.sin(phi) - gy
    y[lay.Y_ROD_DANGLE] = phi - phi0
    y[lay.Y_PISTON_DX] = xp - (r + big_l - xd - u_pin)
    y[lay.Y_PISTON_Y] = yp
    y[lay.Y_PISTON_TILT] = gam
    return y


def state_scales(par: np.ndarray) -> np.ndarray:
    """Characteristic size of each state, for absolute tolerances and convergence checks.

    Deflections: ``d = 100 N / k_max``; tilts: ``d`` over the shortest lever; rates:
    those times ``sqrt(k_max / m_piston)`` (the highest bearing frequency); crank angle
    1 rad; crank speed ``max(|speed|, 1)`` rad/s.

    Returns
    -------
    numpy.ndarray
        Shape ``(N_STATE,)``, positive.
    """
    ks = [par[_ROW + i * _NB + lay.BP_STIFFNESS] for i in range(lay.N_BEARINGS)]
    k_max = max(ks)
    d = 100.0 / k_max
    zg = par[lay.P_ROTOR_COM_Z]
    lever_rotor = min(abs(par[lay.P_PRIMARY_Z] - zg), abs(par[lay.P_SECONDARY_Z] - zg), abs(zg))
    lever_rotor = max(lever_rotor, 1e-3)
    lever_piston = max(abs(par[lay.P_PISTON_TOP_U] - par[lay.P_PISTON_SKIRT_U]), 1e-3)
    w = math.sqrt(k_max / par[lay.P_PISTON_MASS])
    q = np.full(lay.N_COORD, d)
    q[[lay.Y_ROTOR_TILT_X, lay.Y_ROTOR_TILT_Y]] = d / lever_rotor
    q[lay.Y_ROD_DANGLE] = d / par[lay.P_ROD_LENGTH]
    q[lay.Y_PISTON_TILT] = d / lever_piston
    q[lay.Y_CRANK_ANGLE] = 1.0
    v = q * w
    v[lay.Y_CRANK_ANGLE] = max(abs(par[lay.P_SPEED]), 1.0)
    return np.concatenate([q, v])
