"""Pick one submodel per slot and lay out the compiled scene: states, parameters, scales.

:func:`build_model` turns a validated :class:`~recipsim.case.load.Case` into a
:class:`Model`: the float and integer parameter arrays of the compiled right-hand
side, the property callback, the plenum states, the initial state and the state
scales used by the error control.

The cylinder scene's own arrays and property callback are packed by
:mod:`recipsim.model.cylinder_parameters`. The model is built once and its arrays are
read-only: a solve moves a working copy of it (:class:`WorkingModel`, whose setters
move the plena, the wall and the shell between revolutions) and never the model
(:mod:`recipsim.model.scene_model`).
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from recipsim.case.load import Case
from recipsim.case.mechanism import CrankGeometry
from recipsim.case.refrigerant import case_fluid
from recipsim.model import scenes
from recipsim.model.cylinder_parameters import (
    START_ANGLE,
    cylinder_parameters,
    property_callback,
)
from recipsim.model.loss_sources import NetworkLossSources
from recipsim.model.mechanism_parameters import bearing_tables, mechanism_parameters
from recipsim.model.pinned import pinned_torque_profile
from recipsim.model.plenum import PlenumState, isentropic_state, plenum_state
from recipsim.model.scene_model import Model, WorkingModel
from recipsim.model.thermal import ThermalCoupling
from recipsim.physics.kinematics import piston_displacement
from recipsim.physics.mechanics import layout as mlay
from recipsim.physics.mechanics.crank_trains import CRANK_TRAINS
from recipsim.physics.mechanics.drives import DRIVES
from recipsim.physics.mechanics.flexible_setup import initial_state, state_scales
from recipsim.physics.mechanics.tabulated import tabulated_pressure
from recipsim.physics.thermo import cylinder as cyl
from recipsim.physics.thermo.pressure_sources import PRESSURE_SOURCES
from recipsim.physics.thermo.thermal_models import THERMAL_MODELS

if TYPE_CHECKING:
    from recipsim.case.refrigerant import AnyFluid


__all__ = [
    "START_ANGLE",
    "Model",
    "WorkingModel",
    "build_model",
    "case_mechanism_parameters",
    "crank_geometry",
    "cylinder_model",
    "scenes",
]


def cylinder_model(case: Case) -> Model:
    """Lay out the compiled cylinder-on-rigid-crank scene for ``case``.

    Parameters
    ----------
    case : Case
        The case.

    Returns
    -------
    Model
        Plenum states, parameter arrays (:func:`cylinder_parameters`), property
        callback, initial state and scales; with the thermal network, coupled to it
        (:func:`_attach_network`).
    """
    op = case.operating_point
    opts = case.options
    fluid = case_fluid(case.refrigerant, opts.properties)
    suction = plenum_state(fluid, op.suction_pressure, temperature=op.suction_temperature)
    isentropic = isentropic_state(fluid, suction, op.discharge_pressure)
    discharge = plenum_state(fluid, op.discharge_pressure, enthalpy=isentropic["h"])
    shell = plenum_state(fluid, op.shell_pressure, temperature=op.suction_temperature)

    par, ipar = cylinder_parameters(case, fluid, suction, discharge, shell)
    props = property_callback(case, fluid)
    ipar[cyl.I_PROPS] = cyl.PROPS_HEOS if props.table is None else cyl.PROPS_TABLE
    network = THERMAL_MODELS[opts.thermal].shell_network
    # with the network, the initial state follows from the predicted suction plenum (below)
    y0, scale = (
        (np.zeros(cyl.N_STATE), np.ones(cyl.N_STATE))
        if network
        else _initial_gas_state(case, fluid, suction)
    )
    model = Model(
        case=case,
        fluid=fluid,
        par=par,
        ipar=ipar,
        props=props,
        y0=y0,
        mode0=np.zeros(cyl.N_MODES, dtype=np.int64),
        scale=scale,
        period=2.0 * math.pi / op.shaft_speed,
        suction=suction,
        discharge=discharge,
        shell=shell,
    )
    if network:
        return _attach_network(model, case, fluid, suction)
    return model


def _attach_network(model: Model, case: Case, fluid: AnyFluid, suction: PlenumState) -> Model:
    """``model`` coupled to the thermal network: its suction plenum predicted and the
    gas started from it.

    Parameters
    ----------
    model : Model
        The cylinder scene at the operating point's plena.
    case : Case
        The case (its ``options.friction`` feeds the network's loss sources).
    fluid : AnyFluid
        The refrigerant's property backend.
    suction : PlenumState
        The suction plenum of the operating point (the network's inlet).

    Returns
    -------
    Model
        With the inlet, the thermal coupling after its predictor, the plena, wall
        and shell gas it predicts, and the initial state and scales from that suction
        plenum.
    """
    work = model.for_solve()  # the predictor moves the plena like a solve
    thermal = ThermalCoupling(case)
    thermal.loss_sources = NetworkLossSources(case)
    work.thermal = thermal
    thermal.predict(work)
    y0, scale = _initial_gas_state(case, fluid, work.suction)
    return replace(
        model,
        par=work.par,
        inlet=suction,
        thermal=thermal,
        suction=work.suction,
        discharge=work.discharge,
        shell=work.shell,
        y0=y0,
        scale=scale,
    )


#: Largest initial cylinder pressure, a fraction of the discharge pressure.
START_PRESSURE_CAP = 0.95


def _initial_gas_state(
    case: Case, fluid: AnyFluid, suction: PlenumState
) -> tuple[np.ndarray, np.ndarray]:
    """Initial state (suction gas filling the cylinder at BDC, compressed isentropically
    to the start angle) and state scales of the cylinder scene."""
    geo = case.geometry
    y0 = np.zeros(cyl.N_STATE)
    x_start, _, _ = piston_displacement(START_ANGLE, geo.crank_radius, geo.connecting_rod_length)
    v_start = geo.clearance_volume + geo.piston_area * x_start
    rho_start = suction.density * (geo.clearance_volume + geo.swept_volume) / v_start
    guess = suction.temperature * (rho_start / suction.density) ** (suction.kappa - 1.0)
    start = fluid.state_rhos(rho_start, suction.entropy, guess)
    # at a low pressure ratio the gas would already be above the discharge pressure at
    # the start angle with the valve shut, and its opening event (a crossing) never fires
    p_cap = START_PRESSURE_CAP * case.operating_point.discharge_pressure
    if start["p"] > p_cap:
        start = isentropic_state(fluid, suction, p_cap)
        rho_start = start["rho"]
    y0[cyl.Y_T] = start["T"]
    y0[cyl.Y_RHO] = rho_start
    scale = np.ones(cyl.N_STATE)
    scale[cyl.Y_T] = suction.temperature
    scale[cyl.Y_RHO] = suction.density
    for i, valve in enumerate((case.valves.suction, case.valves.discharge)):
        w_n = math.sqrt(valve.stiffness / valve.mass)
        scale[cyl.Y_XS + 2 * i] = valve.stop_height
        scale[cyl.Y_VS + 2 * i] = valve.stop_height * w_n
    return y0, scale


def crank_geometry(case: Case) -> CrankGeometry:
    """The slider-crank geometry of ``case`` for the mechanism library."""
    geo = case.geometry
    return CrankGeometry(
        bore=geo.bore, crank_radius=geo.crank_radius, rod_length=geo.connecting_rod_length
    )


def case_mechanism_parameters(case: Case) -> np.ndarray:
    """Mechanism parameter array (:mod:`recipsim.physics.mechanics.layout`) of ``case``: its
    mechanism, crank geometry, shell pressure, shaft speed and drive."""
    op = case.operating_point
    return mechanism_parameters(
        case.mechanism,
        crank_geometry(case),
        shell_pressure=op.shell_pressure,
        speed=op.shaft_speed,
        drive=case.options.drive,
        motor=case.motor,
    )


def build_model(case: Case, drive_pressure: tuple[np.ndarray, np.ndarray] | None = None) -> Model:
    """Lay out the compiled scene that ``case`` asks for.

    ``drive_pressure`` (crank angles [rad], pressures [Pa]) is the cylinder pressure on
    the rigid crank, which the coupled scene's ``torque_profile`` drive needs (the
    paper's driving torque is the pinned mechanism's under it); it comes from a solve of
    the cylinder scene, which this layer does not run:
    :func:`recipsim.solve.drive.build_model_for` provides it.

    ============  ===========  =====================================================
    pressure      mechanics    scene
    ============  ===========  =====================================================
    cylinder      pinned       cylinder on the rigid crank (bearing loads afterwards
                               by inverse dynamics)
    cylinder      flexible     coupled: cylinder + flexible crank train
    tabulated     pinned       no integration: inverse dynamics of the table
                               (:mod:`recipsim.physics.mechanics.pinned`); the model holds
                               the table and the mechanism parameters
    tabulated     flexible     flexible crank train under the table
    ============  ===========  =====================================================
    """
    model = cylinder_model(case)
    opts = case.options
    if not CRANK_TRAINS[opts.mechanics].flexible and PRESSURE_SOURCES[opts.pressure].solves_gas:
        return model
    mpar = case_mechanism_parameters(case)
    scene, p_angles, p_values = _pressure_table(case)
    drive = DRIVES[opts.drive]
    if drive.torque_table:
        d_angles, d_torques = _drive_table(case, p_angles, p_values, drive_pressure)
    else:
        d_angles, d_torques = np.zeros(1), np.zeros(1)
    b_tables = bearing_tables(case.mechanism)
    par = np.concatenate(
        [model.par[: scenes.P_TABLES], p_angles, p_values, d_angles, d_torques, b_tables]
    )
    par[scenes.P_MECH : scenes.P_MECH + mlay.N_PAR] = mpar
    par[scenes.P_LEAK_CLEARANCE] = case.leakage.radial_clearance
    ipar = model.ipar.copy()
    ipar[cyl.I_SCENE] = scene
    ipar[scenes.I_PTAB] = scenes.P_TABLES
    ipar[scenes.I_PTAB_N] = p_angles.size
    ipar[scenes.I_DTAB] = scenes.P_TABLES + 2 * p_angles.size
    ipar[scenes.I_DTAB_N] = d_angles.size
    ipar[scenes.I_BTAB] = scenes.P_TABLES + 2 * p_angles.size + 2 * d_angles.size
    ipar[scenes.I_BTAB_N] = b_tables.size
    free = drive.free_speed
    ipar[scenes.I_STOP_ON_ANGLE] = 1 if free else 0
    y0, scale, quads = _scene_state(model, scene, mpar, p_angles, p_values)
    return replace(
        model,
        par=par,
        ipar=ipar,
        y0=y0,
        scale=scale,
        n_err=scenes.state_size(scene),
        scene=scene,
        quadratures=quads,
        free_speed=free,
    )


def _pressure_table(case: Case) -> tuple[int, np.ndarray, np.ndarray]:
    """The scene of a flexible mechanism and the pressure table it reads.

    Parameters
    ----------
    case : Case
        A case whose mechanics are flexible or whose pressure is tabulated.

    Returns
    -------
    scene : int
        ``scenes.SCENE_MECHANISM`` under a tabulated pressure, else
        ``scenes.SCENE_COUPLED``.
    angles, pressures : numpy.ndarray
        The tabulated crank angles [rad] and pressures [Pa] (a single zero each when the
        cylinder gives the pressure).
    """
    if not PRESSURE_SOURCES[case.options.pressure].solves_gas:
        assert case.pressure_curve is not None
        curve = case.pressure_curve
        return scenes.SCENE_MECHANISM, curve.crank_angle, curve.pressure
    return scenes.SCENE_COUPLED, np.zeros(1), np.zeros(1)


def _scene_state(
    model: Model, scene: int, mpar: np.ndarray, p_angles: np.ndarray, p_values: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Initial state, state scales and quadrature slots of a scene with the mechanism.

    Parameters
    ----------
    model : Model
        The cylinder scene of the case (its initial gas state and scales; its property
        callback gives the starting pressure of the coupled scene).
    scene : int
        ``scenes.SCENE_COUPLED`` or ``scenes.SCENE_MECHANISM``.
    mpar : numpy.ndarray
        The mechanism's parameters.
    p_angles, p_values : numpy.ndarray
        The tabulated pressure (read by ``scenes.SCENE_MECHANISM``).

    Returns
    -------
    y0, scale : numpy.ndarray
        Initial state and scales (zero scale: a quadrature, outside error control).
    quads : numpy.ndarray
        Indices of the quadrature states.
    """
    m0 = scenes.mechanism_state_offset(scene)
    n = scenes.state_size(scene)
    y0 = np.zeros(n)
    scale = np.zeros(n)  # zero scale: a quadrature, outside error control
    if scene == scenes.SCENE_COUPLED:
        y0[: cyl.N_STATE] = model.y0
        scale[: cyl.N_ERR] = model.scale[: cyl.N_ERR]
        model.props(model.y0[cyl.Y_T], model.y0[cyl.Y_RHO])
        p_start = float(model.props.buffer[0])
        quads = np.concatenate([np.arange(cyl.N_ERR, cyl.N_STATE), _mech_quads(m0)])
    else:
        p_start = tabulated_pressure(START_ANGLE, p_angles, p_values)
        quads = _mech_quads(m0)
    omega = model.case.operating_point.shaft_speed
    y0[m0 : m0 + mlay.N_STATE] = initial_state(mpar, START_ANGLE, omega, p_start)
    scale[m0 : m0 + mlay.N_STATE] = state_scales(mpar)
    return y0, scale, quads


def _mech_quads(m0: int) -> np.ndarray:
    start = m0 + mlay.N_STATE
    return np.arange(start, start + scenes.N_MECH_QUAD)


def _drive_table(
    case: Case,
    p_angles: np.ndarray,
    p_values: np.ndarray,
    drive_pressure: tuple[np.ndarray, np.ndarray] | None,
) -> tuple[np.ndarray, np.ndarray]:
    """Torque of the pinned mechanism at constant speed under the same pressure (the
    paper's ``torque_profile`` drive); for the coupled scene the pressure is that of
    the cylinder on the rigid crank (``drive_pressure``)."""
    op = case.operating_point
    if PRESSURE_SOURCES[case.options.pressure].solves_gas:
        if drive_pressure is None:
            raise ValueError(
                "the coupled torque_profile drive needs the rigid crank's cylinder pressure: "
                "build the model with recipsim.solve.drive.build_model_for(case)"
            )
        p_angles, p_values = drive_pressure
    return pinned_torque_profile(
        case.mechanism,
        crank_geometry(case),
        p_angles,
        p_values,
        op.shell_pressure,
        op.shaft_speed,
    )
