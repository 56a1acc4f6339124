"""What a compiled scene is (:class:`Model`) and the copy of it that one solve moves
(:class:`WorkingModel`).

A :class:`Model` is what :func:`recipsim.model.build.build_model` makes of a case,
once: the float and integer parameter arrays of the compiled right-hand side, the
fluid and the property callback, the plenum states of the operating point (with the
thermal network: after its predictor), the initial state and the state scales. Its
arrays are read-only once built, so nothing that solves it can change it: solving the
same model twice gives the same answer, and a caller's model stays as it was built.

A solve works on :meth:`Model.for_solve`, a :class:`WorkingModel`: its own copy of
every array (the compiled code only ever receives these writable copies: a read-only
array is another numba type and would compile the integrator again), and its own
thermal network state. The setters live there: between revolutions the solver moves
the copy's discharge plenum (the source of back-flow), the thermal network its suction
and discharge plena, shell gas and wall temperature, a start-up its pressures, and a
free crank its revolution's end angle. The periodic solution carries the working copy,
so results read the final boundary from it; a working copy of a working copy continues
from its state (the periodic solve after a start-up, the next speed of the motor-slip
iteration).

The plenum states are never changed, only replaced, so copies share them. Caches of
pure functions stay shared as well: the discharge enthalpy floor at each pressure, the
network's dew points, a plenum's lazily computed entropy and isentropic states, the
property callback's scratch buffer.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np

from recipsim.case.load import Case
from recipsim.model import scenes
from recipsim.model.plenum import PlenumState, plenum_state, write_plenum
from recipsim.model.thermal import ThermalCoupling
from recipsim.physics.mechanics import layout as mlay
from recipsim.physics.thermo import cylinder as cyl
from recipsim.physics.thermo.properties import HeosProperties

if TYPE_CHECKING:
    from recipsim.case.refrigerant import AnyFluid

#: The arrays of a model: read-only in a :class:`Model`, copied into a working copy.
_ARRAYS = ("par", "ipar", "y0", "mode0", "scale", "quadratures")


@dataclass
class Model:
    """A compiled scene ready to integrate; its arrays are read-only (solve
    :meth:`for_solve`).

    Attributes
    ----------
    par, ipar : ndarray
        Float and integer parameters (layouts in :mod:`recipsim.physics.thermo.cylinder`).
    props : HeosProperties
        Property callback passed to the compiled code.
    y0 : ndarray
        Initial state at :data:`recipsim.model.cylinder_parameters.START_ANGLE` (suction
        gas compressed isentropically from bottom dead centre).
    mode0 : ndarray
        Initial discrete modes.
    scale : ndarray
        Typical magnitude of each state for the absolute tolerance.
    period : float
        One revolution [s].
    suction, discharge, shell : PlenumState
        The plenum states the compiled scene reads (``par``'s plenum slots).
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
    #: the discharge plenum's enthalpy floor at each pressure [Pa -> J/kg] (a cache)
    _enthalpy_floor: dict[float, float] = field(default_factory=dict, repr=False)

    def __post_init__(self) -> None:
        for name in _ARRAYS:
            getattr(self, name).flags.writeable = False

    def for_solve(self) -> WorkingModel:
        """A working copy for one solve (module docstring): its own arrays and thermal
        network state, the plenum states and caches shared until it replaces them."""
        work = object.__new__(WorkingModel)
        work.__dict__.update(self.__dict__)  # the fields, without __init__'s cost
        for name in _ARRAYS:
            setattr(work, name, getattr(self, name).copy())
        if self.thermal is not None:
            work.thermal = self.thermal.working_copy()
        return work

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

    # ---- named access to the laid-out arrays: the solver, the results and the studies
    # read and write states and parameters through these, never through index constants
    @property
    def shaft_speed(self) -> float:
        """The nominal crank speed [rad/s] (``par``'s ``shaft_speed``)."""
        return float(self.par[cyl.C_OMEGA])

    @property
    def start_angle(self) -> float:
        """Crank angle at the start of a revolution of the rigid crank [rad]."""
        return float(self.par[cyl.C_THETA0])

    def state_index(self, name: str) -> int:
        """Position of the state slot ``name`` in this scene's state vector (its table in
        :data:`recipsim.model.scenes.STATES`: ``"gas_density"``,
        ``"mechanism_crank_speed"``, ``"drive_work"``)."""
        return scenes.STATES[self.scene].entry(name).index

    def gas_state(self, y: np.ndarray) -> np.ndarray:
        """View of the gas temperature [K] and density [kg/m3] of state(s) ``y`` (the
        last axis indexes the state vector; writable when ``y`` is)."""
        return y[..., cyl.Y_T : cyl.Y_RHO + 1]

    def mechanism_state(self, y: np.ndarray) -> np.ndarray:
        """View of the mechanism block of state(s) ``y`` (layout
        :data:`recipsim.physics.mechanics.layout.STATES`; flexible scenes)."""
        m0 = self.mechanism_offset
        return y[..., m0 : m0 + mlay.N_STATE]

    def mechanism_quadratures(self, y: np.ndarray) -> np.ndarray:
        """View of the mechanism quadratures of state(s) ``y`` (table
        :data:`recipsim.model.scenes.MECH_QUAD`; flexible scenes)."""
        q = self.mechanism_offset + mlay.N_STATE
        return y[..., q : q + scenes.N_MECH_QUAD]

    def mechanism_outputs(self, aux: np.ndarray) -> np.ndarray:
        """View of the mechanism block of scene output(s) ``aux`` (layout
        :data:`recipsim.physics.mechanics.layout.OUTPUTS`)."""
        return aux[..., scenes.A_MECH : scenes.N_AUX]

    def crank_angle(self, y: np.ndarray) -> float:
        """Crank angle [rad] of the flexible scene's state ``y``."""
        return float(y[self.mechanism_offset + mlay.Y_CRANK_ANGLE])

    def unwind_crank(self, y: np.ndarray) -> None:
        """Take one turn (2 pi) off the crank angle of state ``y`` in place (flexible
        scenes; the model is 2 pi-periodic in the crank angle)."""
        y[self.mechanism_offset + mlay.Y_CRANK_ANGLE] -= 2.0 * math.pi

    def detailed_output_par(self) -> np.ndarray:
        """A copy of ``par`` with the mechanism's post-processing outputs (peak film
        pressures) switched on; ``par`` itself for the rigid crank, which has none."""
        if self.scene == scenes.SCENE_CYLINDER:
            return self.par
        par = self.par.copy()
        par[scenes.P_MECH + mlay.P_DETAILED_OUTPUTS] = 1.0
        return par

    def with_start(self, y0: np.ndarray, start_angle: float) -> Model:
        """This model (a new one; arrays copied) starting from ``y0`` with the rigid
        crank's revolutions starting at ``start_angle`` [rad]."""
        par = self.par.copy()
        par[cyl.C_THETA0] = start_angle
        return replace(self, par=par, y0=y0.copy())


class WorkingModel(Model):
    """The working copy of a :class:`Model` that one solve moves (module docstring);
    made by :meth:`Model.for_solve`, its arrays writable."""

    #: Whether the last revolution integrated on this copy ended taking Rosenbrock-W
    #: steps: the next one starts with them
    #: (:func:`recipsim.solve.revolution.integrate_revolution`).
    ended_in_w_step: bool = False

    def __post_init__(self) -> None:  # a working copy's arrays stay writable
        pass

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

    def set_shell_pressure(self, pressure: float) -> None:
        """Move the shell pressure [Pa] (behind the piston and on the crank train); the
        shell gas keeps its other properties until :meth:`set_shell_gas_state`."""
        self.par[cyl.C_PSHELL] = pressure
        self.par[scenes.P_MECH + mlay.P_SHELL_PRESSURE] = pressure
        self.shell = replace(self.shell, pressure=pressure, isentropic={})

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

    def set_wall_temperature(self, temperature: float) -> None:
        """The cylinder wall temperature the heat-transfer correlation sees [K]."""
        self.par[cyl.C_TWALL] = temperature

    def set_revolution_end(self, theta_end: float) -> None:
        """Arm the crank-angle event of a free crank at ``theta_end`` [rad]."""
        self.par[scenes.P_THETA_END] = theta_end

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
        behind; at the periodic state the plenum does not move and nothing changes.
        """
        if self.thermal is None or not self.has_gas:
            return 0.0
        drawn = self.suction
        change = self.thermal.update(self, y_end, duration, follows=y_next is not None)
        if y_next is not None and self.suction is not drawn:
            y_next[cyl.Y_T] *= self.suction.temperature / drawn.temperature
            y_next[cyl.Y_RHO] *= self.suction.density / drawn.density
        return change
