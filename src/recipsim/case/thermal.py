"""The case's shell thermal network and muffler losses (``[thermal]``), read once.

Used with ``options.thermal = "network"`` (:mod:`recipsim.physics.thermo.shell_network`);
validated whenever present, so a study may switch the option with ``--set``. The ambient
is ``operating_point.ambient_temperature``.

Keys (bare numbers are SI; strings may carry units):

- ``ua_<node>_<node>`` [W/K]: conductance of each link of
  :data:`recipsim.physics.thermo.shell_network.LINKS`; ``ua_shell_ambient`` to the ambient;
- ``direct_suction_fraction``: share of the inlet flow that enters the suction muffler
  without mixing with the shell gas (semi-direct suction);
- ``friction_wall_fraction``: share of the friction released in the cylinder wall (the
  piston); the rest goes into the oil (bearings);
- ``motor_loss_power``, ``friction_power`` [W]: fixed sources; not set: the motor and
  friction models' results when the case has them, else 0;
- ``suction_muffler_loss_coefficient``, ``discharge_muffler_loss_coefficient`` (K, 0: no
  pressure drop) and ``..._flow_area`` [m2]: dp = K rho v^2 / 2 with the mean flow.

Default conductances are engineering estimates for a 5-10 cm3 household compressor
(shell about 0.15 m across and 0.19 m high, 0.12 m2 outside), not fitted to any
measurement: each is an area times a film coefficient of the right kind, stated beside it
in :data:`THERMAL_SPEC`. Shell to ambient: laminar natural convection of air on a
vertical surface, h = 1.42 (dT / L)^(1/4) = 5 W/(m2 K) at dT = 35 K, L = 0.19 m, plus
linearised radiation 4 eps sigma T^3 = 7 W/(m2 K) (eps = 0.9, 325 K): 12 W/(m2 K) x
0.12 m2 = 1.5 W/K (PDSim's reciprocating example uses 10 W/(m2 K) on 0.04 m2). The
network is the structure of Todescat et al. (1992, Purdue ICEC paper 936: suction
chamber, cylinder wall, discharge chamber, discharge muffler, shell and the gas inside
the shell from steady balances with effective conductances measured on an Embraco
compressor), with the motor and the oil as nodes of their own as in Ribas et al. (2008,
ICEC paper 1907). Calibrate them where measurements exist.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from recipsim.physics.thermo.shell_network import LINK_NAMES, NetworkParameters
from recipsim.physics.thermo.suction_path import HALF_SINE_VELOCITY_SQUARE_FACTOR
from recipsim.schema import Field, Spec, read_table

_UA = "W/K"
#: Default conductance of each link [W/K] and what it stands for.
DEFAULT_CONDUCTANCES: dict[str, tuple[float, str]] = {
    "suction_muffler_shell_gas": (0.15, "plastic muffler wall, 0.015 m2 x 10 W/(m2 K) overall"),
    "suction_muffler_cylinder_wall": (0.25, "suction passage in the head, 10 cm2 x 250 W/(m2 K)"),
    "discharge_chamber_cylinder_wall": (0.6, "discharge chamber, 20 cm2 x 300 W/(m2 K)"),
    "cylinder_wall_shell_gas": (1.0, "block and head outside, 0.03 m2 x 30 W/(m2 K)"),
    "cylinder_wall_oil": (1.0, "oil splashed on the block and in the bearings"),
    "discharge_muffler_shell_gas": (0.4, "muffler and internal line, 0.013 m2 x 30 W/(m2 K)"),
    "discharge_muffler_shell": (0.05, "discharge tube brazed through the shell"),
    "motor_shell_gas": (1.5, "stator and rotor surfaces, 0.03 m2 x 50 W/(m2 K)"),
    "motor_oil": (0.5, "oil thrown on the windings"),
    "oil_shell": (3.0, "sump on the shell bottom, 0.015 m2 x 200 W/(m2 K)"),
    "shell_gas_shell": (2.0, "shell inside, 0.1 m2 x 20 W/(m2 K)"),
}
#: Shell to ambient [W/K]: natural convection and radiation in still air (module notes).
DEFAULT_SHELL_AMBIENT = 1.5

THERMAL_SPEC: Spec = {
    **{
        f"ua_{name}": Field(
            _UA, value, lo=0.0, hi=1000.0, doc=doc, plausible=(0.3 * value, 3.0 * value),
            plausible_source=f"0.3-3x the default, an estimate: {doc}",
        )
        for name, (value, doc) in DEFAULT_CONDUCTANCES.items()
    },
    "ua_discharge_muffler_suction_muffler": Field(
        _UA, 0.0, lo=0.0, hi=1000.0,
        doc="the discharge muffler or line touching, or routed along, the suction muffler "
        "(0: apart, the usual layout)",
        plausible=(0.0, 0.3),
        plausible_source="a line within a few mm of a plastic muffler over ~0.01 m2 at up to "
        "30 W/(m2 K) (radiation and gas film): at most 0.3 W/K, an estimate; Ribas et al. "
        "(2008) name the discharge line among the suction gas's heat sources",
    ),
    "ua_shell_ambient": Field(
        _UA, DEFAULT_SHELL_AMBIENT, lo=0.0, hi=1000.0, open_lo=True,
        doc="natural convection and radiation in still air, 12 W/(m2 K) x 0.12 m2",
        plausible=(0.3 * DEFAULT_SHELL_AMBIENT, 3.0 * DEFAULT_SHELL_AMBIENT),
        plausible_source="0.3-3x the default, an estimate: 12 W/(m2 K) x 0.12 m2",
    ),
    "direct_suction_fraction": Field(
        "dimensionless", 0.5, lo=0.0, hi=1.0,
        doc="share of the inlet flow entering the suction muffler unmixed (estimate)",
        plausible=(0.0, 1.0), plausible_source="a design choice from indirect (0) to direct "
        "(1) suction; no narrower range is known (household compressors use all three)",
    ),
    "friction_wall_fraction": Field(
        "dimensionless", 0.3, lo=0.0, hi=1.0,
        doc="share of the friction released at the piston (estimate); the rest in the oil",
    ),
    "motor_loss_power": Field(
        "W", None, lo=0.0, hi=1e5, doc="fixed motor loss; not set: the motor model's, else 0"
    ),
    "friction_power": Field(
        "W", None, lo=0.0, hi=1e5, doc="fixed friction; not set: the friction model's, else 0"
    ),
    "suction_muffler_loss_coefficient": Field(
        "dimensionless", 0.0, lo=0.0, hi=1000.0, doc="K of dp = K rho v^2 / 2 (0: no drop)",
        plausible=(0.5, 5.0), plausible_source="a tube's entry 0.5 and exit 1.0 (Idelchik) "
        "and a few tubes or bends in series; not the pulsation's factor on the mean v^2",
    ),
    "suction_muffler_flow_area": Field(
        "m^2", 3.0e-5, lo=0.0, hi=0.01, open_lo=True, doc="area of v (6.2 mm tube)"
    ),
    "suction_muffler_tube_length": Field(
        "m", 0.0, lo=0.0, hi=1.0, doc="length of the tube of area ..._flow_area (Darcy f L/D)"
    ),
    "suction_pulsation_factor": Field(
        "dimensionless", 1.0, lo=1.0, hi=HALF_SINE_VELOCITY_SQUARE_FACTOR,
        doc="mean(v^2)/mean(v)^2 in the tube: 1 smoothed, pi^2/4 a half-sine draw",
    ),
    "suction_muffler_gas_side_area": Field(
        "m^2", None, lo=0.0, hi=1.0, open_lo=True,
        doc="wetted area of the muffler's inside; its link to the shell gas is then this "
        "film (Dittus-Boelter, pulsating) in series with ua_suction_muffler_shell_gas",
        plausible=(2e-3, 2e-2),
        plausible_source="the chambers and tubes of a household suction muffler, 20-200 cm2 "
        "(an engineering estimate)",
    ),
    "suction_passage_gas_side_area": Field(
        "m^2", None, lo=0.0, hi=1.0, open_lo=True,
        doc="wetted area of the suction passage in the head and plate; its link to the "
        "cylinder wall is then this film in series with ua_suction_muffler_cylinder_wall",
        plausible=(5e-4, 3e-3),
        plausible_source="the suction passage in the head and the valve plate of a 5-10 cm3 "
        "compressor, 5-30 cm2 (an engineering estimate)",
    ),
    "discharge_muffler_loss_coefficient": Field(
        "dimensionless", 0.0, lo=0.0, hi=1000.0, doc="K of dp = K rho v^2 / 2 (0: no drop)"
    ),
    "discharge_muffler_flow_area": Field(
        "m^2", 7.0e-6, lo=0.0, hi=0.01, open_lo=True, doc="area of v (3 mm tube)"
    ),
    "discharge_muffler_tube_length": Field(
        "m", 0.0, lo=0.0, hi=5.0, doc="length of the tube of area ..._flow_area (Darcy f L/D)"
    ),
    "discharge_pulsation_factor": Field(
        "dimensionless", 1.0, lo=1.0, hi=20.0, doc="mean(v^2)/mean(v)^2 in the tube"
    ),
}  # fmt: skip


@dataclass(frozen=True)
class ThermalSpec:
    """The ``[thermal]`` table in SI.

    Attributes
    ----------
    conductances : tuple of float
        UA of each link of :data:`~recipsim.physics.thermo.shell_network.LINKS` [W/K].
    shell_ambient : float
        [W/K].
    direct_suction_fraction, friction_wall_fraction : float
        [-].
    motor_loss_power, friction_power : float
        Fixed sources [W]; NaN: from the models when present, else 0.
    suction_muffler_loss_coefficient, discharge_muffler_loss_coefficient : float
        [-].
    suction_muffler_flow_area, discharge_muffler_flow_area : float
        [m2].
    suction_muffler_tube_length, discharge_muffler_tube_length : float
        [m].
    suction_pulsation_factor, discharge_pulsation_factor : float
        mean(v^2) / mean(v)^2 in the muffler tubes [-].
    suction_muffler_gas_side_area, suction_passage_gas_side_area : float
        Gas-side wetted areas [m2] of the suction muffler and of the suction passage;
        NaN: the links' conductances are the fixed UA values.
    """

    conductances: tuple[float, ...]
    shell_ambient: float
    direct_suction_fraction: float
    friction_wall_fraction: float
    motor_loss_power: float
    friction_power: float
    suction_muffler_loss_coefficient: float
    suction_muffler_flow_area: float
    discharge_muffler_loss_coefficient: float
    discharge_muffler_flow_area: float
    suction_muffler_tube_length: float = 0.0
    suction_pulsation_factor: float = 1.0
    suction_muffler_gas_side_area: float = math.nan
    suction_passage_gas_side_area: float = math.nan
    discharge_muffler_tube_length: float = 0.0
    discharge_pulsation_factor: float = 1.0

    @property
    def suction_tube(self) -> tuple[float, float, float, float]:
        """The suction muffler's tube: K [-], flow area [m2], length [m], pulsation [-]."""
        return (
            self.suction_muffler_loss_coefficient, self.suction_muffler_flow_area,
            self.suction_muffler_tube_length, self.suction_pulsation_factor,
        )  # fmt: skip

    @property
    def discharge_tube(self) -> tuple[float, float, float, float]:
        """The discharge muffler's tube and line: K [-], flow area [m2], length [m],
        pulsation [-]."""
        return (
            self.discharge_muffler_loss_coefficient, self.discharge_muffler_flow_area,
            self.discharge_muffler_tube_length, self.discharge_pulsation_factor,
        )  # fmt: skip

    def network(self, ambient_temperature: float) -> NetworkParameters:
        """The network's parameters at ``ambient_temperature`` [K]."""
        return NetworkParameters(
            conductances=self.conductances,
            shell_ambient=self.shell_ambient,
            ambient_temperature=ambient_temperature,
            direct_suction_fraction=self.direct_suction_fraction,
            friction_wall_fraction=self.friction_wall_fraction,
        )


