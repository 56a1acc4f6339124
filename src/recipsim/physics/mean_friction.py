"""Mean friction of a rigid crank train: Petroff journals and a viscous piston skirt.

Evaluated once per converged cycle on its uniform crank-angle samples (numpy), never
in an ODE. Both laws are the concentric-film limit, the
lightly loaded film's friction:

- a journal of radius ``R``, length ``L`` and radial clearance ``c`` turning at
  ``omega`` relative to its sleeve in oil of viscosity ``mu`` dissipates Petroff's
  ``P = 2 pi mu R^3 L omega^2 / c`` (:func:`recipsim.physics.mechanics.journal.couette_torque`
  at eccentricity 0; Hamrock, *Fundamentals of Fluid Film Lubrication*, ch. 8). A loaded
  journal's Couette torque grows as ``1/sqrt(1 - eps^2)``: 6 % at ``eps = 1/3``, 25 % at
  ``0.6``, so Petroff is a lower bound;
- the piston skirt, a concentric annulus of diameter ``D``, wetted length ``L_w`` and
  radial clearance ``delta`` sliding at ``v``, takes the Couette shear force
  ``F = mu pi D L_w v / delta`` and dissipates ``F v`` (PDSim's mechanical-loss model,
  thermo-notes section 1.7).

No load-dependent (mixed or boundary lubrication) term: it needs a friction coefficient
and a contact share that no source gives for these bearings.
"""

from __future__ import annotations

import math

import numpy as np

from recipsim.physics.mechanics.journal import couette_torque


def petroff_coefficient(
    viscosity: float, diameter: float, length: float, clearance: float
) -> float:
    """``k`` of Petroff's dissipation ``P = k omega^2`` [W s^2].

    Parameters
    ----------
    viscosity : float
        Oil dynamic viscosity [Pa s].
    diameter, length, clearance : float
        Journal diameter, bearing length and radial clearance [m].

    Returns
    -------
    float
        ``2 pi mu R^3 L / c`` [N m s] (the torque per unit relative spin rate).
    """
    return -couette_torque(0.0, 1.0, 0.0, 0.5 * diameter, length, clearance, viscosity)


def journal_petroff_power(
    viscosity: float, diameter: float, length: float, clearance: float, relative_speed: np.ndarray
) -> np.ndarray:
    """Petroff dissipation of a centred journal at each sample [W] (>= 0).

    Parameters
    ----------
    viscosity, diameter, length, clearance : float
        As in :func:`petroff_coefficient` [Pa s, m, m, m].
    relative_speed : ndarray
        Spin rate of the journal relative to its sleeve [rad/s] (either sign).
    """
    k = petroff_coefficient(viscosity, diameter, length, clearance)
    return k * np.asarray(relative_speed) ** 2


def rod_swing_rate(theta: np.ndarray, crank_radius: float, rod_length: float) -> np.ndarray:
    """Rod angle's crank-angle derivative ``dphi/dtheta`` [-] at crank angles ``theta`` [rad]
    from top dead centre (vectorised :func:`recipsim.physics.kinematics.rod_angle`:
    ``sin(phi) = -lambda sin(theta)``, so ``dphi/dtheta = -lambda cos(theta) / cos(phi)``).

    Parameters
    ----------
    theta : ndarray
        Crank angles [rad].
    crank_radius, rod_length : float
        [m].
    """
    lam = crank_radius / rod_length
    s = np.sin(theta)
    return -lam * np.cos(theta) / np.sqrt(1.0 - lam * lam * s * s)


def wetted_skirt_length(
    piston_length: float, liner_length: float, crown_from_head: np.ndarray
) -> np.ndarray:
    """Length of the piston inside the bore [m]: the liner from the crown to its open end,
    at most the piston length.

    Parameters
    ----------
    piston_length, liner_length : float
        Piston length and liner length from the head to its open end [m].
    crown_from_head : ndarray
        Distance of the piston crown from the cylinder head [m].
    """
    return np.clip(liner_length - np.asarray(crown_from_head), 0.0, piston_length)


def skirt_viscous_force(
    viscosity: float,
    bore: float,
    wetted_length: np.ndarray,
    clearance: float,
    velocity: np.ndarray,
) -> np.ndarray:
    """Couette force of the concentric skirt film on the piston [N], opposing ``velocity``.

    Parameters
    ----------
    viscosity : float
        Oil dynamic viscosity [Pa s].
    bore, clearance : float
        Bore diameter and radial piston clearance [m].
    wetted_length : ndarray
        Piston length inside the bore [m].
    velocity : ndarray
        Piston velocity [m/s] (any sign convention; the force has the opposite sign).
    """
    return -viscosity * np.pi * bore * np.asarray(wetted_length) * np.asarray(velocity) / clearance


