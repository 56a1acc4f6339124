"""What ``recipsim check`` measures of a finished run: closures, non-finite results and
the cycle metrics an expectation may bound.

Closures, normalised by the swept mass (not by the delivered mass)
------------------------------------------------------------------
Over the converged revolution, with ``m_sw = rho_suction V_swept`` (the mass an ideal
compressor would take in per revolution) and ``dh_s = h(p_d, s_suction) - h_suction``:

- ``mass_closure = |m_suction - m_discharge - m_leakage| / m_sw``;
- ``energy_closure = |W_indicated - (H_out - H_in - Q_in)| / (m_sw dh_s)``;
- ``drive_closure = |P_shaft - P_indicated - P_bearings| / |P_shaft|`` (the crank train's
  energy balance: drive work = gas work + bearing dissipation; 0 for the rigid crank).

The summary's own ``mass_balance_residual`` divides the same imbalance by the suction
mass, which tends to zero with the delivery: the revolution's non-periodicity (the
change of the trapped gas mass) weighs 1/(volumetric efficiency) more there; the cycle
residual includes those closures (:mod:`recipsim.solve.residual`), so a converged run
has them below 10 cycle tolerances. Normalised by the swept mass the closures measure the
integration and periodicity error on the scale of what the cylinder handles, the same
for every operating point. Tolerances (defaults, ``expectations.toml`` may change them
per case): mass 1e-3 and energy 5e-3, the project's closure tolerances (README's
check table), about 10x and 20x above what a converged run at ``rtol = 1e-5`` gives;
drive 5e-3 as for energy.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from recipsim.model.scenes import named_state
from recipsim.physics.thermo.valve_models import VALVE_MODELS

if TYPE_CHECKING:
    from recipsim.results.case_run import CaseRun

#: Cycle metrics that an expectation may bound from below.
METRICS = ("suction_reed_openings", "discharge_reed_openings", "volumetric_efficiency")

#: The largest eccentricity ratio over the lubricated bearings of a run (``cycle_metrics``);
#: a converged run reaching 1 fails the check whatever its expectation says: a journal
#: never passes its sleeve (the film law and the asperity contact keep it inside).
ORBIT_METRIC = "largest_eccentricity_ratio"

# a reed is "closed" below this fraction of its stop height and "open" above the second
# (hysteresis, so that sampling noise near the seat is not counted as an opening)
_REED_CLOSED, _REED_OPEN = 0.02, 0.10

_CORE_FINITE = (
    "shaft_power [W]",
    "indicated_power [W]",
    "peak_cylinder_pressure [Pa]",
    "minimum_cylinder_pressure [Pa]",
    "mean_shaft_torque [N m]",
    "mean_crank_speed [rpm]",
    "cycle_residual [-]",
)
_GAS_FINITE = (
    "suction_mass_flow [kg/s]",
    "discharge_mass_flow [kg/s]",
    "leakage_mass_flow [kg/s]",
    "cooling_capacity [W]",
    "COP [-]",
    "volumetric_efficiency [-]",
    "isentropic_efficiency [-]",
    "discharge_temperature [K]",
    "mass_balance_residual [-]",
    "energy_balance_residual [-]",
)
_BEARING_PREFIXES = ("bearing_rms_", "bearing_max_", "orbit_radius_max_")


def reed_openings(lift: np.ndarray, stop_height: float) -> int:
    """Number of separate openings of a reed over one periodic revolution.

    The reed counts as closed below 2 % of its stop height and as open again above
    10 % (hysteresis): a reed that flutters back onto (or to within 2 % of) its seat in
    mid-stroke and lifts off again opens twice.
    """
    lift = np.asarray(lift, dtype=float)
    if lift.size == 0 or not np.all(np.isfinite(lift)):
        return 0
    closed, opened = _REED_CLOSED * stop_height, _REED_OPEN * stop_height
    start = int(np.argmin(lift))  # start where the reed is most closed
    is_open = False
    count = 0
    for x in np.roll(lift, -start):
        if not is_open and x > opened:
            is_open = True
            count += 1
        elif is_open and x < closed:
            is_open = False
    return count


def closures(run: CaseRun) -> dict[str, float | None]:
    """Mass, energy and drive closures of a run (module docstring); None: not applicable."""
    out: dict[str, float | None] = {"mass": None, "energy": None, "drive": None}
    sol = run.solution
    if sol is None:
        return out
    row = run.row
    p_shaft = float(row["shaft_power [W]"])
    p_ind = float(row["indicated_power [W]"])
    p_bearings = float(row.get("bearing_dissipation_power [W]", 0.0))
    out["drive"] = abs(p_shaft - p_ind - p_bearings) / abs(p_shaft) if p_shaft else math.nan
    model = sol.model
    if not model.has_gas:
        return out
    y = named_state(model.scene, sol.final.y_end)
    m_suc = y.suction_mass_in - y.suction_mass_out
    m_dis = y.discharge_mass_out - y.discharge_mass_in
    m_leak = y.leakage_mass_out - y.leakage_mass_in
    h_out = (y.discharge_enthalpy_out - y.discharge_enthalpy_in) + (
        y.leakage_enthalpy_out - y.leakage_enthalpy_in
    )
    h_in = y.suction_enthalpy_in - y.suction_enthalpy_out
    suction = model.suction
    m_swept = suction.density * run.case.geometry.swept_volume
    h_2s = model.fluid.state_ps(run.case.operating_point.discharge_pressure, suction.entropy)["h"]
    out["mass"] = float(abs(m_suc - m_dis - m_leak) / m_swept)
    out["energy"] = float(
        abs(y.work_on_gas - (h_out - h_in - y.heat_to_gas)) / (m_swept * (h_2s - suction.enthalpy))
    )
    return out


def non_finite_results(run: CaseRun) -> tuple[str, ...]:
    """Names of results that should be finite and are not (cycle columns and summary)."""
    row = run.row
    has_gas = run.solution is not None and run.solution.model.has_gas
    names = list(_CORE_FINITE) + [k for k in row if k.startswith(_BEARING_PREFIXES)]
    if has_gas:
        names += _GAS_FINITE
    bad = [k for k in names if k in row and not np.isfinite(float(row[k]))]
    numbers = run.cycle.select_dtypes("number")
    bad += [f"cycle:{c}" for c in numbers.columns if not np.all(np.isfinite(numbers[c]))]
    return tuple(bad)


def cycle_metrics(run: CaseRun) -> dict[str, float]:
    """Metrics of the converged revolution that expectations may bound (:data:`METRICS`)."""
    case = run.case
    out: dict[str, float] = {}
    ratios = [float(v) for k, v in run.row.items() if k.startswith("max_eccentricity_ratio_")]
    if ratios:
        out[ORBIT_METRIC] = max(ratios)
    if run.solution is None or not run.solution.model.has_gas:
        return out
    out["volumetric_efficiency"] = float(run.row["volumetric_efficiency [-]"])
    if VALVE_MODELS[case.options.valves].moves_reeds:
        for side in ("suction", "discharge"):
            lift = run.cycle[f"{side}_valve_lift [m]"].to_numpy()
            stop = getattr(case.valves, side).stop_height
            out[f"{side}_reed_openings"] = float(reed_openings(lift, stop))
    return out
