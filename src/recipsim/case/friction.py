"""The friction sources beside the journals and the piston (``[friction]``), read once.

Used with ``options.friction = "mean"`` (:mod:`recipsim.model.loss_sources`); validated
whenever present. The defaults describe a 5-10 cm3 household compressor on a vertical
shaft, every one an estimate stated here:

- the thrust bearing carries the rotor and crankshaft (``mechanism.rotor.mass`` times g)
  on a flat annular collar (``thrust_bearing = "collar"``): the crank web's face on the
  top of the main bearing's boss, fed with oil by the shaft's helical groove, the sliding
  thrust bearing of refrigerator reciprocating compressors that Nagata et al. (Purdue
  ICEC 2012, paper 2161; Trans. JSRAE 30(3), 2013) improve on; inner diameter the main
  journal's (16 mm in the reference compressor), outer diameter 26 mm (the boss's face,
  about 1.6 times the journal), and a 10 um film (the journals' radial clearance's
  order; a parallel film's thickness is set by its thermal wedge and roughness, not by
  a wedge theory). ``"ball"``: a thrust
  ball bearing (some designs carry the rotor on a ball cage) at SKF's constant friction
  coefficient 0.0013, the ball track at the collar's mean diameter; ``"none"``: left out;
- the oil pump: a pick-up tube and an eccentric bore in the shaft's lower end (a
  centrifugal stage) and a helical groove (Posch et al. 2015), delivering 1 cm3/s (an
  estimate of the order of the films' side leakage plus the oil thrown from the shaft
  top) from an outlet 5 mm off the axis, lifted 60 mm from the sump's surface to the
  crank web. Its power is milliwatts: Euler's equation, not the estimate, makes it so.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from recipsim.errors import CaseError
from recipsim.schema import Choice, Field, Spec, read_table

#: Standard gravity [m/s2].
GRAVITY = 9.80665
#: Choices of ``thrust_bearing``.
THRUST_BEARINGS = ("collar", "ball", "none")

FRICTION_SPEC: Spec = {
    "thrust_bearing": Choice(
        THRUST_BEARINGS, "collar",
        "the bearing that carries the rotor and crankshaft's weight: a flat annular collar "
        "on an oil film, a thrust ball bearing, or none",
    ),
    "thrust_inner_diameter": Field(
        "m", 0.016, lo=0.0, hi=0.5, open_lo=True,
        doc="inner diameter of the thrust annulus (the main journal's, estimate)",
    ),
    "thrust_outer_diameter": Field(
        "m", 0.026, lo=0.0, hi=0.5, open_lo=True,
        doc="outer diameter of the thrust annulus, above the inner (the boss's face, estimate)",
    ),
    "thrust_film_thickness": Field(
        "m", 10e-6, lo=0.0, hi=1e-3, open_lo=True,
        doc="collar: the film's axial thickness (estimate: the journals' clearance's order)",
    ),
    "thrust_load": Field(
        "N", None, lo=0.0, hi=1e5,
        doc="ball: the axial load; not set: mechanism.rotor.mass times g",
    ),
    "thrust_ball_friction_coefficient": Field(
        "dimensionless", 0.0013, lo=0.0, hi=0.1,
        doc="ball: constant friction coefficient (SKF catalogue, thrust ball bearings)",
    ),
    "oil_pump_flow": Field(
        "m**3/s", 1e-6, lo=0.0, hi=1e-3,
        doc="oil the shaft pumps (estimate; 0: no pump term)",
    ),
    "oil_pump_outlet_radius": Field(
        "m", 0.005, lo=0.0, hi=0.1,
        doc="radius at which the oil leaves the centrifugal stage (estimate)",
    ),
    "oil_pump_lift": Field(
        "m", 0.06, lo=0.0, hi=1.0, doc="sump surface to the crank web (estimate)"
    ),
}  # fmt: skip


@dataclass(frozen=True)
class FrictionSpec:
    """``[friction]`` in SI (attributes as the keys; ``thrust_load`` NaN: the rotor's
    weight)."""

    thrust_bearing: str = "collar"
    thrust_inner_diameter: float = 0.016
    thrust_outer_diameter: float = 0.026
    thrust_film_thickness: float = 10e-6
    thrust_load: float = math.nan
    thrust_ball_friction_coefficient: float = 0.0013
    oil_pump_flow: float = 1e-6
    oil_pump_outlet_radius: float = 0.005
    oil_pump_lift: float = 0.06

    def thrust_force(self, rotor_mass: float) -> float:
        """Axial load of the thrust bearing [N]: the given one, else the rotor's weight."""
        return rotor_mass * GRAVITY if math.isnan(self.thrust_load) else self.thrust_load


def parse_friction(data: Any, file: str) -> FrictionSpec:
    """Read the ``[friction]`` table (``None``: every default).

    Raises
    ------
    CaseError
        Naming the file, the key and the allowed range (an outer diameter not above the
        inner one among them).
    """
    v = read_table(data, FRICTION_SPEC, file, "friction")
    if v["thrust_outer_diameter"] <= v["thrust_inner_diameter"]:
        raise CaseError(
            file,
            "friction.thrust_outer_diameter",
            f"{v['thrust_outer_diameter']!r} m; allowed: above thrust_inner_diameter "
            f"({v['thrust_inner_diameter']!r} m)",
        )
    load = math.nan if v["thrust_load"] is None else float(v["thrust_load"])
    return FrictionSpec(
        thrust_bearing=str(v["thrust_bearing"]),
        thrust_inner_diameter=float(v["thrust_inner_diameter"]),
        thrust_outer_diameter=float(v["thrust_outer_diameter"]),
        thrust_film_thickness=float(v["thrust_film_thickness"]),
        thrust_load=load,
        thrust_ball_friction_coefficient=float(v["thrust_ball_friction_coefficient"]),
        oil_pump_flow=float(v["oil_pump_flow"]),
        oil_pump_outlet_radius=float(v["oil_pump_outlet_radius"]),
        oil_pump_lift=float(v["oil_pump_lift"]),
    )
