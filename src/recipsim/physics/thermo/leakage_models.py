"""The piston-cylinder leakage (``options.leakage``) and its gap law (``leakage.model``):
the two slots' registries.

``none`` and ``piston_gap`` are declared here (the gap flow is a few lines of
:mod:`recipsim.physics.thermo.cylinder_rhs`); the gap laws ``isothermal`` and
``incompressible`` beside their functions in :mod:`recipsim.physics.thermo.flow`. The
compiled code reads one code, ``I_LEAK``: ``LEAK_NONE`` or the gap law's
(:func:`leakage_code`).

Adding a gap law: its compiled function (in ``flow.py`` or its own module), its
:class:`~recipsim.slots.ModelChoice` with a new ``code`` listed in :data:`GAP_LAWS`,
and one ``elif ipar[cyl.I_LEAK] == CODE`` branch where ``cylinder_rhs`` computes the
gap flow; test it against a closed form (the laminar annulus).
"""

from __future__ import annotations

from dataclasses import dataclass

from recipsim.physics.thermo import cylinder as cyl
from recipsim.physics.thermo.flow import INCOMPRESSIBLE_GAP, ISOTHERMAL_GAP
from recipsim.slots import ModelChoice, Slot


@dataclass(frozen=True)
class LeakageModel(ModelChoice):
    """A leakage choice; ``leaks``: gas passes the piston (its law is ``leakage.model``,
    the property callback then computes the viscosity)."""

    leaks: bool = False


NO_LEAKAGE = LeakageModel(name="none", code=cyl.LEAK_NONE, summary="a gas-tight piston")
PISTON_GAP = LeakageModel(
    name="piston_gap",
    code=1,  # the slot's own numbering; the compiled code is the gap law's
    summary="laminar flow through the radial clearance between piston and bore "
    "([leakage]: clearance, eccentricity, law)",
    source="Prata, Fernandes & Fagotti (clearances); the gap laws of leakage.model",
    leaks=True,
)

#: The ``options.leakage`` slot.
LEAKAGE: Slot[LeakageModel] = Slot(
    option="options.leakage",
    doc="piston-cylinder leakage",
    choices=(NO_LEAKAGE, PISTON_GAP),
    default=NO_LEAKAGE.name,
)

#: The ``leakage.model`` slot: the gap's flow law.
GAP_LAWS: Slot[ModelChoice] = Slot(
    option="leakage.model",
    doc="gap law: compressible isothermal (mean-pressure density) or upstream density",
    choices=(ISOTHERMAL_GAP, INCOMPRESSIBLE_GAP),
    default=ISOTHERMAL_GAP.name,
)


def leakage_code(option: str, law: str) -> int:
    """The compiled code ``I_LEAK`` of ``options.leakage = option`` with
    ``leakage.model = law``."""
    return GAP_LAWS[law].code if LEAKAGE[option].leaks else cyl.LEAK_NONE
