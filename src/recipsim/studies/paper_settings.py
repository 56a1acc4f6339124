"""The paper study's settings as ``study.json`` records them: the operating point,
geometry, pressure curve, bearings and how the runs were made, and the hydrodynamic
column's case."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from recipsim.case.mechanism_spec import CrankGeometry, MechanismSpec
from recipsim.physics.mechanics.drives import CONSTANT_SPEED
from recipsim.physics.mechanics.layout import BEARING_NAMES
from recipsim.physics.mechanics.tabulated import PressureCurve
from recipsim.studies.paper_hydrodynamic import JOURNALS, SOLVER_METHOD
from recipsim.version import __version__

if TYPE_CHECKING:
    from recipsim.case.load import Case


def hydrodynamic_settings(case: Case, law: str) -> dict[str, Any]:
    """``study.json``'s description of the hydrodynamic column (its case, law, journals)."""
    journals = {}
    for name in JOURNALS:
        film = case.mechanism.bearing(name).film
        journals[name] = (
            None
            if film is None
            else {
                "diameter [m]": film.diameter,
                "length [m]": film.length,
                "radial_clearance [m]": film.radial_clearance,
                "film_temperature [K]": film.film_temperature,
                "viscosity [Pa s]": film.viscosity,
            }
        )
    return {
        "case": case.name,
        "law": law,
        "journals": journals,
        "drive": CONSTANT_SPEED.name,
        "solver": SOLVER_METHOD,
        "description": (
            f"the case `{case.name}` with primary, secondary and eccentric on `{law}` films, "
            "at constant speed (the pinned torque profile supplies no friction), solved "
            f"like a case (`{SOLVER_METHOD}`, cycle tolerance {case.solver.cycle_tolerance:g})"
        ),
    }


def study_settings(
    spec: MechanismSpec,
    geometry: CrankGeometry,
    curve: PressureCurve,
    shell_pressure: float,
    omega: float,
    **options: Any,
) -> dict[str, Any]:
    """The study's settings as written to ``study.json`` (SI, units in the keys)."""
    return {
        "recipsim": __version__,
        "shell_pressure [Pa]": float(shell_pressure),
        "crank_speed [rad/s]": float(omega),
        "crank_speed [rpm]": float(omega) * 60.0 / (2.0 * math.pi),
        "geometry": {
            "bore [m]": geometry.bore,
            "crank_radius [m]": geometry.crank_radius,
            "rod_length [m]": geometry.rod_length,
        },
        "pressure_curve": {
            "points": int(curve.crank_angle.size),
            "min [Pa]": float(np.min(curve.pressure)),
            "max [Pa]": float(np.max(curve.pressure)),
        },
        "bearings": {
            name: {"law": b.law, "stiffness [N/m]": b.stiffness, "damping [N s/m]": b.damping}
            for name, b in zip(BEARING_NAMES, spec.bearings, strict=True)
        },
        "undamped_runs": (
            "periodic response at constant speed, by shooting (Newton on the one-revolution map)"
            if options["undamped_start"] == "periodic"
            else f"transient from the {options['undamped_start'].replace('_', '-')} pose at "
            f"TDC, {options['undamped_revolutions']} revolutions, the last one reported, as "
            "in a time-marching run of the paper (no dissipation: never periodic)"
        ),
        "damped_run": "from the quasi-static pose until periodic",
        **options,
    }
