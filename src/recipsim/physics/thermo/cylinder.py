"""The cylinder on a rigid crank at constant speed: compiled right-hand side and events.

States (time is the independent variable, ``theta = theta0 + omega t``):
gas temperature T [K] and density rho [kg/m3] (CoolProp's equations of state are
explicit in them), suction and discharge reed lift [m] and velocity [m/s], then
quadratures (cumulative mass, enthalpy, heat and work over the revolution) that the
summary and the closure checks read. Only the first ``N_ERR`` states are under
error control.

Energy (Bell et al., PDSim, Eq. 4)::

    m c_v dT/dt = -T (dp/dT)_rho (dV/dt - dm/dt / rho) - h dm/dt + Qdot + sum(mdot_i h_i)

with ``h_i`` the upstream enthalpy. Valve models:

- ``ideal`` (lossless): while a valve is open the mass flow is whatever keeps the
  cylinder pressure at the plenum pressure (solved from ``dp/dt = 0`` with a small
  Baumgarte term against drift); it opens when p reaches the plenum pressure and
  closes when that flow would reverse. Both are events.
- ``quasi_static``: nozzle flow through the port, no valve state, no back-flow.
- ``reed``: 1-DOF spring-mass per valve, effective force and flow areas; seat and stop
  are events with a restitution coefficient; slow impacts stick. Per valve, the curtain
  diameter (``V_CURTAIN_D``: the port's or the reed's, :func:`flow.reed_flow_area`) and
  whether the jet's momentum (``V_MOMENTUM``, :func:`flow.jet_momentum_force`) adds to
  the pressure force on the reed.

Piston-gap leakage (``I_LEAK``): ``LEAK_INCOMPRESSIBLE`` (upstream density and
viscosity) or ``LEAK_ISOTHERMAL`` (compressible, ``p/rho`` and viscosity the means of
the cylinder gas and the shell gas).

Modes (``mode[0]`` suction, ``mode[1]`` discharge): ideal 0 closed / 1 open; reed
0 seated / 1 free / 2 at the stop.

Size (over the project's 400 lines): the state, parameter and output layout and
the compiled right-hand side, events and impact actions that index it are one piece
today; moving the layout constants into a module of their own (as
:mod:`recipsim.physics.mechanics.layout` does for the crank train) is listed on issue 13.
"""

from __future__ import annotations

import math

from numba import njit

from recipsim.physics.kinematics import inertia_torque, piston_displacement
from recipsim.physics.thermo.flow import (
    gap_leakage_mass_flow,
    isothermal_gap_leakage_mass_flow,
    reed_flow_area,
    valve_mass_flow_and_force,
)
from recipsim.physics.thermo.heat_transfer import HT_ADIABATIC, heat_transfer_coefficient
from recipsim.physics.thermo.properties import (
    PROP_CONDUCTIVITY,
    PROP_CP,
    PROP_CV,
    PROP_DPDRHO,
    PROP_DPDT,
    PROP_ENTHALPY,
    PROP_K0,
    PROP_KAPPA,
    PROP_PRESSURE,
    PROP_QUALITY,
    PROP_VISCOSITY,
    STATUS_OK,
)
from recipsim.physics.thermo.property_table import STATUS_FALLBACK, table_props

# ---- states -----------------------------------------------------------------------
Y_T = 0
Y_RHO = 1
Y_XS = 2
Y_VS = 3
Y_XD = 4
Y_VD = 5
N_ERR = 6
Q_MSUC_IN = 6  # mass in through the suction valve [kg]
Q_MSUC_OUT = 7  # back-flow out through the suction valve [kg]
Q_MDIS_OUT = 8
Q_MDIS_IN = 9
Q_MLEAK_OUT = 10
Q_MLEAK_IN = 11
Q_HSUC_IN = 12  # enthalpy carried [J]
Q_HSUC_OUT = 13
Q_HDIS_OUT = 14
Q_HDIS_IN = 15
Q_HLEAK_OUT = 16
Q_HLEAK_IN = 17
Q_HEAT = 18  # heat into the gas [J]
Q_WORK = 19  # work on the gas, -int p dV [J]
Q_SHAFT = 20  # shaft work, int tau omega dt [J]
N_STATE = 21
N_MODES = 2
N_EVENTS = 4