def parse_thermal(data: Any, file: str) -> ThermalSpec:
    """Read the ``[thermal]`` table (``None``: every default).

    Raises
    ------
    CaseError
        Naming the file, the key and the allowed range.
    """
    v = read_table(data, THERMAL_SPEC, file, "thermal")

    def maybe(key: str) -> float:
        return math.nan if v[key] is None else float(v[key])

    return ThermalSpec(
        conductances=tuple(float(v[f"ua_{name}"]) for name in LINK_NAMES),
        shell_ambient=float(v["ua_shell_ambient"]),
        direct_suction_fraction=float(v["direct_suction_fraction"]),
        friction_wall_fraction=float(v["friction_wall_fraction"]),
        motor_loss_power=maybe("motor_loss_power"),
        friction_power=maybe("friction_power"),
        suction_muffler_loss_coefficient=float(v["suction_muffler_loss_coefficient"]),
        suction_muffler_flow_area=float(v["suction_muffler_flow_area"]),
        discharge_muffler_loss_coefficient=float(v["discharge_muffler_loss_coefficient"]),
        discharge_muffler_flow_area=float(v["discharge_muffler_flow_area"]),
        suction_muffler_tube_length=float(v["suction_muffler_tube_length"]),
        suction_pulsation_factor=float(v["suction_pulsation_factor"]),
        suction_muffler_gas_side_area=maybe("suction_muffler_gas_side_area"),
        suction_passage_gas_side_area=maybe("suction_passage_gas_side_area"),
        discharge_muffler_tube_length=float(v["discharge_muffler_tube_length"]),
        discharge_pulsation_factor=float(v["discharge_pulsation_factor"]),
    )
