"""The compiled right-hand side of the cylinder gas, its valves and the piston gap
(layout: :mod:`recipsim.physics.thermo.cylinder`).

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
- the valve models' flow areas and reed forces come from the registry's dispatch
  (:mod:`recipsim.physics.thermo.valve_models`), where another valve model adds its
  branch.

Piston-gap leakage (``I_LEAK``): ``LEAK_INCOMPRESSIBLE`` (upstream density and
viscosity) or ``LEAK_ISOTHERMAL`` (compressible, ``p/rho`` and viscosity the means of
the cylinder gas and the shell gas).
"""

from __future__ import annotations

import math

from numba import njit

from recipsim.physics.kinematics import inertia_torque, piston_displacement
from recipsim.physics.thermo import cylinder as cyl
from recipsim.physics.thermo.flow import (
    gap_leakage_mass_flow,
    isothermal_gap_leakage_mass_flow,
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
from recipsim.physics.thermo.valve_models import (
    moves_reeds,
    reed_opening_force,
    valve_flow_area,
)


@njit(cache=True)
def cylinder_rhs(t, y, mode, par, ipar, props, pbuf, dydt, aux) -> int:
    """Time derivatives of the cylinder on the rigid crank at constant speed.

    Fills ``aux`` with the outputs; returns the property status (0 when the state is
    inside the equation of state).
    """
    omega = par[cyl.C_OMEGA]
    theta = par[cyl.C_THETA0] + omega * t
    x, dxdth, _ = piston_displacement(theta, par[cyl.C_R], par[cyl.C_L])
    status = cylinder_gas_rhs(
        theta,
        omega,
        x,
        dxdth * omega,
        par[cyl.C_LEAK_ECC],
        y,
        mode,
        par,
        ipar,
        props,
        pbuf,
        dydt,
        aux,
    )
    if status != STATUS_OK:
        return status
    torque_gas = aux[cyl.A_FORCE_GAS] * dxdth
    torque_inertia = inertia_torque(
        theta,
        omega,
        par[cyl.C_R],
        par[cyl.C_L],
        par[cyl.C_MPISTON],
        par[cyl.C_MROD],
        par[cyl.C_AROD],
        par[cyl.C_IROD],
    )
    torque_shaft = torque_inertia - torque_gas
    dydt[cyl.Q_SHAFT] = torque_shaft * omega
    aux[cyl.A_TORQUE_GAS] = torque_gas
    aux[cyl.A_TORQUE_INERTIA] = torque_inertia
    aux[cyl.A_TORQUE_SHAFT] = torque_shaft
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
    ap = par[cyl.C_AP]
    volume = par[cyl.C_VC] + ap * x
    dvdt = ap * xdot
    temp = y[cyl.Y_T]
    rho = y[cyl.Y_RHO]
    if ipar[cyl.I_PROPS] == cyl.PROPS_TABLE:
        status = table_props(temp, rho, pbuf)
        if status == STATUS_FALLBACK:
            status = props(temp, rho)
    else:
        status = props(temp, rho)
    if status != STATUS_OK:
        aux[cyl.A_STATUS] = status
        return status
    p = pbuf[PROP_PRESSURE]
    h = pbuf[PROP_ENTHALPY]
    cv = pbuf[PROP_CV]
    dpdt_rho = pbuf[PROP_DPDT]
    kappa = pbuf[PROP_KAPPA]
    if ipar[cyl.I_FLOW] == cyl.FLOW_IDEAL_GAS:
        kappa = pbuf[PROP_K0]
        kappa_s = par[cyl.C_K0S]
        kappa_d = par[cyl.C_K0D]
        rho_up_cyl = p / (par[cyl.C_RGAS] * temp)
        rho_s = par[cyl.C_PS] / (par[cyl.C_RGAS] * par[cyl.C_TS])
        rho_d = par[cyl.C_PD] / (par[cyl.C_RGAS] * par[cyl.C_TD])
    else:
        kappa_s = par[cyl.C_KAPPAS]
        kappa_d = par[cyl.C_KAPPAD]
        rho_up_cyl = rho
        rho_s = par[cyl.C_RHOS]
        rho_d = par[cyl.C_RHOD]
    mass = rho * volume
    p_s = par[cyl.C_PS]
    p_d = par[cyl.C_PD]
    h_s = par[cyl.C_HS]
    h_d = par[cyl.C_HD]
    dp_lam = par[cyl.C_DPLAM]
    valves = ipar[cyl.I_VALVES]
    bs = cyl.C_VALVE0
    bd = cyl.C_VALVE0 + cyl.VALVE_BLOCK

    # heat transfer
    qdot = 0.0
    htc = 0.0
    if ipar[cyl.I_HT] != HT_ADIABATIC:
        clear_height = par[cyl.C_VC] / ap
        wall_area = 2.0 * ap + math.pi * par[cyl.C_BORE] * (x + clear_height)
        htc = heat_transfer_coefficient(
            ipar[cyl.I_HT],
            par[cyl.C_HT_COEF],
            theta,
            omega,
            volume,
            wall_area,
            par[cyl.C_BORE],
            par[cyl.C_STROKE],
            rho,
            pbuf[PROP_VISCOSITY],
            pbuf[PROP_CONDUCTIVITY],
            pbuf[PROP_CP],
        )
        qdot = htc * wall_area * (par[cyl.C_TWALL] - temp)

    # piston-gap leakage, positive out of the cylinder
    mdot_leak = 0.0
    if ipar[cyl.I_LEAK] == cyl.LEAK_ISOTHERMAL:
        clear_height = par[cyl.C_VC] / ap
        length = max(min(par[cyl.C_PISTON_LEN], par[cyl.C_LINER_LEN] - clear_height - x), 1e-4)
        mdot_leak = isothermal_gap_leakage_mass_flow(
            p,
            par[cyl.C_PSHELL],
            0.5 * (p / rho + par[cyl.C_PSHELL] / par[cyl.C_RHOSHELL]),
            0.5 * (pbuf[PROP_VISCOSITY] + par[cyl.C_MUSHELL]),
            par[cyl.C_BORE],
            par[cyl.C_LEAK_DELTA],
            length,
            -xdot,
            leak_ecc,
        )
    elif ipar[cyl.I_LEAK] == cyl.LEAK_INCOMPRESSIBLE:
        clear_height = par[cyl.C_VC] / ap
        length = min(par[cyl.C_PISTON_LEN], par[cyl.C_LINER_LEN] - clear_height - x)
        length = max(length, 1e-4)
        dp_gap = p - par[cyl.C_PSHELL]
        if dp_gap >= 0.0:
            rho_gap = rho
            mu_gap = pbuf[PROP_VISCOSITY]
        else:
            rho_gap = par[cyl.C_RHOSHELL]
            mu_gap = par[cyl.C_MUSHELL]
        mdot_leak = gap_leakage_mass_flow(
            dp_gap,
            rho_gap,
            mu_gap,
            par[cyl.C_BORE],
            par[cyl.C_LEAK_DELTA],
            length,
            -xdot,
            leak_ecc,
        )
    h_leak = h if mdot_leak >= 0.0 else par[cyl.C_HSHELL]

    # valves with states or closed forms
    mdot_s = 0.0
    mdot_d = 0.0
    lift_s = y[cyl.Y_XS]
    lift_d = y[cyl.Y_XD]
    a_s = valve_flow_area(valves, lift_s, par, bs)
    a_d = valve_flow_area(valves, lift_d, par, bd)
    reeds = moves_reeds(valves)
    # jet momentum on the reeds, along their opening direction [N]
    fjet_s = 0.0
    fjet_d = 0.0
    jet_s = par[bs + cyl.V_MOMENTUM] > 0.5
    jet_d = par[bd + cyl.V_MOMENTUM] > 0.5
    if a_s > 0.0:
        if p_s > p:
            mdot_s, fjet_s = valve_mass_flow_and_force(a_s, p_s, rho_s, p, kappa_s, dp_lam, jet_s)
        elif reeds:
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
        elif reeds:
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
    if valves == cyl.VALVES_IDEAL and (mode[0] == 1 or mode[1] == 1):
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
        beta = par[cyl.C_BAUMGARTE]
        mdot_v = (-beta * (p - p_target) - dpdt_rho * a_temp - dpdrho * a_rho) / denom
        if mode[0] == 1:
            mdot_s = mdot_v
        else:
            mdot_d = -mdot_v
        a_rho += b_rho * mdot_v
        a_temp += b_temp * mdot_v

    dydt[cyl.Y_T] = a_temp
    dydt[cyl.Y_RHO] = a_rho

    # reed dynamics
    f_s = reed_opening_force(
        valves, p_s - p, mdot_s, rho_s if mdot_s >= 0.0 else rho_up_cyl, fjet_s, par, bs
    )
    f_d = reed_opening_force(
        valves, p - p_d, mdot_d, rho_up_cyl if mdot_d >= 0.0 else rho_d, fjet_d, par, bd
    )
    for i in range(2):
        base = cyl.C_VALVE0 + i * cyl.VALVE_BLOCK
        ix = cyl.Y_XS + 2 * i
        if reeds and mode[i] == 1:
            force = f_s if i == 0 else f_d
            acc = (
                force - par[base + cyl.V_STIFF] * y[ix] - par[base + cyl.V_DAMP] * y[ix + 1]
            ) / par[base + cyl.V_MASS]
            dydt[ix] = y[ix + 1]
            dydt[ix + 1] = acc
        else:
            dydt[ix] = 0.0
            dydt[ix + 1] = 0.0

    # quadratures
    dydt[cyl.Q_MSUC_IN] = max(mdot_s, 0.0)
    dydt[cyl.Q_MSUC_OUT] = max(-mdot_s, 0.0)
    dydt[cyl.Q_MDIS_OUT] = max(mdot_d, 0.0)
    dydt[cyl.Q_MDIS_IN] = max(-mdot_d, 0.0)
    dydt[cyl.Q_MLEAK_OUT] = max(mdot_leak, 0.0)
    dydt[cyl.Q_MLEAK_IN] = max(-mdot_leak, 0.0)
    dydt[cyl.Q_HSUC_IN] = max(mdot_s, 0.0) * h_s
    dydt[cyl.Q_HSUC_OUT] = max(-mdot_s, 0.0) * h
    dydt[cyl.Q_HDIS_OUT] = max(mdot_d, 0.0) * h
    dydt[cyl.Q_HDIS_IN] = max(-mdot_d, 0.0) * h_d
    dydt[cyl.Q_HLEAK_OUT] = max(mdot_leak, 0.0) * h
    dydt[cyl.Q_HLEAK_IN] = max(-mdot_leak, 0.0) * par[cyl.C_HSHELL]
    dydt[cyl.Q_HEAT] = qdot
    dydt[cyl.Q_WORK] = -p * dvdt
    dydt[cyl.Q_SHAFT] = 0.0

    aux[cyl.A_THETA] = theta
    aux[cyl.A_VOLUME] = volume
    aux[cyl.A_DVDT] = dvdt
    aux[cyl.A_PRESSURE] = p
    aux[cyl.A_TEMPERATURE] = temp
    aux[cyl.A_DENSITY] = rho
    aux[cyl.A_MASS] = mass
    aux[cyl.A_ENTHALPY] = h
    aux[cyl.A_QUALITY] = pbuf[PROP_QUALITY]
    aux[cyl.A_MDOT_SUC] = mdot_s
    aux[cyl.A_MDOT_DIS] = mdot_d
    aux[cyl.A_MDOT_LEAK] = mdot_leak
    aux[cyl.A_LEAK_ECC] = leak_ecc
    aux[cyl.A_QDOT] = qdot
    aux[cyl.A_HTC] = htc
    aux[cyl.A_LIFT_S] = lift_s
    aux[cyl.A_LIFT_D] = lift_d
    aux[cyl.A_VEL_S] = y[cyl.Y_VS]
    aux[cyl.A_VEL_D] = y[cyl.Y_VD]
    aux[cyl.A_FORCE_GAS] = (p - par[cyl.C_PSHELL]) * ap
    aux[cyl.A_TORQUE_GAS] = 0.0
    aux[cyl.A_TORQUE_INERTIA] = 0.0
    aux[cyl.A_TORQUE_SHAFT] = 0.0
    aux[cyl.A_DISPLACEMENT] = x
    aux[cyl.A_PISTON_VELOCITY] = xdot
    aux[cyl.A_FORCE_REED_S] = f_s
    aux[cyl.A_FORCE_REED_D] = f_d
    aux[cyl.A_STATUS] = 0.0
    return STATUS_OK
