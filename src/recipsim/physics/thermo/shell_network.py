"""Steady lumped thermal network of a hermetic compressor's shell (quasi-steady nodes).

Eight nodes: four gas volumes whose temperature is that of the gas leaving them
(suction muffler, shell gas, discharge chamber, discharge muffler + line) and four
solids (cylinder wall and head, motor, oil, shell), joined by conductances UA [W/K]
(:data:`LINKS`) and the shell to the ambient. Gas streams are advective links::

    inlet -(f M)-> suction muffler <-> cylinder <-> discharge chamber -> discharge muffler -> outlet
    inlet -((1 - f) M)-> shell gas -((1 - f) M + L)-> suction muffler
    cylinder -(L, leakage)-> shell gas

with M the delivered mass flow, L the net piston-gap leakage into the shell and f the
share of the inlet flow that enters the suction muffler directly (semi-direct suction).
Back-flow through the suction valve enters the suction muffler with the enthalpy the
cylinder gave it; back-flow through the discharge valve is drawn from the discharge
chamber at the chamber's enthalpy (the cylinder's discharge plenum is that node).
Sources: the heat the cylinder gas gives its wall, the motor losses (motor node) and the
friction (a share on the cylinder wall for the piston, the rest in the oil).

Energy of node i (heat into it positive, W)::

    sum_j UA_ij (T_j - T_i) + sum_in m h_up - sum_out m h_i(T_i) + S_i = 0

Enthalpies are real-gas ``h(p_i, T_i)`` at each gas node's pressure (no constant-c_p
simplification): the system is solved by Newton on the eight temperatures with the
analytic Jacobian (``dh/dT = c_p`` at the node), which converges in two to four
iterations; the UA part is linear. Mass is conserved by construction: the flow from the
suction muffler into the cylinder is ``M + L + m_back`` (the cycle's net suction plus its
back-flow), so every node balance is independent of the enthalpy reference.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from recipsim.physics.thermo.shell_nodes import (
    CW,
    DC,
    DM,
    GAS_NODES,
    MO,
    N_NODES,
    NODES,
    OIL,
    SG,
    SH,
    SM,
)

#: Conductance links (node a, node b); the case key is ``"<a>_<b>"`` (``ua_`` prefixed).
LINKS = (
    (SM, SG),
    (SM, CW),
    (DC, CW),
    (CW, SG),
    (CW, OIL),
    (DM, SG),
    (DM, SH),
    (MO, SG),
    (MO, OIL),
    (OIL, SH),
    (SG, SH),
    (DM, SM),
)
LINK_NAMES = tuple(f"{NODES[a]}_{NODES[b]}" for a, b in LINKS)
#: Conductances below this are raised to it, so that a node joined to nothing takes
#: its neighbours' temperature instead of making the system singular [W/K].
UA_FLOOR = 1e-9

_NEWTON_TOL = 1e-6  # K
_NEWTON_MAX = 30
_LOAD_STEP = 1e-3  # K

#: ``state(p [Pa], T [K]) -> (h [J/kg], c_p [J/(kg K)], ...)`` of the refrigerant vapour
#: (further entries are ignored).
EnthalpyFunction = Callable[[float, float], tuple[float, ...]]


@dataclass(frozen=True)
class NetworkParameters:
    """Conductances and topology of the network (SI).

    Attributes
    ----------
    conductances : tuple of float
        UA of each link of :data:`LINKS` [W/K].
    shell_ambient : float
        UA from the shell to the ambient [W/K].
    ambient_temperature : float
        [K].
    direct_suction_fraction : float
        Share f of the inlet flow that goes straight into the suction muffler [-].
    friction_wall_fraction : float
        Share of the friction power released in the cylinder wall (the piston) [-]; the
        rest heats the oil (bearings).
    """

    conductances: tuple[float, ...]
    shell_ambient: float
    ambient_temperature: float
    direct_suction_fraction: float
    friction_wall_fraction: float


@dataclass(frozen=True)
class NetworkLoads:
    """What the cycle and the drive put into the network (SI, per second).

    Attributes
    ----------
    delivered_mass_flow : float
        M, net flow through the discharge valve [kg/s] (also the inlet and outlet flow).
    leakage_mass_flow : float
        L, net flow from the cylinder into the shell through the piston gap [kg/s].
    suction_backflow_mass_flow : float
        Mass flowing back out of the cylinder through the suction valve [kg/s].
    suction_backflow_enthalpy_flow : float
        Enthalpy it carries into the suction muffler [W].
    discharge_enthalpy_flow : float
        Enthalpy flow out of the cylinder through the discharge valve into the discharge
        chamber [W] (gross: the back-flow is drawn from the chamber at its enthalpy).
    leakage_enthalpy_flow : float
        Net enthalpy flow through the piston gap into the shell gas [W].
    heat_to_wall : float
        Mean heat from the cylinder gas to the wall [W].
    motor_loss_power, friction_power : float
        [W].
    """

    delivered_mass_flow: float
    leakage_mass_flow: float
    suction_backflow_mass_flow: float
    suction_backflow_enthalpy_flow: float
    discharge_enthalpy_flow: float
    leakage_enthalpy_flow: float
    heat_to_wall: float
    motor_loss_power: float
    friction_power: float
    #: mass flowing back into the cylinder from the discharge chamber [kg/s]
    discharge_backflow_mass_flow: float = 0.0


@dataclass(frozen=True)
class NetworkPressures:
    """Pressures of the gas nodes and the inlet state (SI).

    ``node`` holds the pressure [Pa] of each gas node, laid out by :data:`PRESSURES`
    (``GP_*``: suction muffler, shell gas, discharge chamber, discharge muffler).
    """

    inlet_pressure: float
    inlet_temperature: float
    node: tuple[float, float, float, float]


@dataclass
class NetworkSolution:
    """Node temperatures and what follows from them.

    Attributes
    ----------
    temperature : ndarray
        Node temperatures [K] in the order of :data:`NODES`.
    enthalpy : ndarray
        Gas enthalpy [J/kg] of each node (NaN for solids).
    inlet_enthalpy, outlet_enthalpy : float
        [J/kg] at the shell inlet and the discharge line outlet (the discharge muffler
        node's state at the line pressure).
    shell_heat_rejection : float
        UA (T_shell - T_ambient) [W].
    iterations : int
        Newton iterations.
    loads : NetworkLoads
        The loads solved with (at the solution's suction muffler temperature when they
        depend on it, to the last Newton step).
    """

    temperature: np.ndarray
    enthalpy: np.ndarray
    inlet_enthalpy: float
    outlet_enthalpy: float
    shell_heat_rejection: float
    iterations: int
    loads: NetworkLoads


@functools.lru_cache(maxsize=16)
def _conductance_matrix(par: NetworkParameters) -> tuple[np.ndarray, np.ndarray]:
    """Matrix K with (K T)_i = sum_j UA_ij (T_i - T_j) + UA_amb T_i and the ambient
    column b (b_i = UA_amb T_amb); cached per parameter set, never modified in place."""
    k = np.zeros((N_NODES, N_NODES))
    for (a, b), ua in zip(LINKS, par.conductances, strict=True):
        g = max(ua, UA_FLOOR)
        k[a, a] += g
        k[b, b] += g
        k[a, b] -= g
        k[b, a] -= g
    g_amb = max(par.shell_ambient, UA_FLOOR)
    k[SH, SH] += g_amb
    rhs = np.zeros(N_NODES)
    rhs[SH] = g_amb * par.ambient_temperature
    return k, rhs


def _streams(par: NetworkParameters, loads: NetworkLoads) -> tuple[float, float, float, float]:
    """Inlet flow straight to the muffler, inlet flow to the shell gas, shell gas to
    muffler, muffler to cylinder [kg/s]."""
    m = loads.delivered_mass_flow
    f = par.direct_suction_fraction
    to_shell = (1.0 - f) * m
    shell_to_muffler = to_shell + loads.leakage_mass_flow
    if shell_to_muffler < 0.0:
        raise ValueError(
            f"the shell gas loses more mass through the piston gap ({-loads.leakage_mass_flow:.4g}"
            " kg/s) than the inlet brings it: the network models a low-side shell"
        )
    into_cylinder = m + loads.leakage_mass_flow + loads.suction_backflow_mass_flow
    return f * m, to_shell, shell_to_muffler, into_cylinder


def _balance_terms(
    par: NetworkParameters,
    loads: NetworkLoads,
    temperature: np.ndarray,
    enthalpy: np.ndarray,
    h_in: float,
) -> list[list[float]]:
    """Every term of every node's energy balance [W], advective terms written against
    the node's own enthalpy (m (h_upstream - h_node)), so that they do not depend on the
    enthalpy reference."""
    terms: list[list[float]] = [[] for _ in range(N_NODES)]
    t = temperature
    for (a, b), ua in zip(LINKS, par.conductances, strict=True):
        q = max(ua, UA_FLOOR) * (t[b] - t[a])
        terms[a].append(q)
        terms[b].append(-q)
    terms[SH].append(max(par.shell_ambient, UA_FLOOR) * (par.ambient_temperature - t[SH]))
    direct, to_shell, shell_to_muffler, _ = _streams(par, loads)
    h = enthalpy
    m = loads.delivered_mass_flow
    back = loads.suction_backflow_mass_flow
    terms[SM] += [
        direct * (h_in - h[SM]),
        shell_to_muffler * (h[SG] - h[SM]),
        loads.suction_backflow_enthalpy_flow - back * h[SM],
    ]
    terms[SG] += [
        to_shell * (h_in - h[SG]),
        loads.leakage_enthalpy_flow - loads.leakage_mass_flow * h[SG],
    ]
    phi = par.friction_wall_fraction
    terms[CW] += [loads.heat_to_wall, phi * loads.friction_power]
    terms[DC].append(
        loads.discharge_enthalpy_flow - (m + loads.discharge_backflow_mass_flow) * h[DC]
    )
    terms[DM].append(m * (h[DC] - h[DM]))
    terms[MO].append(loads.motor_loss_power)
    terms[OIL].append((1.0 - phi) * loads.friction_power)
    return terms


def node_residuals(
    par: NetworkParameters,
    loads: NetworkLoads,
    solution: NetworkSolution,
) -> np.ndarray:
    """Energy imbalance of each node relative to the largest flow through it [-].

    ``|sum of terms| / max |term|`` with the terms of the node's balance (heat through
    each link, sources, and each stream as m (h_upstream - h_node)).
    """
    terms = _balance_terms(
        par, loads, solution.temperature, solution.enthalpy, solution.inlet_enthalpy
    )
    out = np.zeros(N_NODES)
    for i, node_terms in enumerate(terms):
        size = max(abs(v) for v in node_terms)
        out[i] = abs(math.fsum(node_terms)) / size if size > 0.0 else 0.0
    return out


def _assemble(
    par: NetworkParameters,
    loads: NetworkLoads,
    h_in: float,
    t: np.ndarray,
    h: np.ndarray,
    cp: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Energy residual of every node [W] at temperatures ``t`` (gas enthalpies ``h``)
    and its Jacobian for fixed loads (``c_p`` on the gas nodes)."""
    k, rhs = _conductance_matrix(par)  # cached: never modified in place
    direct, to_shell, shell_to_muffler, into_cylinder = _streams(par, loads)
    m = loads.delivered_mass_flow
    phi = par.friction_wall_fraction
    f = rhs - k @ t
    f[SM] += direct * h_in + loads.suction_backflow_enthalpy_flow
    f[SG] += to_shell * h_in + loads.leakage_enthalpy_flow
    f[CW] += loads.heat_to_wall + phi * loads.friction_power
    f[DC] += loads.discharge_enthalpy_flow
    f[MO] += loads.motor_loss_power
    f[OIL] += (1.0 - phi) * loads.friction_power
    jac = -k
    # gas leaving each gas node (muffler -> cylinder, shell gas -> muffler, chamber ->
    # discharge muffler and back into the cylinder, discharge muffler -> outlet), where
    # it goes and how much of it
    m_out = m + loads.discharge_backflow_mass_flow
    for node, flow, down, down_flow in (
        (SM, into_cylinder, -1, 0.0), (SG, shell_to_muffler, SM, shell_to_muffler),
        (DC, m_out, DM, m), (DM, m, -1, 0.0),
    ):  # fmt: skip
        f[node] -= flow * h[node]
        jac[node, node] -= flow * cp[node]
        if down >= 0:
            f[down] += down_flow * h[node]
            jac[down, node] += down_flow * cp[node]
    return f, jac


