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
the right-hand side. The three bodies' Newton-Euler equations share every kinematic
quantity of one evaluation, so they stay here; the start pose and scales are in
:mod:`.flexible_setup`, the bearing laws in :mod:`.bearings` (evaluated and recorded by
:mod:`.bearing_forces`), the counterweight's solve in :mod:`.bodies`, the piston's pose
in :mod:`.piston_pose`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from recipsim.physics.kinematics import piston_displacement, rod_angle, rod_centre_of_mass
from recipsim.physics.mechanics import layout as lay
from recipsim.physics.mechanics.bearing_forces import bearing_force, piston_skirt_forces
from recipsim.physics.mechanics.bearing_laws import skirt_film
from recipsim.physics.mechanics.bodies import (
    counterweight_accelerations,
    planar_marker,
    rotor_marker,
    rotor_moment,
)
from recipsim.physics.mechanics.drives import drive_torque
from recipsim.physics.mechanics.tabulated import tabulated_pressure


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
    bearing_tables: np.ndarray,
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
        Output, shape ``(N_AUX,)``, overwritten: bearing forces, displacements,
        friction torques, absorbed powers and contact forces, driving torque, gas
        force, energies and powers, piston position (``A_*``).
    par : numpy.ndarray
        Parameter array (:func:`recipsim.model.mechanism_parameters.mechanism_parameters`).
    gas_pressure : float
        Cylinder pressure at this instant [Pa].
    drive_angles, drive_torques : numpy.ndarray
        Periodic driving-torque table, crank angle [rad] (increasing, span < 2 pi) and
        torque [N m]; read only by the ``torque_profile`` drive (pass any 1-element
        arrays otherwise).
    bearing_tables : numpy.ndarray
        Tables of the ``finite_journal`` bearings
        (:func:`recipsim.model.mechanism_parameters.bearing_tables`; any 1-element
        array when there are none).
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
    f1x, f1y, t1, _, w1, e1 = bearing_force(
        lay.B_PRIMARY, par, bearing_tables, aux, p1x, p1y, v1x, v1y, wz, 0.0
    )
    f2x, f2y, t2, _, w2, e2 = bearing_force(
        lay.B_SECONDARY, par, bearing_tables, aux, p2x, p2y, v2x, v2y, wz, 0.0
    )
    f3x, f3y, t3, t3b, w3, e3 = bearing_force(
        lay.B_ECCENTRIC, par, bearing_tables, aux,
        pex - pbx, pey - pby, vex - vbx, vey - vby, wz, phid,
    )  # fmt: skip
    f4x, f4y, _, t4b, w4, e4 = bearing_force(
        lay.B_PIN, par, bearing_tables, aux, ppx - psx, ppy - psy, vpx - vsx, vpy - vsy, gamd, phid
    )
    friction = 0.0
    if (
        int(par[lay.P_BEARINGS + lay.B_PISTON_SKIRT * lay.N_BEARING_PAR + lay.BP_LAW])
        == skirt_film.CODE
    ):
        f5y, f6y, friction = piston_skirt_forces(par, aux, p5y, p6y, v5y, v6y, vxp, u_top - u_skirt)
        f5x = 0.0
        f6x = 0.0
        w5 = aux[lay.A_BEARING_DISSIPATION + lay.B_PISTON_TOP]
        aux[lay.A_PISTON_FRICTION_POWER] = -friction * vxp
        w6 = aux[lay.A_BEARING_DISSIPATION + lay.B_PISTON_SKIRT] - friction * vxp
        e5 = 0.0
        e6 = 0.0
    else:
        aux[lay.A_PISTON_FRICTION] = 0.0
        aux[lay.A_PISTON_FRICTION_POWER] = 0.0
        f5x, f5y, _, _, w5, e5 = bearing_force(
            lay.B_PISTON_TOP, par, bearing_tables, aux, 0.0, p5y, 0.0, v5y, 0.0, 0.0
        )
        f6x, f6y, _, _, w6, e6 = bearing_force(
            lay.B_PISTON_SKIRT, par, bearing_tables, aux, 0.0, p6y, 0.0, v6y, 0.0, 0.0
        )

    # ------------------------------------------------- rotor Newton-Euler
    m_r = par[lay.P_ROTOR_MASS]
    i_p = par[lay.P_ROTOR_POLAR_INERTIA]
    i_t = par[lay.P_ROTOR_TRANSVERSE_INERTIA]
    m1x, m1y, m1z = rotor_moment(ca, sa, cb, sb, 0.0, 0.0, h1, f1x, f1y)
    m2x, m2y, m2z = rotor_moment(ca, sa, cb, sb, 0.0, 0.0, h2, f2x, f2y)
    m3x, m3y, m3z = rotor_moment(ca, sa, cb, sb, rex, rey, rez, f3x, f3y)
    mx = m1x + m2x + m3x
    my = m1y + m2y + m3y
    mz = m1z + m2z + m3z + t1 + t2 + t3
    # Euler in the tilted frame: I dw/dt + W x (I w) = M, W = (wx, wy, ald sb)
    fa = mx - bed * (i_p * wz - i_t * ald * sb) + i_t * ald * bed * sb  # = i_t cb aldd
    fb = my - wx * (i_t * ald * sb - i_p * wz)  # = i_t bedd
    aldd = fa / (i_t * cb)
    bedd = fb / i_t
    fx_r = f1x + f2x + f3x
    fy_r = f1y + f2y + f3y
    axg = fx_r / m_r
    ayg = fy_r / m_r
    drive = int(par[lay.P_DRIVE])
    torque = drive_torque(drive, th, wz, par, drive_angles, drive_torques)
    spin_rest = i_p * (aldd * sb + ald * bed * cb)  # spin terms of the tilting rotor
    m_u = par[lay.P_COUNTERWEIGHT_MASS]
    free_spin = drive != lay.DRIVE_CONSTANT_SPEED
    if m_u > 0.0:
        r_u = par[lay.P_COUNTERWEIGHT_RADIUS]
        ang = th + par[lay.P_COUNTERWEIGHT_ANGLE]
        rux = r_u * math.cos(ang)
        ruy = r_u * math.sin(ang)
        h_u = par[lay.P_COUNTERWEIGHT_Z] - zg
        # the spin equation holds i_p * tilt_x'' * sin(tilt_y), and the counterweight's
        # moment makes tilt_x'' large: solve again with the tilt acceleration found
        for _ in range(2):
            axg, ayg, aldd, bedd, thdd = counterweight_accelerations(
                (m_r, m_r, i_t * cb, i_t, i_p),
                (fx_r, fy_r, fa, fb, mz + torque - spin_rest),
                m_u, h_u, -ruy, rux, -thd * thd * rux, -thd * thd * ruy, free_spin,
            )  # fmt: skip
            spin_rest = i_p * (aldd * sb + ald * bed * cb)
        # counterweight acceleration and its pull on the spin (constant speed: the torque)
        aux_x = axg + h_u * bedd - ruy * thdd - thd * thd * rux
        aux_y = ayg - h_u * aldd + rux * thdd - thd * thd * ruy
        if not free_spin:
            thdd = 0.0
            torque = spin_rest - mz + m_u * (-ruy * aux_x + rux * aux_y)
        vux = vxg + h_u * bed - ruy * thd
        vuy = vyg - h_u * ald + rux * thd
        ke_counterweight = 0.5 * m_u * (vux * vux + vuy * vuy)
    else:
        ke_counterweight = 0.0
        if free_spin:
            thdd = (mz + torque) / i_p - aldd * sb - ald * bed * cb
        else:
            thdd = 0.0
            torque = spin_rest - mz

    # ---------------------------------------------------- rod Newton-Euler
    m_c = par[lay.P_ROD_MASS]
    fxc = -f3x - f4x
    fyc = -f3y - f4y
    mc = bx * (-f3y) - by * (-f3x) + sx * (-f4y) - sy * (-f4x) + t3b + t4b
    phidd = mc / par[lay.P_ROD_INERTIA]

    # ------------------------------------------------- piston Newton-Euler
    m_p = par[lay.P_PISTON_MASS]
    gas = -(gas_pressure - par[lay.P_SHELL_PRESSURE]) * par[lay.P_PISTON_AREA]
    fxp = f4x + f5x + f6x + (gas + friction) * cg
    fyp = f4y + f5y + f6y + (gas + friction) * sg
    mp = u_pin * (cg * f4y - sg * f4x) + u_top * (cg * f5y - sg * f5x)
    mp += u_skirt * (cg * f6y - sg * f6x)
    gamdd = mp / par[lay.P_PISTON_INERTIA]

    # ------------------------------------------------------------ derivatives
    for i in range(lay.N_COORD):
        dydt[i] = y[lay.N_COORD + i]
    dydt[lay.Y_ROTOR_VX] = axg
    dydt[lay.Y_ROTOR_VY] = ayg
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
    aux[lay.A_KINETIC_ENERGY_ROTOR] = ke_counterweight + 0.5 * (
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
    bearing_tables: np.ndarray,
) -> None:
    """:func:`flexible_rhs` with the cylinder pressure from a periodic p(theta) table.

    ``pressure_angles`` [rad] and ``pressures`` [Pa] as in
    :func:`recipsim.physics.mechanics.tabulated.tabulated_pressure`, read at the crank-angle
    state.
    """
    p = tabulated_pressure(y[lay.Y_CRANK_ANGLE], pressure_angles, pressures)
    flexible_rhs(t, y, dydt, aux, par, p, drive_angles, drive_torques, bearing_tables)


