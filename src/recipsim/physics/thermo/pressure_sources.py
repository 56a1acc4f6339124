"""The pressure source of the cylinder (``options.pressure``): the slot's registry.

``cylinder`` solves the gas in the cylinder (:mod:`recipsim.physics.thermo.cylinder_rhs`:
valves, leakage, heat transfer); ``tabulated`` reads the cylinder pressure from a curve
against the crank angle (``[pressure_curve]``, interpolated by the mechanism's tabulated
pressure load). Both are declared here.

Adding a source: its compiled pressure load, its :class:`PressureSource` entry with a
new ``code`` listed in :data:`PRESSURE_SOURCES`, and the scene that runs it
(``model/scenes.py``, the model builder's scene choice); test it against the cylinder
model on the same cycle.
"""

from __future__ import annotations

from dataclasses import dataclass

from recipsim.slots import ModelChoice, Slot


@dataclass(frozen=True)
class PressureSource(ModelChoice):
    """A pressure source; ``solves_gas``: the cylinder's gas is a state of the model
    (mass flows, valves, the thermodynamic summary), else the pressure is given.
    ``label``: how a report's title names it."""

    solves_gas: bool = True
    label: str = ""


CYLINDER = PressureSource(
    name="cylinder",
    code=0,
    summary="the cylinder's gas solved with its valves, leakage and heat transfer",
    label="cylinder model",
)
TABULATED = PressureSource(
    name="tabulated",
    code=1,
    summary="cylinder pressure read from a curve against the crank angle ([pressure_curve])",
    source="a measured or published indicator diagram",
    solves_gas=False,
    label="tabulated pressure",
)

#: The ``options.pressure`` slot.
PRESSURE_SOURCES: Slot[PressureSource] = Slot(
    option="options.pressure",
    doc="pressure source",
    choices=(CYLINDER, TABULATED),
    default=CYLINDER.name,
)