def solve_network(
    par: NetworkParameters,
    loads: NetworkLoads | Callable[[float], NetworkLoads],
    pressures: NetworkPressures,
    state: EnthalpyFunction,
    guess: np.ndarray | None = None,
) -> NetworkSolution:
    """Node temperatures of the steady network (Newton on the real-gas balances).

    Parameters
    ----------
    par : NetworkParameters
    loads : NetworkLoads or callable
        The loads, or ``loads(T_suction_muffler [K]) -> NetworkLoads`` when they depend
        on the suction muffler's temperature (a cylinder drawing from it): Newton then
        includes that dependence (by a 1e-3 K difference).
    pressures : NetworkPressures
    state : callable
        ``state(p, T) -> (h, c_p, ...)`` of the refrigerant vapour [J/kg, J/(kg K)].
    guess : ndarray, optional
        Starting temperatures [K] (default: every node at the inlet temperature).

    Returns
    -------
    NetworkSolution

    Raises
    ------
    ValueError
        If Newton does not converge to 1e-6 K in 30 iterations, or the leakage drains
        the shell gas (a high-side shell, not modelled).
    """
    h_in = state(pressures.inlet_pressure, pressures.inlet_temperature)[0]
    t = np.full(N_NODES, pressures.inlet_temperature) if guess is None else guess.copy()
    h = np.full(N_NODES, math.nan)
    cp = np.zeros(N_NODES)
    iterations = 0
    while iterations < _NEWTON_MAX:
        iterations += 1
        for node, p in zip(GAS_NODES, pressures.node, strict=True):
            h[node], cp[node] = state(p, float(t[node]))[:2]
        now = loads(float(t[SM])) if callable(loads) else loads
        f, jac = _assemble(par, now, h_in, t, h, cp)
        if callable(loads):
            moved = loads(float(t[SM]) + _LOAD_STEP)
            jac[:, SM] += (_assemble(par, moved, h_in, t, h, cp)[0] - f) / _LOAD_STEP
        step = np.linalg.solve(jac, -f)
        t += step
        if float(np.max(np.abs(step))) < _NEWTON_TOL:
            break
    else:
        raise ValueError(f"the thermal network did not converge (last step {step} K)")
    # h was evaluated before the last step (< 1e-6 K): c_p 1e-6 K is below 0.01 J/kg
    return NetworkSolution(
        temperature=t,
        enthalpy=h,
        inlet_enthalpy=h_in,
        outlet_enthalpy=float(h[DM]),
        shell_heat_rejection=max(par.shell_ambient, UA_FLOOR) * (t[SH] - par.ambient_temperature),
        iterations=iterations,
        loads=now,
    )