# ---- integer parameters --------------------------------------------------------------
I_SCENE = 0
I_VALVES = 1
I_FLOW = 2
I_HT = 3
I_LEAK = 4
I_PROPS = 5  # property backend: PROPS_HEOS (the ``props`` callback) or PROPS_TABLE
N_IPAR = 6
PROPS_HEOS = 0
PROPS_TABLE = 1  # table in pbuf after the outputs (property_table); HEOS where it has no data
VALVES_IDEAL = 0
VALVES_QUASI_STATIC = 1
VALVES_REED = 2
FLOW_REAL_GAS = 0
FLOW_IDEAL_GAS = 1
LEAK_NONE = 0
LEAK_INCOMPRESSIBLE = 1
LEAK_ISOTHERMAL = 2

# ---- float parameters ----------------------------------------------------------------
C_OMEGA = 0
C_THETA0 = 1
C_R = 2
C_L = 3
C_AP = 4
C_VC = 5
C_BORE = 6
C_STROKE = 7
C_PISTON_LEN = 8
C_LINER_LEN = 9
C_PS = 10
C_RHOS = 11
C_HS = 12
C_KAPPAS = 13
C_K0S = 14
C_TS = 15
C_PD = 16
C_RHOD = 17
C_HD = 18
C_KAPPAD = 19
C_K0D = 20
C_TD = 21
C_PSHELL = 22
C_RHOSHELL = 23
C_HSHELL = 24
C_MUSHELL = 25
C_RGAS = 26
C_DPLAM = 27
C_VSTICK = 28
C_LEAK_DELTA = 29
C_LEAK_ECC = 30
C_HT_COEF = 31
C_TWALL = 32
C_MPISTON = 33
C_MROD = 34
C_AROD = 35
C_IROD = 36
C_BAUMGARTE = 37
C_VALVE0 = 40  # first valve block; valve i starts at C_VALVE0 + i * VALVE_BLOCK
VALVE_BLOCK = 11
V_PORT_D = 0
V_CFLOW = 1
V_AFORCE = 2
V_MASS = 3
V_STIFF = 4
V_DAMP = 5
V_STOP = 6
V_REST = 7
V_PRELOAD = 8
V_CURTAIN_D = 9  # diameter of the curtain flow area [m]
V_MOMENTUM = 10  # 1.0: the jet's momentum pushes on the reed
N_PAR = C_VALVE0 + 2 * VALVE_BLOCK

# ---- auxiliary outputs --------------------------------------------------------------
A_THETA = 0
A_VOLUME = 1
A_DVDT = 2
A_PRESSURE = 3
A_TEMPERATURE = 4
A_DENSITY = 5
A_MASS = 6
A_ENTHALPY = 7
A_QUALITY = 8
A_MDOT_SUC = 9  # into the cylinder through the suction valve [kg/s]
A_MDOT_DIS = 10  # out of the cylinder through the discharge valve [kg/s]
A_MDOT_LEAK = 11  # out of the cylinder through the piston gap [kg/s]
A_QDOT = 12  # heat into the gas [W]
A_HTC = 13
A_LIFT_S = 14
A_LIFT_D = 15
A_VEL_S = 16
A_VEL_D = 17
A_FORCE_GAS = 18  # (p - p_shell) A_p on the piston, towards the crank [N]
A_TORQUE_GAS = 19  # (p - p_shell) A_p dx/dtheta [N m]
A_TORQUE_INERTIA = 20
A_TORQUE_SHAFT = 21  # driving torque for constant speed [N m]
A_DISPLACEMENT = 22  # piston displacement from TDC [m]
A_PISTON_VELOCITY = 23  # dx/dt [m/s]
A_FORCE_REED_S = 24  # net opening force on the suction reed (spring excluded) [N]
A_FORCE_REED_D = 25
A_STATUS = 26
A_LEAK_ECC = 27  # eccentricity ratio of the piston in the bore seen by the leak [-]
N_AUX = 28


