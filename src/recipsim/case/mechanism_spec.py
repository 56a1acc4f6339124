"""The mechanism's data as frozen dataclasses (SI): the slider-crank geometry, the piston,
connecting rod and rotor as rigid bodies, the bearings with their laws, and copies with
scaled or replaced bearing stiffness and damping.

The case tables are read into them by :mod:`recipsim.case.mechanism`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace

from recipsim.case.lubrication import FilmSpec, OilSpec
from recipsim.physics.mechanics.layout import BEARING_NAMES


@dataclass(frozen=True)
class CrankGeometry:
    """Slider-crank geometry shared with the cylinder model (SI).

    Attributes
    ----------
    bore : float
        Cylinder bore = piston diameter [m].
    crank_radius : float
        Crank radius r = stroke / 2 [m].
    rod_length : float
        Connecting-rod length L between the big-end and small-end centres [m].
    """

    bore: float
    crank_radius: float
    rod_length: float

    @classmethod
    def from_stroke(cls, bore: float, stroke: float, rod_length: float) -> CrankGeometry:
        """Build from bore, stroke and rod length, all in [m]."""
        return cls(bore=bore, crank_radius=0.5 * stroke, rod_length=rod_length)

    @property
    def piston_area(self) -> float:
        """Crown area pi D^2 / 4 [m^2]."""
        return math.pi * self.bore**2 / 4.0


@dataclass(frozen=True)
class PistonSpec:
    """Piston as a rigid body (SI).

    Attributes
    ----------
    mass : float
        [kg].
    length : float
        Axial length, crown to skirt end [m].
    pin_offset_from_crown : float
        Distance of the pin axis below the crown [m].
    centre_of_mass_from_crown : float
        Distance of the centre of mass below the crown [m].
    transverse_inertia : float
        Moment of inertia about the pin axis (Z) through the centre of mass [kg m^2].
    """

    mass: float
    length: float
    pin_offset_from_crown: float
    centre_of_mass_from_crown: float
    transverse_inertia: float


@dataclass(frozen=True)
class ConnectingRodSpec:
    """Connecting rod as a planar rigid body (SI).

    Attributes
    ----------
    mass : float
        [kg].
    centre_of_mass_fraction : float
        Distance of the centre of mass from the big end over the rod length [-].
    inertia : float
        Moment of inertia about Z through the centre of mass [kg m^2].
    """

    mass: float
    centre_of_mass_fraction: float
    inertia: float


@dataclass(frozen=True)
class RotorSpec:
    """Motor rotor plus crankshaft, axisymmetric and balanced (SI).

    Attributes
    ----------
    mass : float
        [kg].
    polar_inertia, transverse_inertia : float
        About the spin axis and about a diameter through the centre of mass [kg m^2].
    centre_of_mass_z : float
        Axial position of the centre of mass (eccentric plane at z = 0) [m].
    primary_z, secondary_z : float
        Axial positions of the primary (1) and secondary (2) bearings [m].
    counterweight_mass : float
        Counterweight: a point mass on the rotor [kg] (0: none). ``mass`` and the
        inertias are the rotor's without it.
    counterweight_radius : float
        Its distance from the spin axis [m].
    counterweight_angle : float
        Its angle ahead of the crank pin about +Z [rad] (pi: opposite the pin).
    counterweight_z : float
        Its axial position [m].
    """

    mass: float
    polar_inertia: float
    transverse_inertia: float
    centre_of_mass_z: float
    primary_z: float
    secondary_z: float
    counterweight_mass: float = 0.0
    counterweight_radius: float = 0.0
    counterweight_angle: float = math.pi
    counterweight_z: float = 0.0


@dataclass(frozen=True)
class BearingSpec:
    """One bearing: a law and its parameters (SI).

    Attributes
    ----------
    law : str
        The name of its law in the bearing laws' registry
        (:data:`recipsim.physics.mechanics.bearing_laws.registry.BEARING_LAWS`).
    stiffness : float
        [N/m] (linear law; 0 when not given).
    damping : float
        [N s/m] (linear law).
    position_from_crown : float or None
        Piston bearings only: axial position of the bearing marker below the crown [m].
    film : FilmSpec or None
        Film data (geometry, clearance, viscosity, contact), required by the film laws
        and kept when given for a linear bearing (so the law can be switched).
    """

    law: str
    stiffness: float
    damping: float
    position_from_crown: float | None = None
    film: FilmSpec | None = None


@dataclass(frozen=True)
class MechanismSpec:
    """Everything the mechanism needs besides the slider-crank geometry.

    ``bearings`` holds one :class:`BearingSpec` per name of
    :data:`recipsim.physics.mechanics.layout.BEARING_NAMES`, in that order.
    """

    piston: PistonSpec
    connecting_rod: ConnectingRodSpec
    rotor: RotorSpec
    bearings: tuple[BearingSpec, ...]
    oil: OilSpec | None = None

    def bearing(self, name: str) -> BearingSpec:
        """The bearing called ``name`` (one of ``BEARING_NAMES``)."""
        return self.bearings[BEARING_NAMES.index(name)]


def solid_cylinder_transverse_inertia(mass: float, diameter: float, length: float) -> float:
    """Moment of inertia of a solid cylinder about a diameter through its centre.

    ``m (3 R^2 + l^2) / 12``; used as the default piston inertia. A real piston is a
    hollow cup whose inertia is somewhat larger (a thin shell gives
    ``m (6 R^2 + l^2) / 12``), so this is an estimate for the reference compressor
    (35 g, 22 mm x 20 mm: 2.23e-6 kg m^2).

    Parameters
    ----------
    mass : float
        [kg].
    diameter, length : float
        [m].

    Returns
    -------
    float
        [kg m^2].
    """
    radius = 0.5 * diameter
    return mass * (3.0 * radius**2 + length**2) / 12.0


def scale_bearings(
    spec: MechanismSpec, stiffness_factor: float, damping_factor: float | None = None
) -> MechanismSpec:
    """Return a copy with every bearing stiffness scaled.

    Parameters
    ----------
    spec : MechanismSpec
    stiffness_factor : float
        Factor on every stiffness [-].
    damping_factor : float, optional
        Factor on every damping [-]. Default ``sqrt(stiffness_factor)``, which keeps
        every damping ratio ``c / (2 sqrt(k m))``.
    """
    if damping_factor is None:
        damping_factor = math.sqrt(stiffness_factor)
    bearings = tuple(
        replace(b, stiffness=b.stiffness * stiffness_factor, damping=b.damping * damping_factor)
        for b in spec.bearings
    )
    return replace(spec, bearings=bearings)


def with_damping(spec: MechanismSpec, damping: float | Mapping[str, float]) -> MechanismSpec:
    """Return a copy with the bearing damping replaced [N s/m] (one value or per name)."""
    bearings = []
    for name, b in zip(BEARING_NAMES, spec.bearings, strict=True):
        c = damping[name] if isinstance(damping, Mapping) else damping
        bearings.append(replace(b, damping=float(c)))
    return replace(spec, bearings=tuple(bearings))
