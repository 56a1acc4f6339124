"""Pick one submodel per slot and lay out the compiled scene: states, parameters, scales.

:func:`build_model` turns a validated :class:`~recipsim.case.load.Case` into a
:class:`Model`: the float and integer parameter arrays of the compiled right-hand
side, the property callback, the plenum states, the initial state and the state
scales used by the error control.

The cylinder scene's own arrays and property callback are packed by
:mod:`recipsim.model.cylinder_parameters`.

Size (over the project's 400 lines): the scenes' layout with the mechanism and the
plenum setters that the thermal network and shooting call between revolutions share the
model; moving the setters and the drive table into modules of their own is listed on
issue 13.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
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
from recipsim.model.loss_sources import NetworkLossSources, constant_speed_mean_friction
from recipsim.model.mechanism_parameters import bearing_tables, mechanism_parameters
from recipsim.model.pinned import pinned_torque_profile
from recipsim.model.plenum import PlenumState, isentropic_state, plenum_state, write_plenum
from recipsim.model.thermal import ThermalCoupling
from recipsim.physics.kinematics import piston_displacement
from recipsim.physics.mechanics import layout as mlay
from recipsim.physics.mechanics.flexible_setup import initial_state, state_scales
from recipsim.physics.mechanics.tabulated import tabulated_pressure
from recipsim.physics.thermo import cylinder as cyl
from recipsim.physics.thermo.properties import HeosProperties

if TYPE_CHECKING:
    from recipsim.case.refrigerant import AnyFluid


@dataclass
class Model:
    """A compiled scene ready to integrate.

    Attributes
    ----------
    par, ipar : ndarray
        Float and integer parameters (layouts in :mod:`recipsim.physics.thermo.cylinder`).
    props : HeosProperties
        Property callback passed to the compiled code.
    y0 : ndarray
        Initial state at :data:`START_ANGLE` (suction gas compressed isentropically
        from bottom dead centre).
    mode0 : ndarray
        Initial discrete modes.
    scale : ndarray
        Typical magnitude of each state for the absolute tolerance.
    period : float
        One revolution [s].
    """

    case: Case
    fluid: AnyFluid
    par: np.ndarray
    ipar: np.ndarray
    props: HeosProperties
    y0: np.ndarray
    mode0: np.ndarray
    scale: np.ndarray
    period: float
    suction: PlenumState
    discharge: PlenumState
    shell: PlenumState
    n_err: int = cyl.N_ERR
    scene: int = scenes.SCENE_CYLINDER
    #: indices of the quadrature states (reset at the start of every revolution)
    quadratures: np.ndarray = field(default_factory=lambda: np.arange(cyl.N_ERR, cyl.N_STATE))
    #: the crank speed is free (a revolution ends on the crank-angle event)
    free_speed: bool = False
    #: the gas entering the shell (the operating point's suction state); None: the
    #: suction plenum is that state (``options.thermal = "fixed_wall"``)
    inlet: PlenumState | None = None
    #: the shell's thermal network (``options.thermal = "network"``)
    thermal: ThermalCoupling | None = None
    #: the discharge plenum's enthalpy floor at each pressure [Pa -> J/kg]
    _enthalpy_floor: dict[float, float] = field(default_factory=dict, repr=False)

    @property
    def compressor_inlet(self) -> PlenumState:
        """The suction gas at the compressor inlet (capacity and efficiencies refer to it)."""
        return self.suction if self.inlet is None else self.inlet

    @property
    def has_gas(self) -> bool:
        """Whether the scene integrates the cylinder gas (else the pressure is tabulated)."""
        return self.scene != scenes.SCENE_MECHANISM

    @property
    def mechanism_offset(self) -> int:
        """Index of the first mechanism state (flexible scenes)."""
        return scenes.mechanism_state_offset(self.scene)

    @property
    def mechanism_par(self) -> np.ndarray:
        """The mechanism block of ``par`` (layout :mod:`recipsim.physics.mechanics.layout`)."""
        return self.par[scenes.P_MECH : scenes.P_MECH + mlay.N_PAR]

    def set_discharge_enthalpy(self, enthalpy: float) -> None:
        """Move the discharge plenum (the source of back-flow) to ``enthalpy`` [J/kg],
        kept at or above the vapour 0.5 K above its dew point (a Newton iterate of the
        shooting solver may ask for less: the plenum holds vapour, and a flash far into
        the liquid fails in CoolProp)."""
        self.set_discharge_state(self.discharge.pressure, enthalpy)

    def _discharge_enthalpy_floor(self, pressure: float) -> float:
        """Enthalpy of the vapour 0.5 K above the dew point at ``pressure`` [Pa] [J/kg]
        (-inf above the critical pressure)."""
        floor = self._enthalpy_floor.get(pressure)
        if floor is None:
            if pressure >= getattr(self.fluid, "critical_pressure", math.inf):
                floor = -math.inf
            else:
                dew = self.fluid.saturation_temperature(pressure, 1.0)
                floor = float(self.fluid.enthalpy_pt(pressure, dew + 0.5)[0])
            if len(self._enthalpy_floor) > 64:  # a start-up ramps the pressure
                self._enthalpy_floor.clear()
            self._enthalpy_floor[pressure] = floor
        return floor

    def set_discharge_state(self, pressure: float, enthalpy: float) -> None:
        """Move the discharge plenum to ``pressure`` [Pa] and ``enthalpy`` [J/kg] (at least
        the floor of :meth:`set_discharge_enthalpy`)."""
        enthalpy = max(enthalpy, self._discharge_enthalpy_floor(pressure))
        state = plenum_state(self.fluid, pressure, enthalpy=enthalpy)
        self.discharge = state
        write_plenum(
            self.par, state, cyl.C_PD, cyl.C_RHOD, cyl.C_HD, cyl.C_KAPPAD, cyl.C_K0D, cyl.C_TD
        )

    def set_suction_state(self, pressure: float, temperature: float) -> None:
        """Move the suction plenum (the gas the suction valve draws) to (p [Pa], T [K])."""
        state = plenum_state(self.fluid, pressure, temperature=temperature)
        self.suction = state
        write_plenum(
            self.par, state, cyl.C_PS, cyl.C_RHOS, cyl.C_HS, cyl.C_KAPPAS, cyl.C_K0S, cyl.C_TS
        )

    def set_shell_gas_state(self, temperature: float) -> None:
        """The gas behind the piston (drawn into the gap by reverse leakage) at the shell
        pressure and ``temperature`` [K]."""
        if self.ipar[cyl.I_LEAK] == 0:
            return
        state = plenum_state(self.fluid, self.shell.pressure, temperature=temperature)
        self.shell = state
        self.par[cyl.C_RHOSHELL] = state.density
        self.par[cyl.C_HSHELL] = state.enthalpy
        self.par[cyl.C_MUSHELL] = state.viscosity

    def update_thermal(
        self, y_end: np.ndarray, duration: float, y_next: np.ndarray | None = None
    ) -> float:
        """Solve the thermal network (if any) with a revolution's quadratures ``y_end``
        over ``duration`` [s] and apply it; its relative change [-] (0 without one).

        ``y_next``, the state the next revolution starts from (``y_end``'s copy), follows
        a moved suction plenum in place: the gas the cylinder holds at the start angle,
        valves shut, was drawn from the old plenum; its density is scaled with the
        plenum's density and its temperature with the plenum's temperature, the same
        compression from a scaled intake (exact for an ideal gas). The next revolution
        then starts near the new periodic state instead of one lagging revolution
        behind (measured on 24 map points of the reference case: 5.0 instead of 6.5
        revolutions); at the periodic state the plenum does not move and nothing
        changes.
        """
        if self.thermal is None or not self.has_gas:
            return 0.0
        drawn = self.suction
        change = self.thermal.update(self, y_end, duration, follows=y_next is not None)
        if y_next is not None and self.suction is not drawn:
            y_next[cyl.Y_T] *= self.suction.temperature / drawn.temperature
            y_next[cyl.Y_RHO] *= self.suction.density / drawn.density
        return change


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
    network = opts.thermal == "network"
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
        _attach_network(model, case, fluid, suction)
    return model


def _attach_network(model: Model, case: Case, fluid: AnyFluid, suction: PlenumState) -> None:
    """Couple the thermal network to ``model``: predict the suction plenum and start the
    gas from it.

    Parameters
    ----------
    model : Model
        The cylinder scene, changed in place (inlet, thermal coupling, initial state
        and scales).
    case : Case
        The case (its ``options.friction`` feeds the network's loss sources).
    fluid : AnyFluid
        The refrigerant's property backend.
    suction : PlenumState
        The suction plenum of the operating point (the network's inlet).
    """
    model.inlet = suction
    model.thermal = ThermalCoupling(case)
    friction = constant_speed_mean_friction(case) if case.options.friction == "mean" else 0.0
    model.thermal.loss_sources = NetworkLossSources(friction)
    model.thermal.predict(model)
    model.y0, model.scale = _initial_gas_state(case, fluid, model.suction)


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
    if opts.mechanics == "pinned" and opts.pressure == "cylinder":
        return model
    mpar = case_mechanism_parameters(case)
    scene, p_angles, p_values = _pressure_table(case)
    if opts.drive == "torque_profile":
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
    free = opts.drive != "constant_speed"
    ipar[scenes.I_STOP_ON_ANGLE] = 1 if free else 0
    y0, scale, quads = _scene_state(model, scene, mpar, p_angles, p_values)
    model.par = par
    model.ipar = ipar
    model.y0 = y0
    model.scale = scale
    model.n_err = scenes.state_size(scene)
    model.scene = scene
    model.quadratures = quads
    model.free_speed = free
    return model


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
    if case.options.pressure == "tabulated":
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
    if case.options.pressure == "cylinder":
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
