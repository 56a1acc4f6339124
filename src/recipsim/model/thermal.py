"""Coupling of the shell thermal network with the cylinder (``options.thermal = "network"``).

The network's nodes are quasi-steady (:mod:`recipsim.physics.thermo.shell_network`), so
they are solved exactly after every revolution, from that revolution's mean flows:

- in: the delivered and leaked mass, the suction back-flow, the enthalpy through the
  discharge valve and the piston gap, the cylinder gas's heat to the wall (the
  revolution's quadratures), the motor and friction losses;
- out, for the next revolution: the suction plenum state (the muffler node's temperature
  at the line pressure less the suction muffler's drop), the wall temperature the
  heat-transfer correlation sees, the discharge plenum (the discharge chamber node's
  enthalpy, the source of back-flow, at the line pressure plus the discharge muffler's
  drop) and the shell gas state that the piston gap draws from.

The revolution iteration (:func:`recipsim.solve.periodic.solve_revolutions`) and the
plain revolutions of shooting call :meth:`ThermalCoupling.update` and count its relative
change in the cycle residual, so the gas cycle and the network converge together (the
thermal update costs well under a revolution). Revolution iteration also moves the
cylinder's start state with the suction plenum
(:meth:`recipsim.model.scene_model.WorkingModel.update_thermal`), so each revolution discharges gas
drawn at the plenum it runs with. Before the first revolution a predictor
solves the network with the clearance-volume estimate of the mass flow and an
isentropic discharge, so the first revolution already starts near the heated suction
state.

Motor and friction losses are the ``[thermal]`` table's ``motor_loss_power`` and
``friction_power`` when set, else ``loss_sources(model, y_end, duration)`` when a model
provides it, else 0 (``loss_sources(model, y_end, duration, drive_power)``).
"""

from __future__ import annotations

import copy
import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any, Protocol

import numpy as np

from recipsim.case.load import Case
from recipsim.model.cycle_response import CycleResponse
from recipsim.model.plenum import PlenumState, isentropic_state
from recipsim.physics.thermo import cylinder as cyl
from recipsim.physics.thermo.shell_network import (
    CW,
    DC,
    LINK_NAMES,
    SG,
    SM,
    NetworkLoads,
    NetworkParameters,
    NetworkPressures,
    NetworkSolution,
    solve_network,
)
from recipsim.physics.thermo.shell_nodes import GP_DC, GP_SM
from recipsim.physics.thermo.suction_path import (
    film_pulse_factor,
    gas_tube_pressure_drop,
    series_conductance,
    tube_diameter,
    tube_film_coefficient,
)

_DEW_MARGIN = 0.5  # K


class CoupledModel(Protocol):
    """What the coupling needs of :class:`recipsim.model.scene_model.WorkingModel`."""

    case: Case
    fluid: Any

    @property
    def suction(self) -> PlenumState: ...
    @property
    def discharge(self) -> PlenumState: ...

    def set_suction_state(self, pressure: float, temperature: float) -> None: ...
    def set_discharge_state(self, pressure: float, enthalpy: float) -> None: ...
    def set_shell_gas_state(self, temperature: float) -> None: ...
    def set_wall_temperature(self, temperature: float) -> None: ...


@dataclass(frozen=True)
class AppliedNetwork:
    """A network solution and the boundary it gave the cylinder.

    Attributes
    ----------
    solution : NetworkSolution
    loads : NetworkLoads
        The flows and sources it was solved with.
    pressures : NetworkPressures
        Its node pressures (suction and discharge plenum pressures among them).
    parameters : NetworkParameters
        The conductances it was solved with (the suction path's films at its flows).
    """

    solution: NetworkSolution
    loads: NetworkLoads
    pressures: NetworkPressures
    parameters: NetworkParameters