@njit(cache=True)
def _valve_force(dp_open: float, par, base: int) -> float:
    """Net opening force of a reed at zero lift: A_ff dp - preload [N]."""
    return par[base + V_AFORCE] * dp_open - par[base + V_PRELOAD]


@njit(cache=True)
def cylinder_rhs(t, y, mode, par, ipar, props, pbuf, dydt, aux) -> int:
    """Time derivatives of the cylinder on the rigid crank at constant speed.

    Fills ``aux`` with the outputs; returns the property status (0 when the state is
    inside the equation of state).
    """
    omega = par[C_OMEGA]
    theta = par[C_THETA0] + omega * t
    x, dxdth, _ = piston_displacement(theta, par[C_R], par[C_L])
    status = cylinder_gas_rhs(
        theta, omega, x, dxdth * omega, par[C_LEAK_ECC], y, mode, par, ipar, props, pbuf, dydt, aux
    )
    if status != STATUS_OK:
        return status
    torque_gas = aux[A_FORCE_GAS] * dxdth
    torque_inertia = inertia_torque(
        theta, omega, par[C_R], par[C_L], par[C_MPISTON], par[C_MROD], par[C_AROD], par[C_IROD]
    )
    torque_shaft = torque_inertia - torque_gas
    dydt[Q_SHAFT] = torque_shaft * omega
    aux[A_TORQUE_GAS] = torque_gas
    aux[A_TORQUE_INERTIA] = torque_inertia
    aux[A_TORQUE_SHAFT] = torque_shaft
    return STATUS_OK


