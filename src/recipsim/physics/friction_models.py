"""The friction slot (``options.friction``): the mechanical friction the shaft pays.

Choices, declared here beside the laws they pick:

- ``off``: no mechanical friction;
- ``mean``: the concentric-film limits of :mod:`.mean_friction` (Petroff journals,
  viscous skirt), the thrust bearing and the oil pump, evaluated on the converged
  cycle from ``[friction]`` and ``[oil]``;
- ``films``: the oil films of the bearings themselves, already part of the flexible
  crank's dynamics (their dissipation is in the cycle's columns).

The slot has no fixed default: a case that names none gets ``films`` where the flexible
crank runs a bearing on an oil film, else ``off`` (:func:`default_friction`). Friction
is evaluated after the cycle (numpy), so no compiled code dispatches on this slot. A
new friction model: its entry here with the flags the results read, and its law beside
:mod:`.mean_friction`.
"""

from __future__ import annotations

from dataclasses import dataclass

from recipsim.slots import ModelChoice, Output, Slot


@dataclass(frozen=True)
class FrictionModel(ModelChoice):
    """A mechanical-friction model.

    Attributes
    ----------
    mean_laws : bool
        Its power is the mean friction of :mod:`.mean_friction` added to the drive's
        (shaft power = drive power + friction power).
    on_films : bool
        It is the bearings' own films: it needs the flexible crank with a bearing on an
        oil film, and such a crank takes no other.
    """

    mean_laws: bool = False
    on_films: bool = False


NO_FRICTION = FrictionModel(
    name="off",
    code=0,
    summary="no mechanical friction",
    source="ideal machine",
)
MEAN_FRICTION = FrictionModel(
    name="mean",
    code=1,
    summary="Petroff journals, viscous skirt, thrust bearing and oil pump ([friction], "
    "[oil]) on the converged cycle",
    source="Hamrock, Fundamentals of Fluid Film Lubrication, ch. 8; PDSim's skirt loss",
    outputs=(
        Output(
            "friction_power_<name>",
            "W",
            "Petroff's 2 pi mu R^3 L w^2 / c of each journal with film data (w: crank speed; "
            "eccentric: crank minus rod spin; pin: rod spin)",
            "summary",
        ),
        Output(
            "piston_friction_power",
            "W",
            "the concentric skirt's mu pi D L v^2 / delta (L: piston length inside the bore, "
            "delta: the piston film's or else the leakage radial clearance)",
            "summary",
        ),
        Output(
            "friction_power_thrust",
            "W",
            "the thrust bearing carrying the rotor and crankshaft (`[friction]`): a flat "
            "collar's viscous torque pi mu w (R_o^4 - R_i^4) / (2 h) times w, or a ball "
            'bearing\'s mu F d / 2 times w; absent with `thrust_bearing = "none"`',
            "summary",
        ),
        Output(
            "friction_power_oil_pump",
            "W",
            "the power the shaft gives the oil it pumps, rho Q (w^2 r^2 + g H) (Euler's pump "
            "equation for the centrifugal stage, the helical groove's lift; `[friction]`)",
            "summary",
        ),
        Output(
            "friction_film_temperature",
            "K",
            "the oil temperature the films are taken at, the thermal network's oil node "
            '(`options.thermal = "network"`) or `oil.film_temperature`',
            "summary",
        ),
        Output(
            "friction_film_viscosity",
            "Pa*s",
            "the oil's dynamic viscosity at that temperature (its Walther or Vogel law), "
            "diluted by `oil.dissolved_refrigerant_fraction`",
            "summary",
        ),
    ),
    mean_laws=True,
)
FILM_FRICTION = FrictionModel(
    name="films",
    code=2,
    summary="the bearings' oil films in the flexible crank's dynamics",
    source="the bearing laws' film forces (docs: bearings)",
    on_films=True,
)

#: The registry of ``options.friction``.
FRICTION_MODELS: Slot[FrictionModel] = Slot(
    option="options.friction",
    doc="mechanical friction: none, mean (Petroff journals, viscous skirt, thrust bearing, "
    "oil pump: [friction]), or the oil films (default: films where a bearing runs on one, "
    "else off)",
    choices=(NO_FRICTION, MEAN_FRICTION, FILM_FRICTION),
    default=None,
)


def default_friction(film_bearings: bool) -> FrictionModel:
    """The friction of a case that names none: the films where the flexible crank runs a
    bearing on one (``film_bearings``), else none."""
    return FILM_FRICTION if film_bearings else NO_FRICTION
