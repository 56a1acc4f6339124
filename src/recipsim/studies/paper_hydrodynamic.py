"""The paper study's hydrodynamic column: the same loads with the journals on oil films.

The paper (Kurka et al., ISMA 2010) closes by asking for hydrodynamic bearings coupled
with the crank train (its conclusion 3 expects their loads to be close to the pinned
ones). This module runs the study's ``inertia`` and ``gas`` loads with the primary,
secondary and eccentric journals on a film law (``finite_journal`` by default: the
reference compressor's film geometry, clearance and oil as in
``reference_r134a_lbp_lubricated``) through the ordinary path of every case:
:class:`~recipsim.case.load.Case` -> :func:`recipsim.model.build.build_model` ->
:func:`recipsim.solve.periodic.solve_periodic`, so its cycle tables are those of
``recipsim run`` (film thickness, eccentricity, friction columns included).

The runs turn at the constant speed of the pinned runs: the paper's ``torque_profile``
drive (the pinned, frictionless driving torque) cannot supply the films' friction, so
the crank would slow every revolution and never repeat (on ``paper_tabulated`` no
periodic state is reached in 60 revolutions). The pin and the
piston bearings keep the case's laws. The solver is DOPRI5 switching to the
Rosenbrock-W step (the films' squeeze damping makes the crank train stiff), as in
``reference_r134a_lbp_lubricated``.
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from recipsim.case.load import Case
from recipsim.physics.mechanics.bearing_laws import finite_journal
from recipsim.physics.mechanics.bearing_laws.registry import BEARING_LAWS, JOURNAL_LAWS
from recipsim.physics.mechanics.drives import CONSTANT_SPEED
from recipsim.physics.mechanics.layout import JOURNAL_NAMES
from recipsim.physics.mechanics.tabulated import PressureCurve
from recipsim.pipeline import simulate_case
from recipsim.studies.paper_load_run import LoadRun, tabulated_case

#: Load configurations of the hydrodynamic column (the films bring their own damping,
#: so ``gas_damped`` has no hydrodynamic counterpart).
HYDRODYNAMIC_CONFIGURATIONS = ("inertia", "gas")
#: Bearings that run on the film law; the pin and piston bearings keep their laws.
JOURNALS = JOURNAL_NAMES
#: Film law of the column.
DEFAULT_LAW = finite_journal.LAW.name
#: The film laws a journal may run on: the hydrodynamic column's choices.
FILM_LAWS: tuple[str, ...] = tuple(name for name in JOURNAL_LAWS if BEARING_LAWS[name].film)
#: Solver of the film runs (``reference_r134a_lbp_lubricated``'s).
SOLVER_METHOD = "dopri5_stiff"


#: One load of the column (the study's flexible runs are the same kind of result).
HydrodynamicRun = LoadRun


def hydrodynamic_case(
    case: Case,
    curve: PressureCurve,
    *,
    law: str = DEFAULT_LAW,
    samples_per_revolution: int = 360,
    label: str = "",
) -> Case:
    """``case``'s crank train on film journals under a tabulated pressure, constant speed.

    Parameters
    ----------
    case : Case
        Gives the mechanism, the journals' film data (``diameter``, ``length``,
        ``radial_clearance``), the ``[oil]`` table, the shell pressure and the speed.
    curve : PressureCurve
        Cylinder pressure against crank angle from TDC [rad], [Pa].
    law : str
        Film law of the primary, secondary and eccentric journals, one of
        :data:`FILM_LAWS`.
    samples_per_revolution : int
        Samples of the reported revolution.
    label : str
        Appended to the case name (``<name>_hydrodynamic_<label>``).

    Returns
    -------
    Case
        Validated like the file for every key it changes; the pressure source is set to
        the given curve directly (a curve is data, not a case key).

    Raises
    ------
    CaseError
        If a journal lacks its film data.
    """
    changes: dict[str, Any] = {
        "options.drive": CONSTANT_SPEED.name,
        "solver.method": SOLVER_METHOD,
        "solver.samples_per_revolution": samples_per_revolution,
    }
    changes.update({f"bearings.{name}.law": law for name in JOURNALS})
    return tabulated_case(case, curve, changes, "hydrodynamic" + (f"_{label}" if label else ""))


def run_hydrodynamic(
    case: Case,
    loads: dict[str, PressureCurve],
    *,
    law: str = DEFAULT_LAW,
    samples_per_revolution: int = 360,
) -> dict[str, HydrodynamicRun]:
    """Solve each load of the column to its periodic state (:func:`simulate_case`).

    Parameters
    ----------
    case : Case
        See :func:`hydrodynamic_case`.
    loads : dict of str to PressureCurve
        Cylinder pressure per configuration (``"inertia"``: the shell pressure at
        every angle; ``"gas"``: the study's curve).
    law : str
        Film law of the journals.
    samples_per_revolution : int

    Returns
    -------
    dict of str to HydrodynamicRun
        By configuration, in the order of ``loads``.

    Raises
    ------
    CaseError
        If the case's journals lack film data.
    SolverError
        If an integration fails.
    """
    runs: dict[str, HydrodynamicRun] = {}
    for config, curve in loads.items():
        run_case = hydrodynamic_case(
            case, curve, law=law, samples_per_revolution=samples_per_revolution, label=config
        )
        t0 = time.perf_counter()
        run = simulate_case(run_case)
        assert run.solution is not None  # a flexible scene is always integrated
        cycle = run.cycle.copy()
        cycle["drive_torque [N m]"] = cycle["shaft_torque [N m]"]
        sol = run.solution
        runs[config] = HydrodynamicRun(
            configuration=config,
            case=run_case,
            cycle=cycle,
            summary=run.row,
            revolutions=sol.revolutions,
            converged=sol.converged,
            residual=sol.residual,
            nfev=sol.nfev,
            wall_time=time.perf_counter() - t0,
        )
    return runs


def constant_curve(pressure: float, points: int = 8) -> PressureCurve:
    """A pressure curve equal to ``pressure`` [Pa] at every crank angle (inertia load)."""
    angles = 2.0 * np.pi * np.arange(points) / points
    return PressureCurve(angles, np.full(points, float(pressure)))