def time_mean(values: np.ndarray, crank_speed: np.ndarray) -> float:
    """Time mean over one revolution of samples at uniform crank angles (dt = dtheta/omega).

    Parameters
    ----------
    values : ndarray
        The quantity at each sample (any unit).
    crank_speed : ndarray
        Crank speed at each sample [rad/s], positive.
    """
    weights = 1.0 / np.asarray(crank_speed)
    return float(np.sum(np.asarray(values) * weights) / np.sum(weights))


def thrust_collar_torque(
    viscosity: float,
    inner_diameter: float,
    outer_diameter: float,
    film_thickness: float,
    speed: np.ndarray,
) -> np.ndarray:
    """Viscous torque of a flat annular thrust collar on a parallel film [N m] (>= 0 for
    ``speed`` > 0).

    Couette flow across a film of uniform thickness ``h`` between a collar turning at
    ``omega`` and its stationary seat: the shear stress ``mu omega r / h`` at radius
    ``r``, integrated over the annulus, gives the thrust-face analogue of Petroff's law
    ``T = pi mu omega (R_o^4 - R_i^4) / (2 h)`` (Hamrock, Schmid & Jacobson,
    *Fundamentals of Fluid Film Lubrication*, 2nd ed., the viscous friction of a
    parallel-surface thrust bearing; the same integral as the flat collar's friction
    torque of machine design with the shear ``mu u / h`` in place of Coulomb friction).
    The film thickness is given: a parallel film carries its load by no wedge (the
    thermal wedge and the surface texture do, Nagata et al. 2013), so the load does not
    enter.

    Parameters
    ----------
    viscosity : float
        Oil dynamic viscosity [Pa s].
    inner_diameter, outer_diameter : float
        Diameters of the annulus [m], inner < outer.
    film_thickness : float
        Axial film thickness [m] (> 0).
    speed : ndarray
        Spin rate of the collar relative to its seat [rad/s].

    Raises
    ------
    ValueError
        A film thickness that is not positive.
    """
    if not film_thickness > 0.0:
        raise ValueError(f"thrust film thickness {film_thickness!r} m: must be > 0")
    r_o, r_i = 0.5 * outer_diameter, 0.5 * inner_diameter
    return math.pi * viscosity * np.asarray(speed) * (r_o**4 - r_i**4) / (2.0 * film_thickness)


def thrust_ball_torque(friction_coefficient: float, load: float, pitch_diameter: float) -> float:
    """Frictional moment of a thrust ball bearing at constant friction coefficient [N m]:
    ``M = mu F d / 2`` (SKF, *Rolling bearings* catalogue, "Estimating the frictional
    moment": ``mu`` about 0.0013 for thrust ball bearings under normal conditions, ``d``
    the bore diameter; here the pitch diameter of the ball track).

    Parameters
    ----------
    friction_coefficient : float
        Constant friction coefficient of the bearing [-].
    load : float
        Axial load [N].
    pitch_diameter : float
        Diameter of the ball track [m].
    """
    return 0.5 * friction_coefficient * load * pitch_diameter


def oil_pump_power(
    density: float, flow: float, speed: np.ndarray, outlet_radius: float, lift: float
) -> np.ndarray:
    """Power the crankshaft gives the oil it pumps [W]: Euler's pump equation for the
    centrifugal pump of the shaft's eccentric bore plus the lift of the helical groove.

    The oil enters the pick-up tube on the axis without swirl and leaves the shaft
    co-rotating at ``outlet_radius``: Euler's turbomachinery equation gives the shaft
    power ``rho Q u c_u = rho Q omega^2 r^2`` (the centrifugal head ``omega^2 r^2 / 2``
    and as much again of swirl, which the oil dissipates as it leaves); the helical groove
    then lifts it by ``lift`` against gravity, ``rho Q g H`` (a viscous drag pump: the
    groove's shear beyond this work is in the journal's Petroff term). The pump's two
    stages are those of Posch et al. (2015, IOP Conf. Ser.: Mater. Sci. Eng. 90 012028,
    a Secop household compressor: pick-up tube and eccentric bore, then a helical groove)
    and Alves, Barbosa & Prata (2012, Purdue ICEC paper 2045, the eccentric-tube
    centrifugal pump).

    Parameters
    ----------
    density : float
        Oil density [kg/m3].
    flow : float
        Volume flow of oil the pump delivers [m3/s].
    speed : ndarray
        Shaft speed [rad/s] at each sample.
    outlet_radius : float
        Radius at which the oil leaves the centrifugal stage [m].
    lift : float
        Height from the sump's surface to where the groove delivers the oil [m].
    """
    omega = np.asarray(speed)
    return density * flow * (omega**2 * outlet_radius**2 + 9.80665 * lift)
