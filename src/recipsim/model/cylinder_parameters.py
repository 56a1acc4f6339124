"""The cylinder scene's parameter arrays: the float parameters (geometry, plenum states,
gas, valves) and the integer option codes of
:data:`recipsim.physics.thermo.cylinder.PAR` and ``IPAR``, and its property callback
(:func:`recipsim.model.build.cylinder_model` lays the scene out with them).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from recipsim.case.load import Case
from recipsim.model import scenes
from recipsim.model.plenum import PlenumState, write_plenum
from recipsim.physics.thermo import cylinder as cyl
from recipsim.physics.thermo.heat_transfer import HEAT_TRANSFER
from recipsim.physics.thermo.leakage_models import LEAKAGE, leakage_code
from recipsim.physics.thermo.properties import HeosProperties
from recipsim.physics.thermo.table_states import TableFluid
from recipsim.physics.thermo.valve_models import VALVE_MODELS

if TYPE_CHECKING:
    from recipsim.case.refrigerant import AnyFluid

START_ANGLE = 1.5 * math.pi  # crank angle at which every revolution starts [rad]

_FLOW_CODES = {"real_gas": cyl.FLOW_REAL_GAS, "ideal_gas": cyl.FLOW_IDEAL_GAS}


def cylinder_parameters(
    case: Case,
    fluid: AnyFluid,
    suction: PlenumState,
    discharge: PlenumState,
    shell: PlenumState,
) -> tuple[np.ndarray, np.ndarray]:
    """Float and integer parameters of the cylinder scene for ``case``.

    Parameters
    ----------
    case : Case
        The case.
    fluid : AnyFluid
        The refrigerant's property backend.
    suction, discharge, shell : PlenumState
        The plenum states.

    Returns
    -------
    par : numpy.ndarray
        Float parameters, shape ``(scenes.P_TABLES,)``.
    ipar : numpy.ndarray
        Integer parameters, shape ``(scenes.N_IPAR,)``; the property backend's code
        (``cyl.I_PROPS``) is left to the caller, which builds the callback.
    """
    opts = case.options
    par = np.zeros(scenes.P_TABLES)
    _write_geometry(par, case)
    _write_gas(par, case, fluid, suction, discharge, shell)
    _write_valves(par, case)
    ipar = np.zeros(scenes.N_IPAR, dtype=np.int64)
    ipar[cyl.I_SCENE] = 0
    ipar[cyl.I_VALVES] = VALVE_MODELS[opts.valves].code
    ipar[cyl.I_FLOW] = _FLOW_CODES[case.valves.flow_model]
    ipar[cyl.I_HT] = HEAT_TRANSFER[opts.heat_transfer].code
    ipar[cyl.I_LEAK] = leakage_code(opts.leakage, case.leakage.model)
    return par, ipar


def _write_geometry(par: np.ndarray, case: Case) -> None:
    """Write the speed, start angle, crank and cylinder geometry and the masses of the
    crank train into the cylinder's float parameters.

    Parameters
    ----------
    par : numpy.ndarray
        The float parameters (``scenes.P_TABLES``), written in place.
    case : Case
        The case.
    """
    geo = case.geometry
    omega = case.operating_point.shaft_speed
    par[cyl.C_OMEGA] = omega
    # revolutions start a quarter turn before top dead centre, where both valves are shut
    par[cyl.C_THETA0] = START_ANGLE
    par[cyl.C_R] = geo.crank_radius
    par[cyl.C_L] = geo.connecting_rod_length
    par[cyl.C_AP] = geo.piston_area
    par[cyl.C_VC] = geo.clearance_volume
    par[cyl.C_BORE] = geo.bore
    par[cyl.C_STROKE] = geo.stroke
    par[cyl.C_PISTON_LEN] = case.mechanism.piston.length
    par[cyl.C_LINER_LEN] = geo.liner_length
    mech = case.mechanism
    par[cyl.C_MPISTON] = mech.piston.mass
    par[cyl.C_MROD] = mech.connecting_rod.mass
    par[cyl.C_AROD] = mech.connecting_rod.centre_of_mass_fraction
    par[cyl.C_IROD] = mech.connecting_rod.inertia
    par[cyl.C_BAUMGARTE] = 200.0 * omega  # pressure drift of the ideal valves decays in ~1 deg


def _write_gas(
    par: np.ndarray,
    case: Case,
    fluid: AnyFluid,
    suction: PlenumState,
    discharge: PlenumState,
    shell: PlenumState,
) -> None:
    """Write the plenum states, the gas constant, the valve-flow, leakage and heat-transfer
    parameters into the cylinder's float parameters.

    Parameters
    ----------
    par : numpy.ndarray
        The float parameters (``scenes.P_TABLES``), written in place.
    case : Case
        The case.
    fluid : AnyFluid
        The refrigerant's property backend.
    suction, discharge, shell : PlenumState
        The plenum states.
    """
    write_plenum(par, suction, cyl.C_PS, cyl.C_RHOS, cyl.C_HS, cyl.C_KAPPAS, cyl.C_K0S, cyl.C_TS)
    write_plenum(par, discharge, cyl.C_PD, cyl.C_RHOD, cyl.C_HD, cyl.C_KAPPAD, cyl.C_K0D, cyl.C_TD)
    par[cyl.C_PSHELL] = shell.pressure
    par[cyl.C_RHOSHELL] = shell.density
    par[cyl.C_HSHELL] = shell.enthalpy
    par[cyl.C_MUSHELL] = shell.viscosity
    par[cyl.C_RGAS] = fluid.gas_constant
    par[cyl.C_DPLAM] = case.valves.laminar_pressure_difference
    par[cyl.C_VSTICK] = case.valves.stick_velocity
    par[cyl.C_LEAK_DELTA] = case.leakage.radial_clearance
    par[cyl.C_LEAK_ECC] = case.leakage.eccentricity_ratio
    correlation = HEAT_TRANSFER[case.options.heat_transfer]
    coef = case.heat_transfer.coefficient
    par[cyl.C_HT_COEF] = correlation.default_coefficient if math.isnan(coef) else coef
    par[cyl.C_TWALL] = case.heat_transfer.wall_temperature


def _write_valves(par: np.ndarray, case: Case) -> None:
    """Write the suction and the discharge valve's rows into the cylinder's float
    parameters.

    Parameters
    ----------
    par : numpy.ndarray
        The float parameters (``scenes.P_TABLES``), written in place.
    case : Case
        The case.
    """
    for i, valve in enumerate((case.valves.suction, case.valves.discharge)):
        base = cyl.C_VALVE0 + i * cyl.VALVE_BLOCK
        par[base + cyl.V_PORT_D] = valve.port_diameter
        par[base + cyl.V_CFLOW] = valve.flow_coefficient
        par[base + cyl.V_AFORCE] = valve.force_coefficient * valve.port_area
        par[base + cyl.V_MASS] = valve.mass
        par[base + cyl.V_STIFF] = valve.stiffness
        par[base + cyl.V_DAMP] = 2.0 * valve.damping_ratio * math.sqrt(valve.stiffness * valve.mass)
        par[base + cyl.V_STOP] = valve.stop_height
        par[base + cyl.V_REST] = valve.restitution
        par[base + cyl.V_PRELOAD] = valve.preload
        par[base + cyl.V_CURTAIN_D] = valve.curtain_diameter
        par[base + cyl.V_MOMENTUM] = 1.0 if valve.momentum_force else 0.0


def property_callback(case: Case, fluid: AnyFluid) -> HeosProperties:
    """The property callback of the compiled code.

    With a tabulated property backend the compiled code interpolates a cached table that
    follows the outputs in the callback's buffer, and calls HEOS only where the table
    has no data; transport properties are computed when heat transfer or leakage needs
    them.

    Parameters
    ----------
    case : Case
        The case.
    fluid : AnyFluid
        The refrigerant's property backend (a :class:`TableFluid` brings its table).

    Returns
    -------
    HeosProperties
        The callback, its ``table`` set (None without one).
    """
    opts = case.options
    transport = HEAT_TRANSFER[opts.heat_transfer].exchanges_heat or LEAKAGE[opts.leakage].leaks
    ref = case.refrigerant
    table = fluid.table if isinstance(fluid, TableFluid) else None
    props = HeosProperties(
        ref.coolprop_name,
        transport=transport,
        t_min=ref.min_temperature,
        t_max=ref.max_temperature,
        buffer=None if table is None else table.property_buffer(transport),
    )
    props.table = table
    return props
