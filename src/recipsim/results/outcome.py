"""How a run ended, in words shared by ``recipsim run``'s summary and sweeps.

Statuses (the summary's ``status`` column; a sweep row's ``status``):

- ``ok``: the periodic steady state, converged within ``solver.cycle_tolerance``;
- ``no_delivery``: converged, but the discharge valve never opens (the re-expanding
  clearance gas fills the stroke). The discharge quantities (discharge temperature,
  capacity, COP, isentropic efficiencies) are NaN *by design*, which the message says;
  the closures are defined on what does flow (:func:`no_delivery_closures`) and the
  volumetric efficiency is 0;
- ``subharmonic``: the valve dynamics settle on a period of n > 1 revolutions
  (:mod:`recipsim.solve.periodic`, found by shooting on the n-revolution map in
  :mod:`recipsim.solve.subharmonic`); the flows, powers and closures are the averages over
  the n revolutions, the cycle table shows the last one;
- ``not_converged``: ``solver.max_revolutions`` spent; the message holds the diagnosis
  (:func:`not_converged_diagnosis`: residual history and the states that drift);
- ``outside_envelope``: refused before integrating (:mod:`recipsim.case.envelope`);
- ``failed``: the integration or a property evaluation failed; the message names the
  quantity and the state (:class:`PropertyEvaluationError`).

Sweeps add ``invalid`` (the case cannot be built) and ``error`` (a bug in recipsim).
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING, Any

from recipsim.errors import SolverError
from recipsim.model.scenes import STATES, named_state
from recipsim.results.sampled import CycleColumns, nan_max
from recipsim.solve.residual import residual_reference

if TYPE_CHECKING:
    from recipsim.solve.revolution import PeriodicSolution

OK = "ok"
NO_DELIVERY = "no_delivery"
SUBHARMONIC = "subharmonic"
NOT_CONVERGED = "not_converged"
OUTSIDE_ENVELOPE = "outside_envelope"
FAILED = "failed"
#: every status a run can end with
RUN_STATUSES = (OK, NO_DELIVERY, SUBHARMONIC, NOT_CONVERGED, OUTSIDE_ENVELOPE, FAILED)

#: A discharge valve that passes less than this fraction of the swept suction-density
#: mass per revolution counts as never open (the integrator's event location alone can
#: leave a round-off there).
NO_DELIVERY_FRACTION = 1e-9

#: Summary columns that need gas through the discharge valve (NaN under ``no_delivery``).
DISCHARGE_COLUMNS = (
    "discharge_temperature [K]",
    "cooling_capacity [W]",
    "COP [-]",
    "indicated_COP [-]",
    "isentropic_power [W]",
    "isentropic_efficiency [-]",
    "indicated_isentropic_efficiency [-]",
)


class PropertyEvaluationError(SolverError):
    """A property evaluation failed; the message names the quantity and the state."""


def state_or_explain(
    fluid: Any, pair: str, a: float, b: float, what: str, entropy: bool = True
) -> dict[str, float]:
    """``fluid.state_ph(a, b)`` or ``fluid.state_ps(a, b)``, with a failure explained.

    Parameters
    ----------
    fluid : Fluid or TableFluid
    pair : {"ph", "ps"}
        Pressure [Pa] with specific enthalpy [J/kg] or specific entropy [J/(kg K)].
    a, b : float
        The pressure and the enthalpy or entropy.
    what : str
        What is being computed (``"the discharge temperature"``), for the message.
    entropy : bool
        With ``"ph"``: compute the entropy (an integral over the property table; NaN
        in the result when False).

    Raises
    ------
    PropertyEvaluationError
        With the library's reason, the state and ``what``, e.g. "CoolProp: no state at
        p = 1.2 MPa, h = 2.1e+05 J/kg (below the minimum) while computing the discharge
        temperature".
    """
    try:
        if pair == "ph":
            return fluid.state_ph(a, b, entropy=entropy)
        return fluid.state_ps(a, b)
    except (ValueError, ArithmeticError, RuntimeError) as exc:
        raise property_error(exc, pair, a, b, what) from None


def property_error(
    exc: Exception, pair: str, a: float, b: float, what: str
) -> PropertyEvaluationError:
    """The :class:`PropertyEvaluationError` of a failed ``pair`` evaluation at ``a, b``
    (see :func:`state_or_explain`)."""
    second = f"h = {b:.4g} J/kg" if pair == "ph" else f"s = {b:.4g} J/(kg K)"
    reason = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
    return PropertyEvaluationError(
        f"CoolProp: no state at p = {a / 1e6:.4g} MPa, {second} while computing {what} "
        f"({reason[:160]})"
    )


@contextmanager
def explained(stage: str) -> Iterator[None]:
    """Turn a library error (CoolProp's ValueError, a ZeroDivisionError, ...) raised
    during ``stage`` into a :class:`PropertyEvaluationError` naming the stage."""
    try:
        yield
    except (ValueError, ArithmeticError) as exc:
        reason = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
        raise PropertyEvaluationError(
            f"{type(exc).__name__} while {stage}: {reason[:200]}"
        ) from None


def delivered_mass(solution: PeriodicSolution) -> float:
    """Mass out through the discharge valve over the final revolution [kg] (gross)."""
    return float(named_state(solution.model.scene, solution.final.y_end).discharge_mass_out)


def discharge_valve_never_opens(solution: PeriodicSolution) -> bool:
    """Whether nothing (beyond round-off) left through the discharge valve."""
    model = solution.model
    swept = model.compressor_inlet.density * model.case.geometry.swept_volume
    return delivered_mass(solution) <= NO_DELIVERY_FRACTION * swept


def no_delivery_closures(solution: PeriodicSolution, cycle: CycleColumns) -> dict[str, float]:
    """Mass and energy closures of a revolution without delivery.

    Mass: net suction mass less leakage, relative to the largest of the gross suction
    in-flow and the gas mass in the cylinder (nothing else flows). Energy: indicated
    work - (enthalpy out - enthalpy in - heat in), relative to the gross boundary work
    ``closed integral |p dV|`` (the net work of a closed cycle is itself ~0, so relative
    to it the closure would read 1).
    """
    import numpy as np

    y = named_state(solution.model.scene, solution.final.y_end)
    m_suc = y.suction_mass_in - y.suction_mass_out
    m_dis = y.discharge_mass_out - y.discharge_mass_in
    m_leak = y.leakage_mass_out - y.leakage_mass_in
    m_ref = max(y.suction_mass_in, float(nan_max(cycle["gas_mass [kg]"])))
    h_out = (y.discharge_enthalpy_out - y.discharge_enthalpy_in) + (
        y.leakage_enthalpy_out - y.leakage_enthalpy_in
    )
    h_in = y.suction_enthalpy_in - y.suction_enthalpy_out
    p = cycle["cylinder_pressure [Pa]"]
    v = cycle["cylinder_volume [m3]"]
    gross_work = float(np.sum(np.abs(0.5 * (p + np.roll(p, -1)) * (np.roll(v, -1) - v))))
    energy = y.work_on_gas - (h_out - h_in - y.heat_to_gas)
    return {
        "mass_balance_residual [-]": float((m_suc - m_dis - m_leak) / m_ref),
        "energy_balance_residual [-]": float(energy / gross_work) if gross_work > 0 else 0.0,
    }


def not_converged_diagnosis(solution: PeriodicSolution) -> str:
    """Residual history and the drifting states of a run that did not converge."""
    history = solution.residual_history
    parts = [f"not converged after {solution.revolutions} revolutions"]
    if history:
        best = min(history)
        tail = history[-min(len(history), 10) :]
        trend = "stalled" if min(tail) >= 0.5 * best else "still decaying"
        parts.append(
            f"cycle residual {history[0]:.2e} -> {history[-1]:.2e} (best {best:.2e}, "
            f"last {len(tail)} between {min(tail):.2e} and {max(tail):.2e}: {trend})"
        )
    drift = drifting_states(solution)
    if drift:
        parts.append("drifting: " + ", ".join(drift))
    parts.append(f"tolerance {solution.model.case.solver.cycle_tolerance:.0e}")
    return "; ".join(parts)


def drifting_states(solution: PeriodicSolution, count: int = 3) -> list[str]:
    """The ``count`` states that change most over the final revolution, relative to their
    residual reference, as ``"name 1.2e-03"``."""
    import numpy as np

    model = solution.model
    rev = solution.final
    ref = residual_reference(model, rev)
    controlled = model.scale[: model.n_err] > 0.0
    change = np.zeros(model.n_err)
    d = np.abs(rev.y_end[: model.n_err] - rev.y_start[: model.n_err])
    change[controlled] = d[controlled] / ref[controlled]
    names = _state_names(model)
    order = np.argsort(change)[::-1][:count]
    return [f"{names[i]} {change[i]:.1e}" for i in order if change[i] > 0.0]


def _state_names(model: Any) -> list[str]:
    """Names of the error-controlled states, from the scene's state table
    (:data:`recipsim.model.scenes.STATES`: ``gas_temperature``, ``mechanism_crank_speed``)."""
    entries = STATES[model.scene].entries
    return [entries[i].name if i < len(entries) else f"state {i}" for i in range(model.n_err)]


def classify(
    solution: PeriodicSolution | None, cycle: CycleColumns, row: dict[str, Any]
) -> tuple[str, str]:
    """Status and message of a finished run; fixes the row of a ``no_delivery`` run.

    ``row`` is the summary row (:func:`recipsim.results.tables.summary`); under
    ``no_delivery`` its discharge columns become NaN and its closures those of
    :func:`no_delivery_closures`, under ``subharmonic`` it already holds the
    n-revolution averages.
    """
    if solution is None:
        return OK, ""
    if not solution.converged:
        return NOT_CONVERGED, not_converged_diagnosis(solution)
    period = getattr(solution, "period_revolutions", 1)
    backwards = row.get("discharge_mass_flow [kg/s]", 0.0) < 0.0
    if solution.model.has_gas and (discharge_valve_never_opens(solution) or backwards):
        why = (
            "more gas flows back through the discharge valve than leaves through it"
            if backwards and not discharge_valve_never_opens(solution)
            else "the discharge valve never opens"
        )
        row.update(dict.fromkeys(DISCHARGE_COLUMNS, math.nan))
        row.update(no_delivery_closures(solution, cycle))
        row["discharge_mass_flow [kg/s]"] = 0.0
        row["volumetric_efficiency [-]"] = 0.0
        return NO_DELIVERY, (
            f"{why} (the clearance gas re-expands over the whole "
            f"stroke at pressure ratio {row.get('pressure_ratio [-]', math.nan):.3g}): "
            "discharge temperature, capacity, COP and isentropic efficiencies are NaN by "
            "design; closures on the suction side and the gross p dV work"
        )
    if period > 1:
        return SUBHARMONIC, (
            f"the valve dynamics repeat every {period} revolutions: flows, powers and "
            f"closures are the {period}-revolution averages, the cycle table the last one"
        )
    return OK, ""
