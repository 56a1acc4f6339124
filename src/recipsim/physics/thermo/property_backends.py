"""The property backend (``options.properties``): the slot's registry.

Both choices are declared here, each a line beside the module that implements it:
``heos`` calls CoolProp's Helmholtz equation of state through the compiled callback of
:mod:`recipsim.physics.thermo.properties`; ``table`` interpolates a cached table of the
same (:mod:`recipsim.physics.thermo.property_table`), calling HEOS where it has no
data. The compiled code reads ``I_PROPS`` (``PROPS_*`` in the cylinder's layout).

Adding a backend: its module (a point-state calculator answering what
:class:`~recipsim.physics.thermo.fluid.Fluid` answers, and the compiled property call
filling the property buffer), its :class:`PropertyBackend` entry with a new ``code``
listed in :data:`PROPERTY_BACKENDS`, and one branch where ``cylinder_rhs`` calls the
properties; test it against HEOS.
"""

from __future__ import annotations

from dataclasses import dataclass

from recipsim.physics.thermo import cylinder as cyl
from recipsim.slots import ModelChoice, Slot


@dataclass(frozen=True)
class PropertyBackend(ModelChoice):
    """A property backend; ``tabulated``: it interpolates the refrigerant's cached table
    (built on first use, `recipsim warmup`)."""

    tabulated: bool = False


HEOS = PropertyBackend(
    name="heos",
    code=cyl.PROPS_HEOS,
    summary="CoolProp's Helmholtz equation of state at every call",
    source="CoolProp HEOS (Bell et al. 2014)",
)
TABLE = PropertyBackend(
    name="table",
    code=cyl.PROPS_TABLE,
    summary="interpolated cached table of HEOS (its measured error in the provenance), "
    "HEOS where it has no data",
    source="bicubic interpolation of CoolProp HEOS states",
    tabulated=True,
)

#: The ``options.properties`` slot.
PROPERTY_BACKENDS: Slot[PropertyBackend] = Slot(
    option="options.properties",
    doc="property backend",
    choices=(HEOS, TABLE),
    default=HEOS.name,
)
