"""The pressure source of the cylinder (``options.pressure``): the slot's registry.

``cylinder`` solves the gas in the cylinder (:mod:`recipsim.physics.thermo.cylinder_rhs`:
valves, leakage, heat transfer) and adds the gas's columns to the cycle table
(:data:`GAS_OUTPUTS`, :data:`VALVE_STATE_OUTPUTS`); ``tabulated`` reads the cylinder
pressure from a curve against the crank angle (``[pressure_curve]``, interpolated by the
mechanism's tabulated pressure load). Both are declared here.

Adding a source: its compiled pressure load, its :class:`PressureSource` entry with a
new ``code`` listed in :data:`PRESSURE_SOURCES`, and the scene that runs it
(``model/scenes.py``, the model builder's scene choice); test it against the cylinder
model on the same cycle.
"""

from __future__ import annotations

from dataclasses import dataclass

from recipsim.physics.thermo import cylinder as cyl
from recipsim.slots import ModelChoice, Output, Slot


@dataclass(frozen=True)
class PressureSource(ModelChoice):
    """A pressure source; ``solves_gas``: the cylinder's gas is a state of the model
    (mass flows, valves, the thermodynamic summary), else the pressure is given.
    ``label``: how a report's title names it."""

    solves_gas: bool = True
    label: str = ""


def _gas_output(index: int) -> Output:
    """The cycle column of the cylinder's output slot ``index`` (its name, unit, meaning)."""
    entry = cyl.OUTPUTS.entries[index]
    return Output(entry.name, entry.unit, entry.meaning, "cycle")


#: The cylinder's outputs that need its gas: the cycle table writes them (in this order,
#: among its other outputs) only where the gas is solved.
GAS_OUTPUTS: tuple[Output, ...] = tuple(
    _gas_output(i)
    for i in (
        cyl.A_TEMPERATURE,
        cyl.A_DENSITY,
        cyl.A_MASS,
        cyl.A_ENTHALPY,
        cyl.A_QUALITY,
        cyl.A_LIFT_S,
        cyl.A_LIFT_D,
        cyl.A_VEL_S,
        cyl.A_VEL_D,
        cyl.A_MDOT_SUC,
        cyl.A_MDOT_DIS,
        cyl.A_MDOT_LEAK,
        cyl.A_LEAK_ECC,
        cyl.A_QDOT,
        cyl.A_HTC,
    )
)
#: The valves' modes over the cycle, suction then discharge.
VALVE_STATE_OUTPUTS = (
    Output(
        "suction_valve_state",
        "-",
        "mode of the suction valve: reed 0 seated, 1 moving, 2 on the stop; ideal 0 closed, 1 open",
        "cycle",
    ),
    Output("discharge_valve_state", "-", "mode of the discharge valve, as above", "cycle"),
)

CYLINDER = PressureSource(
    name="cylinder",
    code=0,
    summary="the cylinder's gas solved with its valves, leakage and heat transfer",
    outputs=(*GAS_OUTPUTS, *VALVE_STATE_OUTPUTS),
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
