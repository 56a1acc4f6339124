"""The valve models (``options.valves``): the slot's registry and its compiled dispatch.

Each choice is a :class:`~recipsim.physics.thermo.valve_choice.ValveModel` (a
:class:`~recipsim.slots.ModelChoice` with the capabilities the builder, the solver and
the results need). ``ideal``, ``quasi_static``
and ``reed`` are declared here: their laws are a few lines of
:mod:`recipsim.physics.thermo.cylinder_rhs` (the ideal valves' pressure constraint),
:func:`~recipsim.physics.thermo.flow.reed_flow_area` and the reed events of
:mod:`recipsim.physics.thermo.cylinder_events`; their codes are the layout's
``VALVES_*`` constants. A choice with its own law has its own module beside this one
(``jet_reed``: the flow-momentum force from the port geometry).

Adding a valve model
--------------------
1. Write its module in ``physics/thermo/`` with its compiled functions under the
   signatures of this module's dispatch (:func:`valve_flow_area`,
   :func:`reed_opening_force`) and its
   :class:`~recipsim.physics.thermo.valve_choice.ValveModel` entry (a new ``code``).
2. Import the entry here, list it in :data:`VALVE_MODELS`, and add one
   ``if code == mod.CODE`` branch to each dispatch function it changes (numba compiles
   the dispatch statically: an explicit ``if`` chain on codes is the accepted form) and
   to :func:`moves_reeds` if its reeds move.
3. Test it against a closed form or another model's limit, and show it in a case or a
   docs page. The case schema, the model builder, the bench ladder and the docs read
   this registry.
"""

from __future__ import annotations

import math

from numba import njit

from recipsim.physics.thermo import cylinder as cyl
from recipsim.physics.thermo import jet_reed
from recipsim.physics.thermo.flow import reed_flow_area
from recipsim.physics.thermo.valve_choice import ValveModel
from recipsim.slots import Slot

IDEAL = ValveModel(
    name="ideal",
    code=cyl.VALVES_IDEAL,
    summary="lossless: an open valve holds the cylinder at its plenum's pressure",
    source="the indicated cycle of a lossless machine (no valve data read)",
    uses_valve_data=False,
    event_functions=(0, 2),
    fidelity=0,
)
QUASI_STATIC = ValveModel(
    name="quasi_static",
    code=cyl.VALVES_QUASI_STATIC,
    summary="isentropic-nozzle flow through the port whenever the pressure drives it, "
    "no reed state, no back-flow",
    source="a valve that opens and shuts instantly (flow: flow.nozzle_mass_flux)",
    fidelity=1,
)
REED = ValveModel(
    name="reed",
    code=cyl.VALVES_REED,
    summary="1-DOF spring-mass reed per valve: effective force (force_coefficient x port "
    "area) and flow areas, seat and stop impacts with restitution, optional jet momentum",
    source="Soedel, Design and Mechanics of Compressor Valves (1984); Bell et al., PDSim "
    "(2013), Eq. 14-15",
    moves_reeds=True,
    event_functions=(0, 1, 2, 3),
    fidelity=2,
)

#: The ``options.valves`` slot.
VALVE_MODELS: Slot[ValveModel] = Slot(
    option="options.valves",
    doc="valve model",
    choices=(IDEAL, QUASI_STATIC, REED, jet_reed.JET_REED),
    default=REED.name,
)


@njit(cache=True)
def moves_reeds(code: int) -> bool:
    """Whether the valve model ``code`` has moving reeds (states, back-flow, events)."""
    return code == cyl.VALVES_REED or code == jet_reed.CODE


@njit(cache=True)
def valve_flow_area(code: int, lift: float, par, base: int) -> float:
    """Effective flow area [m2] of one valve of model ``code`` at ``lift`` [m]
    (``par[base:]`` its row of :data:`~recipsim.physics.thermo.cylinder.VALVE`);
    0 for the ideal valves, whose flow is a constraint."""
    if code == cyl.VALVES_REED or code == jet_reed.CODE:
        return reed_flow_area(
            lift, par[base + cyl.V_PORT_D], par[base + cyl.V_CURTAIN_D], par[base + cyl.V_CFLOW]
        )
    if code == cyl.VALVES_QUASI_STATIC:
        return par[base + cyl.V_CFLOW] * 0.25 * math.pi * par[base + cyl.V_PORT_D] ** 2
    return 0.0


@njit(cache=True)
def reed_opening_force(
    code: int, dp_open: float, mdot: float, rho_up: float, jet_force: float, par, base: int
) -> float:
    """Net opening force on one reed of model ``code``, spring and damping excluded [N].

    Parameters
    ----------
    code : int
        The valve model's code.
    dp_open : float
        Pressure difference pushing the reed open (seat side minus stop side) [Pa].
    mdot : float
        Mass flow through the valve along its opening direction [kg/s] (negative:
        back-flow).
    rho_up : float
        Density upstream of that flow [kg/m3].
    jet_force : float
        The reed law's jet momentum force along the opening direction [N] (0 unless the
        valve's ``momentum_force`` flag is set).
    par : ndarray
        The float parameters; ``par[base:]`` is the valve's row.
    """
    if code == jet_reed.CODE:
        return jet_reed.jet_reed_force(
            dp_open, mdot, rho_up, par[base + cyl.V_PORT_D], par[base + cyl.V_PRELOAD]
        )
    return par[base + cyl.V_AFORCE] * dp_open - par[base + cyl.V_PRELOAD] + jet_force