@njit(cache=True)
def flexible_outputs(
    t: float,
    y: np.ndarray,
    aux: np.ndarray,
    par: np.ndarray,
    gas_pressure: float,
    drive_angles: np.ndarray,
    drive_torques: np.ndarray,
    bearing_tables: np.ndarray,
) -> None:
    """Write the outputs (``aux`` layout ``A_*`` of :mod:`.layout`) for one state.

    Same arguments as :func:`flexible_rhs` without ``dydt`` (a scratch array is
    allocated here: this is for post-processing, not the integrator's hot path).
    """
    scratch = np.empty(lay.N_STATE)
    flexible_rhs(t, y, scratch, aux, par, gas_pressure, drive_angles, drive_torques, bearing_tables)


@njit(cache=True)
def flexible_output_history(
    t: np.ndarray,
    ys: np.ndarray,
    par: np.ndarray,
    gas_pressures: np.ndarray,
    drive_angles: np.ndarray,
    drive_torques: np.ndarray,
    bearing_tables: np.ndarray,
    out: np.ndarray,
) -> None:
    """:func:`flexible_outputs` for a history: ``ys`` (n, N_STATE) -> ``out`` (n, N_AUX)."""
    scratch = np.empty(lay.N_STATE)
    for i in range(t.shape[0]):
        flexible_rhs(
            t[i], ys[i], scratch, out[i], par, gas_pressures[i], drive_angles, drive_torques,
            bearing_tables,
        )  # fmt: skip


# ------------------------------------------------------------ state accessors
