"""Boundary conditions and initial state of the start-up from rest
(:mod:`recipsim.solve.startup`, whose docstring states the model): the standstill
pressure, the pull-down ramp of the suction, discharge and shell pressures, the suction
gas temperature along it, and the state at standstill.
"""

from __future__ import annotations

import math

import numpy as np

from recipsim.errors import SolverError
from recipsim.model import scenes
from recipsim.model.build import Model, WorkingModel
from recipsim.physics.mechanics.flexible_setup import initial_state

#: crank angle at standstill [rad]: top dead centre
REST_ANGLE = 0.0
#: least superheat of the gas at rest and of the suction gas during the ramp [K]
REST_SUPERHEAT = 5.0


def standstill_pressure(model: Model) -> float:
    """``solver.standstill_pressure``, or the saturation pressure at the ambient
    temperature (above the critical temperature: the suction pressure) [Pa]."""
    given = model.case.solver.standstill_pressure
    if math.isfinite(given):
        return float(given)
    ambient = model.case.operating_point.ambient_temperature
    try:
        return float(model.fluid.saturation_pressure(ambient))
    except ValueError:
        return float(model.case.operating_point.suction_pressure)


def ramp_fraction(t: float, pull_down_time: float) -> float:
    """Smooth ramp ``3 x^2 - 2 x^3`` of ``x = t / pull_down_time`` in [0, 1] (1 once
    ``t >= pull_down_time``, and always for a zero ramp time) [-]."""
    if pull_down_time <= 0.0 or t >= pull_down_time:
        return 1.0
    x = max(t, 0.0) / pull_down_time
    return x * x * (3.0 - 2.0 * x)


def plenum_pressures(model: Model, p0: float, t: float) -> tuple[float, float, float]:
    """Suction, discharge and shell pressures at time ``t`` of the start-up [Pa]."""
    op = model.case.operating_point
    f = ramp_fraction(t, model.case.solver.pull_down_time)
    return tuple(  # type: ignore[return-value]
        p0 + f * (p - p0) for p in (op.suction_pressure, op.discharge_pressure, op.shell_pressure)
    )


def _gas_temperature(model: Model, p0: float, pressure: float, f: float) -> float:
    """Suction gas temperature at ramp fraction ``f`` and suction pressure ``pressure``:
    from the rest temperature to the case's, never closer to the dew point than the
    case's own suction gas (nor than :data:`REST_SUPERHEAT`) [K]."""
    op = model.case.operating_point
    fluid = model.fluid
    t_rest = max(op.suction_temperature, fluid.saturation_temperature(p0) + REST_SUPERHEAT)
    margin = min(REST_SUPERHEAT, op.suction_temperature - fluid.saturation_temperature(
        op.suction_pressure))  # fmt: skip
    chord = op.suction_temperature + (1.0 - f) * (t_rest - op.suction_temperature)
    return max(chord, fluid.saturation_temperature(pressure) + margin)


def set_plenums(model: WorkingModel, p0: float, t: float, enthalpy: float | None) -> None:
    """Move the suction, discharge and shell states to their values at ``t`` [s]; the
    discharge plenum at ``enthalpy`` [J/kg] (None: the isentropic discharge of the
    suction gas)."""
    p_s, p_d, p_sh = plenum_pressures(model, p0, t)
    f = ramp_fraction(t, model.case.solver.pull_down_time)
    temperature = _gas_temperature(model, p0, p_s, f)
    model.set_suction_state(p_s, temperature)
    if enthalpy is None:
        enthalpy = float(model.fluid.state_ps(p_d, model.suction.entropy)["h"])
    model.set_discharge_state(p_d, enthalpy)
    model.set_shell_pressure(p_sh)
    model.set_shell_gas_state(temperature)


def rest_state(model: WorkingModel, p0: float) -> tuple[np.ndarray, np.ndarray]:
    """State and modes at standstill (module docstring); moves the plenums to ``t = 0``."""
    if model.scene != scenes.SCENE_COUPLED or not model.free_speed:
        raise SolverError(
            "start-up from rest runs the coupled scene on a free crank "
            "(options.pressure = 'cylinder', mechanics = 'flexible', drive = 'induction_motor')"
        )
    set_plenums(model, p0, 0.0, None)
    y = np.zeros_like(model.y0)
    gas = model.fluid.state_pt(p0, model.suction.temperature)
    model.gas_state(y)[:] = (gas["T"], gas["rho"])
    model.mechanism_state(y)[:] = initial_state(model.mechanism_par, REST_ANGLE, 0.0, p0)
    return y, np.zeros_like(model.mode0)
