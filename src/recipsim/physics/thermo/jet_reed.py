"""The jet reed (``options.valves = "jet_reed"``): the reed valve whose opening force is
the momentum balance of the gas under it, with a force coefficient that follows from the
port geometry instead of a constant.

The reed moves, seats, stops and passes gas as the ``reed`` model does (lift and
velocity states, the curtain or port flow area :func:`~recipsim.physics.thermo.flow.
reed_flow_area`, restitution at seat and stop). Only the force differs. Take the gas
between the port's exit plane and the curtain: it enters through the port (area
``A_p``) at the velocity ``V_p = mdot / (rho A_p)``, leaves radially through the
curtain, so its momentum normal to the reed, ``mdot V_p``, is given up to the reed; the
static pressure in the port is the upstream pressure less the jet's dynamic head
``q_p = rho V_p^2 / 2`` (Bernoulli). The force on the reed is then::

    F = (p_port - p_down) A_p + mdot V_p = A_p (dp + q_p)          (minus the preload)

and its force coefficient over the port area ``C_F = F / (dp A_p) = 1 + q_p / dp``.
With the nozzle flow through the effective area ``A_e = C min(pi d_c x, A_p)``, in the
incompressible limit ``q_p / dp = (A_e / A_p)^2``::

    C_F(x) = 1 + (C min(pi d_c x, pi d_p^2 / 4) / (pi d_p^2 / 4))^2

from the port diameter ``d_p``, the curtain diameter ``d_c`` and the flow coefficient
``C``: 1 at small lift (the static reed law over the port), rising with the lift to
``1 + C^2`` once the port is the throat, and 2 for a loss-free port: the momentum
balance of a free jet on a disk (``F = rho V^2 A = 2 dp A``). PDSim's valve model
(Bell et al., "PDSim: a general quasi-steady modeling approach for positive
displacement compressors and expanders", 2013) switches between the same two regimes at
the lift where the curtain equals the port (``x_tr = d_p^2 / (4 d_c)``), with a
pressure force below it and the jet's momentum ``rho V^2 A_port`` plus a drag term above;
here the momentum balance joins them continuously and needs no drag coefficient.

Left out: the pressure on the reed's overlap beyond the port (the radial diffuser
under the reed, which adds to the force at small lift: what the ``reed`` model's
``force_coefficient`` above 1 stands for) and the reed's own velocity in the jet's
relative velocity. The jet reed reads neither ``force_coefficient`` nor
``momentum_force`` (its force coefficient comes from the geometry, its jet momentum is
part of the balance); a case keeps both keys for the ``reed`` model.
"""

from __future__ import annotations

import math

from numba import njit

from recipsim.physics.thermo.valve_choice import ValveModel

#: the compiled code of the jet reed (``ipar[I_VALVES]``)
CODE = 3


@njit(cache=True)
def port_dynamic_pressure(mdot: float, rho: float, port_diameter: float) -> float:
    """Signed dynamic head of the flow in the port, ``mdot |mdot| / (2 rho A_p^2)`` [Pa]
    (positive along the reed's opening direction)."""
    area = 0.25 * math.pi * port_diameter * port_diameter
    return mdot * abs(mdot) / (2.0 * rho * area * area)


@njit(cache=True)
def jet_reed_force(
    dp_open: float, mdot: float, rho_up: float, port_diameter: float, preload: float
) -> float:
    """Opening force on the reed, ``A_p (dp + q_p) - preload`` [N].

    Parameters
    ----------
    dp_open : float
        Pressure difference pushing the reed open [Pa].
    mdot : float
        Mass flow through the valve along the opening direction [kg/s].
    rho_up : float
        Density upstream of the flow [kg/m3] (the port's gas: its expansion up to the
        port is left out, as in the incompressible balance).
    port_diameter : float
        Port diameter [m].
    preload : float
        Preload holding the reed on its seat [N].
    """
    area = 0.25 * math.pi * port_diameter * port_diameter
    q_port = port_dynamic_pressure(mdot, rho_up, port_diameter) if rho_up > 0.0 else 0.0
    return area * (dp_open + q_port) - preload


def force_coefficient(
    lift: float, port_diameter: float, curtain_diameter: float, flow_coefficient: float
) -> float:
    """The jet reed's force coefficient ``C_F = F / (dp A_p)`` in the incompressible
    limit, ``1 + (A_e / A_p)^2`` with ``A_e`` the valve's effective flow area [-]."""
    port = 0.25 * math.pi * port_diameter**2
    effective = flow_coefficient * min(math.pi * curtain_diameter * max(lift, 0.0), port)
    return 1.0 + (effective / port) ** 2


JET_REED = ValveModel(
    name="jet_reed",
    code=CODE,
    summary="the reed with the gas's momentum balance as its force: A_p (dp + rho V_p^2/2), "
    "a force coefficient 1 + (A_eff/A_port)^2 from the port and curtain geometry (1 at "
    "small lift, 2 for a free jet on a disk)",
    source="momentum balance of the port's jet on the reed; PDSim's valve model (Bell et "
    "al. 2013) for the two regimes it joins",
    moves_reeds=True,
    event_functions=(0, 1, 2, 3),
    fidelity=3,
)
