"""The validated sections of a case, frozen dataclasses in SI: options, operating point,
geometry, valves, leakage, heat transfer and solver settings.

They are built from the case file by :mod:`.build` and :mod:`.operating_point` and held
by :class:`~recipsim.case.case.Case`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from recipsim.physics.friction_models import NO_FRICTION
from recipsim.physics.motor_models import LOSSLESS
from recipsim.physics.speed_models import CASE_SPEED
from recipsim.physics.thermo.thermal_models import FIXED_WALL


@dataclass(frozen=True)
class Options:
    """One choice per submodel slot (see the README's option table)."""

    pressure: str
    properties: str
    valves: str
    heat_transfer: str
    leakage: str
    mechanics: str
    bearing_law: str
    drive: str
    #: a name of ``FRICTION_MODELS`` (resolved from the bearings when the case gives none)
    friction: str = NO_FRICTION.name
    motor: str = LOSSLESS.name
    thermal: str = FIXED_WALL.name
    #: a name of ``SPEED_MODELS``: the case's shaft speed or the motor's speed at load
    speed: str = CASE_SPEED.name


@dataclass(frozen=True)
class OperatingPoint:
    """Thermodynamic operating point, in SI.

    ``condensing_temperature`` is ``nan`` for a transcritical point given by its
    discharge pressure.
    """

    evaporating_temperature: float
    condensing_temperature: float
    suction_pressure: float
    discharge_pressure: float
    suction_temperature: float
    liquid_temperature: float
    shell_pressure: float
    shaft_speed: float  # [rad/s]
    #: air around the compressor shell [K]
    ambient_temperature: float = 305.35
    #: rating standard that set the temperatures ("none": the case's own)
    standard: str = "none"

    @property
    def pressure_ratio(self) -> float:
        return self.discharge_pressure / self.suction_pressure


@dataclass(frozen=True)
class Geometry:
    """Cylinder and crank geometry [m, m3]."""

    bore: float
    stroke: float
    connecting_rod_length: float
    clearance_volume: float
    liner_length: float  # head to the open end of the bore [m]

    @property
    def crank_radius(self) -> float:
        return 0.5 * self.stroke

    @property
    def piston_area(self) -> float:
        return math.pi * self.bore**2 / 4.0

    @property
    def swept_volume(self) -> float:
        return self.piston_area * self.stroke


@dataclass(frozen=True)
class ValveSpec:
    """One reed valve (also used for the port of ``quasi_static``)."""

    port_diameter: float
    reed_width: float
    reed_thickness: float
    reed_length: float
    port_position: float
    stop_height: float
    youngs_modulus: float
    density: float
    damping_ratio: float
    restitution: float
    preload: float
    flow_coefficient: float
    force_coefficient: float
    #: curtain of the flow area: "port" (pi d_port x) or "reed_diameter" (pi reed_width x)
    flow_area: str = "port"
    #: the jet's momentum flux adds to the pressure force on the reed
    momentum_force: bool = False

    @property
    def curtain_diameter(self) -> float:
        """Diameter of the curtain flow area pi d x [m]: the port's or the reed's."""
        return self.reed_width if self.flow_area == "reed_diameter" else self.port_diameter

    @property
    def port_area(self) -> float:
        return math.pi * self.port_diameter**2 / 4.0

    @property
    def stiffness(self) -> float:
        """Cantilever stiffness at the port centre, 6 E I / (a^2 (3 l - a)) [N/m]."""
        inertia = self.reed_width * self.reed_thickness**3 / 12.0
        a, length = self.port_position, self.reed_length
        return 6.0 * self.youngs_modulus * inertia / (a * a * (3.0 * length - a))

    @property
    def mass(self) -> float:
        """Equivalent moving mass, one third of the reed [kg]."""
        return self.density * self.reed_length * self.reed_width * self.reed_thickness / 3.0

    @property
    def natural_frequency(self) -> float:
        """[Hz]"""
        return math.sqrt(self.stiffness / self.mass) / (2.0 * math.pi)


@dataclass(frozen=True)
class Valves:
    suction: ValveSpec
    discharge: ValveSpec
    flow_model: str
    laminar_pressure_difference: float
    stick_velocity: float


@dataclass(frozen=True)
class Leakage:
    radial_clearance: float
    eccentricity_ratio: float
    #: "isothermal" (compressible) or "incompressible" gap law
    model: str = "isothermal"


@dataclass(frozen=True)
class HeatTransfer:
    wall_temperature: float
    coefficient: float  # nan: the correlation's own


@dataclass(frozen=True)
class SolverSettings:
    method: str
    rtol: float
    atol: float
    cycle_tolerance: float
    max_revolutions: int
    min_revolutions: int
    samples_per_revolution: int
    max_step: float  # crank angle [rad]
    #: periodic steady-state solver: "revolutions", "shooting" or "auto"
    periodic: str = "auto"
    #: "periodic", or "rest": the start-up transient first (:mod:`recipsim.solve.startup`)
    start: str = "periodic"
    #: equalised pressure at standstill [Pa] (nan: saturation at the ambient temperature)
    standstill_pressure: float = math.nan
    #: time over which the plenums move from the standstill to the case's pressures [s]
    pull_down_time: float = 2.5
    #: outside the refrigerant's envelope: "refuse" or "ignore" (recipsim.case.envelope)
    envelope: str = "refuse"
    #: most integration steps a solve may take (:func:`recipsim.solve.periodic.check_step_budget`)
    step_budget: int = 20_000_000