@njit(cache=True)
def cylinder_gas_rhs(
    theta, omega, x, xdot, leak_ecc, y, mode, par, ipar, props, pbuf, dydt, aux
) -> int:
    """Gas, valve and leakage derivatives for a given piston motion.

    The piston motion comes from the caller (rigid slider-crank or the flexible
    mechanism's piston), so the cylinder never needs to know which crank drives it.

    Parameters
    ----------
    theta, omega : float
        Crank angle [rad] and speed [rad/s] (heat-transfer correlations).
    x, xdot : float
        Crown displacement from top dead centre [m] and its rate [m/s].
    leak_ecc : float
        Eccentricity ratio of the piston in the bore for the gap leakage [-].
    y, dydt, aux : ndarray
        Cylinder states, their derivatives and outputs (this module's layouts); the
        shaft quadrature and the torque outputs are left to the caller.

    Returns
    -------
    int
        Property status.
    """
    ap = par[C_AP]
    volume = par[C_VC] + ap * x
    dvdt = ap * xdot
    temp = y[Y_T]
    rho = y[Y_RHO]
    if ipar[I_PROPS] == PROPS_TABLE:
        status = table_props(temp, rho, pbuf)
        if status == STATUS_FALLBACK:
            status = props(temp, rho)
    else:
        status = props(temp, rho)
    if status != STATUS_OK:
        aux[A_STATUS] = status
        return status
    p = pbuf[PROP_PRESSURE]
    h = pbuf[PROP_ENTHALPY]
    cv = pbuf[PROP_CV]
    dpdt_rho = pbuf[PROP_DPDT]
    kappa = pbuf[PROP_KAPPA]
    if ipar[I_FLOW] == FLOW_IDEAL_GAS:
        kappa = pbuf[PROP_K0]
        kappa_s = par[C_K0S]
        kappa_d = par[C_K0D]
        rho_up_cyl = p / (par[C_RGAS] * temp)
        rho_s = par[C_PS] / (par[C_RGAS] * par[C_TS])
        rho_d = par[C_PD] / (par[C_RGAS] * par[C_TD])
    else:
        kappa_s = par[C_KAPPAS]
        kappa_d = par[C_KAPPAD]
        rho_up_cyl = rho
        rho_s = par[C_RHOS]
        rho_d = par[C_RHOD]
    mass = rho * volume
    p_s = par[C_PS]
    p_d = par[C_PD]
    h_s = par[C_HS]
    h_d = par[C_HD]
    dp_lam = par[C_DPLAM]
    valves = ipar[I_VALVES]
    bs = C_VALVE0
    bd = C_VALVE0 + VALVE_BLOCK

    # heat transfer
    qdot = 0.0
    htc = 0.0
    if ipar[I_HT] != HT_ADIABATIC:
        clear_height = par[C_VC] / ap
        wall_area = 2.0 * ap + math.pi * par[C_BORE] * (x + clear_height)
        htc = heat_transfer_coefficient(
            ipar[I_HT],
            par[C_HT_COEF],
            theta,
            omega,
            volume,
            wall_area,
            par[C_BORE],
            par[C_STROKE],
            rho,
            pbuf[PROP_VISCOSITY],
            pbuf[PROP_CONDUCTIVITY],
            pbuf[PROP_CP],
        )
        qdot = htc * wall_area * (par[C_TWALL] - temp)

    # piston-gap leakage, positive out of the cylinder
    mdot_leak = 0.0
    if ipar[I_LEAK] == LEAK_ISOTHERMAL:
        clear_height = par[C_VC] / ap
        length = max(min(par[C_PISTON_LEN], par[C_LINER_LEN] - clear_height - x), 1e-4)
        mdot_leak = isothermal_gap_leakage_mass_flow(
            p,
            par[C_PSHELL],
            0.5 * (p / rho + par[C_PSHELL] / par[C_RHOSHELL]),
            0.5 * (pbuf[PROP_VISCOSITY] + par[C_MUSHELL]),
            par[C_BORE],
            par[C_LEAK_DELTA],
            length,
            -xdot,
            leak_ecc,
        )
    elif ipar[I_LEAK] == LEAK_INCOMPRESSIBLE:
        clear_height = par[C_VC] / ap
        length = min(par[C_PISTON_LEN], par[C_LINER_LEN] - clear_height - x)
        length = max(length, 1e-4)
        dp_gap = p - par[C_PSHELL]
        if dp_gap >= 0.0:
            rho_gap = rho
            mu_gap = pbuf[PROP_VISCOSITY]
        else:
            rho_gap = par[C_RHOSHELL]
            mu_gap = par[C_MUSHELL]
        mdot_leak = gap_leakage_mass_flow(
            dp_gap,
            rho_gap,
            mu_gap,
            par[C_BORE],
            par[C_LEAK_DELTA],
            length,
            -xdot,
            leak_ecc,
        )
    h_leak = h if mdot_leak >= 0.0 else par[C_HSHELL]

    # valves with states or closed forms
    mdot_s = 0.0
    mdot_d = 0.0
    lift_s = y[Y_XS]
    lift_d = y[Y_XD]
    if valves == VALVES_REED:
        a_s = reed_flow_area(lift_s, par[bs + V_PORT_D], par[bs + V_CURTAIN_D], par[bs + V_CFLOW])
        a_d = reed_flow_area(lift_d, par[bd + V_PORT_D], par[bd + V_CURTAIN_D], par[bd + V_CFLOW])
    elif valves == VALVES_QUASI_STATIC:
        a_s = par[bs + V_CFLOW] * 0.25 * math.pi * par[bs + V_PORT_D] ** 2
        a_d = par[bd + V_CFLOW] * 0.25 * math.pi * par[bd + V_PORT_D] ** 2
    else:
        a_s = 0.0
        a_d = 0.0
    # jet momentum on the reeds, along their opening direction [N]
    fjet_s = 0.0
    fjet_d = 0.0
    jet_s = par[bs + V_MOMENTUM] > 0.5
    jet_d = par[bd + V_MOMENTUM] > 0.5
    if a_s > 0.0:
        if p_s > p:
            mdot_s, fjet_s = valve_mass_flow_and_force(a_s, p_s, rho_s, p, kappa_s, dp_lam, jet_s)
        elif valves == VALVES_REED:
            mdot_s, fjet_s = valve_mass_flow_and_force(
                a_s, p, rho_up_cyl, p_s, kappa, dp_lam, jet_s
            )
            mdot_s = -mdot_s
            fjet_s = -fjet_s
    if a_d > 0.0:
        if p > p_d:
            mdot_d, fjet_d = valve_mass_flow_and_force(
                a_d, p, rho_up_cyl, p_d, kappa, dp_lam, jet_d
            )
        elif valves == VALVES_REED:
            mdot_d, fjet_d = valve_mass_flow_and_force(a_d, p_d, rho_d, p, kappa_d, dp_lam, jet_d)
            mdot_d = -mdot_d
            fjet_d = -fjet_d

    mdot_known = mdot_s - mdot_d - mdot_leak
    h_in_known = (
        (mdot_s * h_s if mdot_s >= 0.0 else mdot_s * h)
        - (mdot_d * h if mdot_d >= 0.0 else mdot_d * h_d)
        - mdot_leak * h_leak
    )
    mcv = mass * cv
    a_rho = (mdot_known - rho * dvdt) / volume
    a_temp = (
        -temp * dpdt_rho * (dvdt - mdot_known / rho) - h * mdot_known + qdot + h_in_known
    ) / mcv

    # ideal valves: the open valve's flow keeps p at the plenum pressure
    if valves == VALVES_IDEAL and (mode[0] == 1 or mode[1] == 1):
        if mode[0] == 1:
            p_target = p_s
            h_v = h_s
        else:
            p_target = p_d
            h_v = h
        b_rho = 1.0 / volume
        b_temp = (temp * dpdt_rho / rho - h + h_v) / mcv
        dpdrho = pbuf[PROP_DPDRHO]
        denom = dpdt_rho * b_temp + dpdrho * b_rho
        beta = par[C_BAUMGARTE]
        mdot_v = (-beta * (p - p_target) - dpdt_rho * a_temp - dpdrho * a_rho) / denom
        if mode[0] == 1:
            mdot_s = mdot_v
        else:
            mdot_d = -mdot_v
        a_rho += b_rho * mdot_v
        a_temp += b_temp * mdot_v

    dydt[Y_T] = a_temp
    dydt[Y_RHO] = a_rho

    # reed dynamics
    f_s = _valve_force(p_s - p, par, bs) + fjet_s
    f_d = _valve_force(p - p_d, par, bd) + fjet_d
    for i in range(2):
        base = C_VALVE0 + i * VALVE_BLOCK
        ix = Y_XS + 2 * i
        if valves == VALVES_REED and mode[i] == 1:
            force = f_s if i == 0 else f_d
            acc = (force - par[base + V_STIFF] * y[ix] - par[base + V_DAMP] * y[ix + 1]) / par[
                base + V_MASS
            ]
            dydt[ix] = y[ix + 1]
            dydt[ix + 1] = acc
        else:
            dydt[ix] = 0.0
            dydt[ix + 1] = 0.0

    # quadratures
    dydt[Q_MSUC_IN] = max(mdot_s, 0.0)
    dydt[Q_MSUC_OUT] = max(-mdot_s, 0.0)
    dydt[Q_MDIS_OUT] = max(mdot_d, 0.0)
    dydt[Q_MDIS_IN] = max(-mdot_d, 0.0)
    dydt[Q_MLEAK_OUT] = max(mdot_leak, 0.0)
    dydt[Q_MLEAK_IN] = max(-mdot_leak, 0.0)
    dydt[Q_HSUC_IN] = max(mdot_s, 0.0) * h_s
    dydt[Q_HSUC_OUT] = max(-mdot_s, 0.0) * h
    dydt[Q_HDIS_OUT] = max(mdot_d, 0.0) * h
    dydt[Q_HDIS_IN] = max(-mdot_d, 0.0) * h_d
    dydt[Q_HLEAK_OUT] = max(mdot_leak, 0.0) * h
    dydt[Q_HLEAK_IN] = max(-mdot_leak, 0.0) * par[C_HSHELL]
    dydt[Q_HEAT] = qdot
    dydt[Q_WORK] = -p * dvdt
    dydt[Q_SHAFT] = 0.0

    aux[A_THETA] = theta
    aux[A_VOLUME] = volume
    aux[A_DVDT] = dvdt
    aux[A_PRESSURE] = p
    aux[A_TEMPERATURE] = temp
    aux[A_DENSITY] = rho
    aux[A_MASS] = mass
    aux[A_ENTHALPY] = h
    aux[A_QUALITY] = pbuf[PROP_QUALITY]
    aux[A_MDOT_SUC] = mdot_s
    aux[A_MDOT_DIS] = mdot_d
    aux[A_MDOT_LEAK] = mdot_leak
    aux[A_LEAK_ECC] = leak_ecc
    aux[A_QDOT] = qdot
    aux[A_HTC] = htc
    aux[A_LIFT_S] = lift_s
    aux[A_LIFT_D] = lift_d
    aux[A_VEL_S] = y[Y_VS]
    aux[A_VEL_D] = y[Y_VD]
    aux[A_FORCE_GAS] = (p - par[C_PSHELL]) * ap
    aux[A_TORQUE_GAS] = 0.0
    aux[A_TORQUE_INERTIA] = 0.0
    aux[A_TORQUE_SHAFT] = 0.0
    aux[A_DISPLACEMENT] = x
    aux[A_PISTON_VELOCITY] = xdot
    aux[A_FORCE_REED_S] = f_s
    aux[A_FORCE_REED_D] = f_d
    aux[A_STATUS] = 0.0
    return STATUS_OK


