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
