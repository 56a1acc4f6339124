"""The crank-train slot (``options.mechanics``): how the bodies between the rotor and the
piston move.

Choices, declared here beside the models they pick:

- ``pinned``: the rigid slider-crank at constant speed; bearing reactions and the drive
  torque follow by inverse dynamics (:mod:`.pinned`);
- ``flexible``: rotor, connecting rod and piston on their bearings, integrated in time
  (:mod:`.flexible`).

The crank train picks the compiled scene together with ``options.pressure``
(:mod:`recipsim.model.scenes`), so no compiled code dispatches on this slot's code. A new
crank train is a new scene: add its entry here, with the capability flags its model
builder and the results read, and its scene in :mod:`recipsim.model.scenes`.
"""

from __future__ import annotations

from dataclasses import dataclass

from recipsim.slots import ModelChoice, Output, Slot


@dataclass(frozen=True)
class CrankTrain(ModelChoice):
    """A crank-train model.

    Attributes
    ----------
    flexible : bool
        The bodies ride on their bearings (state variables) and the crank speed may vary
        under a drive; False: the rigid slider-crank, at constant speed by definition.
    """

    flexible: bool = False


PINNED = CrankTrain(
    name="pinned",
    code=0,
    summary="rigid slider-crank at constant speed; bearing loads by inverse dynamics",
    source="textbook slider-crank kinematics and Newton-Euler inverse dynamics",
)
FLEXIBLE = CrankTrain(
    name="flexible",
    code=1,
    summary="rotor, connecting rod and piston on their bearings, integrated in time",
    source="Kurka, Paulino & Izuka (ISMA 2010)",
    outputs=(
        Output("mechanical_efficiency", "-", "indicated power / shaft power", "summary"),
        Output(
            "mechanical_balance_residual",
            "-",
            "(shaft power - indicated power - bearing dissipation) / shaft power over the "
            "converged revolution: the closure of the mechanical energy chain",
            "summary",
        ),
    ),
    flexible=True,
)

#: The registry of ``options.mechanics``.
CRANK_TRAINS: Slot[CrankTrain] = Slot(
    option="options.mechanics", doc="crank train", choices=(PINNED, FLEXIBLE), default=PINNED.name
)