@njit(cache=True)
def cylinder_event_values(y, mode, par, ipar, aux, g) -> None:
    """Event functions of the current modes; an event fires when g goes from <= 0 to > 0."""
    for k in range(N_EVENTS):
        g[k] = -1.0
    valves = ipar[I_VALVES]
    if valves == VALVES_IDEAL:
        p = aux[A_PRESSURE]
        if mode[0] == 1:
            g[0] = -aux[A_MDOT_SUC]
        elif mode[1] == 1:
            g[2] = -aux[A_MDOT_DIS]
        else:
            g[0] = (par[C_PS] - p) / par[C_PS]
            g[2] = (p - par[C_PD]) / par[C_PD]
    elif valves == VALVES_REED:
        for i in range(2):
            base = C_VALVE0 + i * VALVE_BLOCK
            ix = Y_XS + 2 * i
            force = aux[A_FORCE_REED_S] if i == 0 else aux[A_FORCE_REED_D]
            if mode[i] == 0:
                g[2 * i] = force
            elif mode[i] == 1:
                g[2 * i] = -y[ix] / par[base + V_STOP]
                g[2 * i + 1] = (y[ix] - par[base + V_STOP]) / par[base + V_STOP]
            else:
                g[2 * i] = -(force - par[base + V_STIFF] * par[base + V_STOP])


