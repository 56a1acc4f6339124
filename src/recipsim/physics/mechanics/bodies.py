"""Rigid-body kinematics of the three bodies, as small compiled scalar functions.

Rotor orientation: tilt ``alpha`` about X, then ``beta`` about the once-tilted Y, then
the spin (crank angle) ``theta`` about the twice-tilted Z: ``R = Rx(alpha) Ry(beta)
Rz(theta)`` (Cardan angles; exact for finite angles, singular only at beta = 90 deg).
Vectors of the rotor are written in the *tilted, non-spinning* frame
``F' = Rx(alpha) Ry(beta)``, in which the axisymmetric rotor's inertia is constant.
Its angular velocity there is ``(alpha' cos beta, beta', alpha' sin beta + theta')``.

The rod and the piston move in the X-Y plane; a marker of the rod or piston is given
by its position relative to the body's centre of mass.
"""

from __future__ import annotations

from numba import njit


@njit(cache=True)
def rotor_marker(
    xg: float,
    yg: float,
    vxg: float,
    vyg: float,
    ca: float,
    sa: float,
    cb: float,
    sb: float,
    wx: float,
    wy: float,
    wz: float,
    rx: float,
    ry: float,
    rz: float,
) -> tuple[float, float, float, float]:
    """Inertial X-Y position and velocity of a rotor marker.

    Parameters
    ----------
    xg, yg, vxg, vyg : float
        Rotor centre of mass position [m] and velocity [m/s] in X, Y.
    ca, sa, cb, sb : float
        cos and sin of the tilts alpha (about X) and beta (about the tilted Y).
    wx, wy, wz : float
        Rotor angular velocity in the tilted frame F' [rad/s].
    rx, ry, rz : float
        Marker position relative to the centre of mass, in F' [m].

    Returns
    -------
    px, py, vx, vy : float
        Inertial position [m] and velocity [m/s] of the marker, X and Y.
    """
    ux = wy * rz - wz * ry
    uy = wz * rx - wx * rz
    uz = wx * ry - wy * rx
    px = xg + cb * rx + sb * rz
    py = yg + sa * sb * rx + ca * ry - sa * cb * rz
    vx = vxg + cb * ux + sb * uz
    vy = vyg + sa * sb * ux + ca * uy - sa * cb * uz
    return px, py, vx, vy


@njit(cache=True)
def rotor_moment(
    ca: float,
    sa: float,
    cb: float,
    sb: float,
    rx: float,
    ry: float,
    rz: float,
    fx: float,
    fy: float,
) -> tuple[float, float, float]:
    """Moment about the rotor centre of mass, in F', of an inertial force (fx, fy, 0).

    Parameters
    ----------
    ca, sa, cb, sb : float
        cos and sin of the two tilts.
    rx, ry, rz : float
        Point of application relative to the centre of mass, in F' [m].
    fx, fy : float
        Inertial force [N].

    Returns
    -------
    mx, my, mz : float
        Moment in F' [N m].
    """
    gx = cb * fx + sa * sb * fy
    gy = ca * fy
    gz = sb * fx - sa * cb * fy
    return ry * gz - rz * gy, rz * gx - rx * gz, rx * gy - ry * gx


@njit(cache=True)
def planar_marker(
    xg: float, yg: float, vxg: float, vyg: float, omega: float, dx: float, dy: float
) -> tuple[float, float, float, float]:
    """Position and velocity of a marker of a body moving in the X-Y plane.

    Parameters
    ----------
    xg, yg, vxg, vyg : float
        Centre of mass position [m] and velocity [m/s].
    omega : float
        Angular velocity about Z [rad/s].
    dx, dy : float
        Marker relative to the centre of mass, inertial axes [m].

    Returns
    -------
    px, py, vx, vy : float
    """
    return xg + dx, yg + dy, vxg - omega * dy, vyg + omega * dx


@njit(cache=True)
def counterweight_accelerations(
    d: tuple[float, float, float, float, float],
    f: tuple[float, float, float, float, float],
    m_u: float,
    h: float,
    rpx: float,
    rpy: float,
    bx: float,
    by: float,
    free_spin: bool,
) -> tuple[float, float, float, float, float]:
    """Rotor accelerations with a counterweight point mass rigidly on the rotor.

    Small-tilt generalised equations ``(D + m_u J^T J) qdd = f - m_u J^T b`` in
    ``q = (x, y, tilt_x, tilt_y, crank angle)``: ``D`` the diagonal of the balanced
    rotor's equations, ``f`` their right-hand sides, ``J`` the Jacobian of the
    counterweight's in-plane position ``(x + h tilt_y + rho_x, y - h tilt_x + rho_y)``
    (``h`` its height above the rotor's centre of mass, ``rho`` its radius vector,
    ``rho' = (rpx, rpy)`` its derivative in the crank angle), i.e. rows
    ``(1, 0, 0, h, rpx)`` and ``(0, 1, -h, 0, rpy)``, and ``b = (bx, by)`` the
    centripetal part of its acceleration. Solved in closed form by the Woodbury
    identity (a rank-2 update of ``D``). With ``free_spin`` False the crank angle is
    prescribed (``qdd[4] = 0``) and drops out.
    """
    d0, d1, d2, d3, d4 = d
    u0 = (f[0] - m_u * bx) / d0
    u1 = (f[1] - m_u * by) / d1
    u2 = (f[2] + m_u * h * by) / d2
    u3 = (f[3] - m_u * h * bx) / d3
    inv4 = 1.0 / d4 if free_spin else 0.0
    u4 = (f[4] - m_u * (rpx * bx + rpy * by)) * inv4
    ju0 = u0 + h * u3 + rpx * u4
    ju1 = u1 - h * u2 + rpy * u4
    s00 = 1.0 / m_u + 1.0 / d0 + h * h / d3 + rpx * rpx * inv4
    s11 = 1.0 / m_u + 1.0 / d1 + h * h / d2 + rpy * rpy * inv4
    s01 = rpx * rpy * inv4
    det = s00 * s11 - s01 * s01
    w0 = (s11 * ju0 - s01 * ju1) / det
    w1 = (s00 * ju1 - s01 * ju0) / det
    return (
        u0 - w0 / d0,
        u1 - w1 / d1,
        u2 + h * w1 / d2,
        u3 - h * w0 / d3,
        u4 - (rpx * w0 + rpy * w1) * inv4,
    )