class ThermalCoupling:
    """The network of one model and its last solutions.

    Attributes
    ----------
    applied : AppliedNetwork or None
        The solution the cylinder runs with now (solved from the last revolution).
    last_loads : NetworkLoads or None
        The flows of the last integrated revolution, as measured.
    loss_sources : callable or None
        ``(model, y_end, duration, drive_power) -> (motor loss, friction) [W]`` of a motor
        or friction model, used when the ``[thermal]`` table does not fix them: for the
        revolution whose quadratures are ``y_end``, or (``y_end`` None) for an estimated
        drive power [W].
    """

    def __init__(self, case: Case) -> None:
        self.spec = case.thermal
        self.parameters = case.thermal.network(case.operating_point.ambient_temperature)
        self.applied: AppliedNetwork | None = None
        self.last_loads: NetworkLoads | None = None
        #: suction plenum of the revolution before the last one (whose gas the last
        #: revolution discharged)
        self._earlier_plenum: PlenumState | None = None
        self._dew: dict[float, float] = {}  # dew point + margin at each pressure [K]
        self.loss_sources: (
            Callable[[Any, np.ndarray | None, float, float | None], tuple[float, float]] | None
        ) = None

    def working_copy(self) -> ThermalCoupling:
        """A copy with its own running state (the solutions applied, the last loads, the
        plenum before, the motor's last slip), for one solve
        (:meth:`recipsim.model.scene_model.Model.for_solve`); the dew point cache is
        shared."""
        work = copy.copy(self)
        work.loss_sources = copy.copy(self.loss_sources)
        return work

    # ---- the network's boundary -----------------------------------------------------------
    def _losses(
        self,
        model: CoupledModel,
        y_end: np.ndarray | None,
        duration: float,
        drive_power: float | None = None,
    ):
        """Motor loss and friction [W]: the ``[thermal]`` table's, else the models' for
        the revolution ``y_end`` or, before any, for the estimated ``drive_power`` [W]."""
        motor, friction = self.spec.motor_loss_power, self.spec.friction_power
        known = y_end is not None or drive_power is not None
        if (math.isnan(motor) or math.isnan(friction)) and self.loss_sources and known:
            m_model, f_model = self.loss_sources(model, y_end, duration, drive_power)
            motor = m_model if math.isnan(motor) else motor
            friction = f_model if math.isnan(friction) else friction
        return (0.0 if math.isnan(motor) else motor), (0.0 if math.isnan(friction) else friction)

    def loads(self, model: CoupledModel, y_end: np.ndarray, duration: float) -> NetworkLoads:
        """Mean flows of a revolution (quadratures ``y_end``, ``duration`` [s]) and the
        motor and friction sources."""
        f = 1.0 / duration
        motor, friction = self._losses(model, y_end, duration)
        return NetworkLoads(
            delivered_mass_flow=(y_end[cyl.Q_MDIS_OUT] - y_end[cyl.Q_MDIS_IN]) * f,
            leakage_mass_flow=(y_end[cyl.Q_MLEAK_OUT] - y_end[cyl.Q_MLEAK_IN]) * f,
            suction_backflow_mass_flow=y_end[cyl.Q_MSUC_OUT] * f,
            suction_backflow_enthalpy_flow=y_end[cyl.Q_HSUC_OUT] * f,
            discharge_enthalpy_flow=y_end[cyl.Q_HDIS_OUT] * f,
            leakage_enthalpy_flow=(y_end[cyl.Q_HLEAK_OUT] - y_end[cyl.Q_HLEAK_IN]) * f,
            heat_to_wall=-y_end[cyl.Q_HEAT] * f,
            motor_loss_power=motor,
            friction_power=friction,
            discharge_backflow_mass_flow=y_end[cyl.Q_MDIS_IN] * f,
        )

    def pressures(self, model: CoupledModel, loads: NetworkLoads) -> NetworkPressures:
        """Node pressures: the muffler drops with the mean flows and the densities of
        the plenum states now in the model."""
        op = model.case.operating_point
        spec = self.spec
        suction_flow = loads.delivered_mass_flow + loads.leakage_mass_flow
        suction, discharge, fluid = model.suction, model.discharge, model.fluid
        dp_s = gas_tube_pressure_drop(
            fluid, suction.pressure, suction.temperature, suction.density, suction_flow,
            spec.suction_tube,
        )  # fmt: skip
        dp_d = gas_tube_pressure_drop(
            fluid, discharge.pressure, discharge.temperature, discharge.density,
            loads.delivered_mass_flow, spec.discharge_tube,
        )  # fmt: skip
        if dp_s >= 0.5 * op.suction_pressure:
            raise ValueError(
                f"the suction muffler's pressure drop {dp_s:.4g} Pa reaches half the suction "
                "pressure: thermal.suction_muffler_loss_coefficient or _flow_area is off"
            )
        return NetworkPressures(
            inlet_pressure=op.suction_pressure,
            inlet_temperature=op.suction_temperature,
            node=(
                op.suction_pressure - dp_s,
                op.shell_pressure,
                op.discharge_pressure + dp_d,
                op.discharge_pressure,
            ),
        )

    def _state(self, model: CoupledModel) -> Callable[[float, float], tuple[float, ...]]:
        """``(p, T) -> (h, c_p, rho)`` of the vapour; below the dew point (a discharge
        chamber cooled under the condensing temperature when almost nothing is
        delivered) the vapour's enthalpy is continued linearly from 0.5 K above it:
        condensation inside the shell is outside the network."""
        fluid = model.fluid
        dew = self._dew

        def state(pressure: float, temperature: float) -> tuple[float, ...]:
            t_dew = dew.get(pressure)
            if t_dew is None:
                t_dew = dew[pressure] = fluid.saturation_temperature(pressure, 1.0) + _DEW_MARGIN
            if temperature >= t_dew:
                return fluid.enthalpy_pt(pressure, temperature)
            h, cp, rho = fluid.enthalpy_pt(pressure, t_dew)
            return h + cp * (temperature - t_dew), cp, rho * t_dew / temperature

        return state

    # ---- solving and applying -------------------------------------------------------------
    def _coupled_solution(
        self,
        model: CoupledModel,
        response: CycleResponse,
        pressures: NetworkPressures,
        parameters: NetworkParameters,
    ) -> NetworkSolution:
        """The network (``parameters``) together with the cycle moved to a plenum at the
        suction muffler's temperature (:class:`CycleResponse`), solved by one Newton."""
        state = self._state(model)
        p_sm = pressures.node[GP_SM]
        guess = None if self.applied is None else self.applied.solution.temperature

        def loads_at(t_sm: float) -> NetworkLoads:
            return response.at(t_sm, state(p_sm, t_sm))

        try:
            return solve_network(parameters, loads_at, pressures, state, guess)
        except ValueError:
            # far from the periodic state (a shooting iterate, a nearly closed valve) the
            # linearised response can mislead Newton: the revolution's loads as they are
            return solve_network(parameters, response.loads, pressures, state, guess)

    def network_parameters(self, model: CoupledModel, loads: NetworkLoads) -> NetworkParameters:
        """The network's conductances at a revolution's flows: where the case gives the
        suction path's gas-side areas, the links of the suction muffler to the shell gas
        and to the cylinder wall are the gas film at the flow into the cylinder
        (Dittus-Boelter in the muffler tube, :mod:`recipsim.physics.thermo.suction_path`)
        in series with the fixed UA of the wall and outer side."""
        spec = self.spec
        areas = {
            "suction_muffler_shell_gas": spec.suction_muffler_gas_side_area,
            "suction_muffler_cylinder_wall": spec.suction_passage_gas_side_area,
        }
        if all(math.isnan(a) for a in areas.values()):
            return self.parameters
        suction = model.suction
        gas = model.fluid.transport(suction.pressure, suction.temperature)
        cp = model.fluid.enthalpy_pt(suction.pressure, suction.temperature)[1]
        prandtl = gas["viscosity"] * cp / gas["conductivity"]
        diameter = tube_diameter(spec.suction_muffler_flow_area)
        flow = loads.delivered_mass_flow + loads.leakage_mass_flow
        film = tube_film_coefficient(
            flow, diameter, gas["viscosity"], gas["conductivity"], prandtl,
            film_pulse_factor(spec.suction_pulsation_factor),
        )  # fmt: skip
        conductances = list(self.parameters.conductances)
        for name, area in areas.items():
            if not math.isnan(area):
                i = LINK_NAMES.index(name)
                conductances[i] = series_conductance(film * area, conductances[i])
        return replace(self.parameters, conductances=tuple(conductances))

    def _solve_and_apply(self, model: CoupledModel, response: CycleResponse) -> float:
        """Solve with the cycle's ``response``, give the cylinder the new boundary; the
        largest relative change of the boundary (suction plenum temperature and pressure,
        wall temperature, discharge plenum temperature and pressure)."""
        pressures = self.pressures(model, response.loads)
        # the films at the plenum the revolution ran with: the conductances solved with
        parameters = self.network_parameters(model, response.loads)
        solution = self._coupled_solution(model, response, pressures, parameters)
        _apply(model, solution, pressures)
        t = solution.temperature
        change = 1.0
        if self.applied is not None:
            old = self.applied
            t_old = old.solution.temperature
            change = max(
                abs(t[SM] - t_old[SM]) / t[SM],
                abs(t[CW] - t_old[CW]) / t[CW],
                abs(t[DC] - t_old[DC]) / t[DC],
                abs(pressures.node[GP_SM] - old.pressures.node[GP_SM]) / pressures.node[GP_SM],
                abs(pressures.node[GP_DC] - old.pressures.node[GP_DC]) / pressures.node[GP_DC],
            )
        self.applied = AppliedNetwork(solution, solution.loads, pressures, parameters)
        return change

    def update(
        self, model: CoupledModel, y_end: np.ndarray, duration: float, follows: bool = False
    ) -> float:
        """Solve the network with the revolution that just ended and apply it.

        Parameters
        ----------
        model : Model
        y_end : ndarray
            The revolution's end state (its quadratures) [SI].
        duration : float
            Its duration [s].
        follows : bool
            The gas the cylinder holds at the start angle follows the new suction plenum
            (:meth:`recipsim.model.scene_model.WorkingModel.update_thermal`), so the next revolution
            discharges gas drawn at the new plenum: the discharge stream is paired with
            the plenum of this revolution. Otherwise (shooting's revolutions, which start
            where the last one ended) with the plenum of the revolution before.

        Returns
        -------
        float
            Largest relative change of the boundary the network gives the cylinder:
            suction plenum temperature and pressure, wall temperature, discharge plenum
            temperature and pressure [-] (0 when the revolution delivered nothing: the
            network keeps its state). The other nodes follow the cycle's totals, which
            the cycle residual checks.
        """
        loads = self.loads(model, y_end, duration)
        self.last_loads = loads
        drawn = model.suction
        earlier = drawn if self._earlier_plenum is None or follows else self._earlier_plenum
        self._earlier_plenum = drawn
        if loads.delivered_mass_flow <= 0.0:
            return 0.0
        suction = (y_end[cyl.Q_MSUC_IN] - y_end[cyl.Q_MSUC_OUT]) / duration
        return self._solve_and_apply(model, CycleResponse(loads, suction, drawn, earlier))

    def continue_from(self, model: CoupledModel, other: ThermalCoupling) -> None:
        """Start ``model`` from the network solution of ``other`` (the same compressor at a
        nearby operating point, e.g. another speed) instead of the predictor's."""
        if other.applied is None:
            return
        self.applied = other.applied
        self._earlier_plenum = None
        _apply(model, other.applied.solution, other.applied.pressures)

    def predict(self, model: CoupledModel) -> None:
        """First network solution, before any revolution: mass flow from the clearance
        re-expansion estimate, isentropic discharge from the suction plenum, no wall heat,
        motor and friction losses at the isentropic power."""
        case = model.case
        geo = case.geometry
        freq = case.operating_point.shaft_speed / (2.0 * math.pi)
        clearance = geo.clearance_volume / geo.swept_volume
        s = model.suction
        ratio = model.discharge.pressure / s.pressure
        eta = max(0.2, 1.0 - clearance * (ratio ** (1.0 / s.kappa) - 1.0))
        m = eta * s.density * geo.swept_volume * freq
        h_dis = isentropic_state(model.fluid, s, model.discharge.pressure)["h"]
        # the motor's heat from the isentropic power: the largest source in the shell
        motor, friction = self._losses(model, None, 1.0 / freq, m * (h_dis - s.enthalpy))
        loads = NetworkLoads(m, 0.0, 0.0, 0.0, m * h_dis, 0.0, 0.0, motor, friction)
        self._solve_and_apply(model, CycleResponse(loads, m, s, s))


def _apply(model: CoupledModel, solution: NetworkSolution, pressures: NetworkPressures) -> None:
    """Give the cylinder the boundary of a network solution: suction plenum (suction
    muffler node), discharge plenum (discharge chamber), shell gas, cylinder wall."""
    t = solution.temperature
    model.set_suction_state(pressures.node[GP_SM], float(t[SM]))
    model.set_discharge_state(pressures.node[GP_DC], float(solution.enthalpy[DC]))
    model.set_shell_gas_state(float(t[SG]))
    model.set_wall_temperature(float(t[CW]))