@njit(cache=True)
def cylinder_event_action(k, y, mode, par, ipar, aux) -> None:
    """Apply event ``k`` at the event time: switch modes, impacts with restitution."""
    valves = ipar[I_VALVES]
    i = k // 2
    if valves == VALVES_IDEAL:
        mode[i] = 1 - mode[i]
        return
    base = C_VALVE0 + i * VALVE_BLOCK
    ix = Y_XS + 2 * i
    stop = par[base + V_STOP]
    v_stick = par[C_VSTICK]
    force = aux[A_FORCE_REED_S] if i == 0 else aux[A_FORCE_REED_D]
    if mode[i] == 0:  # seated -> free
        mode[i] = 1
        y[ix] = 0.0
        y[ix + 1] = 0.0
    elif mode[i] == 2:  # leaves the stop
        mode[i] = 1
        y[ix] = stop
        y[ix + 1] = 0.0
    elif k % 2 == 0:  # hits the seat
        v_new = -par[base + V_REST] * y[ix + 1]
        y[ix] = 0.0
        if force > 0.0:  # gas already pushes it open again: leave from the seat
            y[ix + 1] = max(v_new, 0.0)
        elif v_new < v_stick:  # a slow impact against a closing force sticks
            mode[i] = 0
            y[ix + 1] = 0.0
        else:
            y[ix + 1] = v_new
    else:  # hits the stop
        v_new = -par[base + V_REST] * y[ix + 1]
        y[ix] = stop
        net = force - par[base + V_STIFF] * stop
        if net > 0.0 and -v_new < v_stick:  # held against the stop
            mode[i] = 2
            y[ix + 1] = 0.0
        else:
            y[ix + 1] = min(v_new, 0.0)
