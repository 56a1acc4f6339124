"""The rungs of the benchmark ladder and the reference settings.

A rung is a set of ``--set`` overrides on top of the case and the integrator that runs
them. Axes (see :func:`build_ladder`):

- tolerances of the compiled DOPRI5 integrator: ``solver.rtol`` (``atol`` follows it)
  x ``solver.cycle_tolerance``, and a longer ``solver.max_step``;
- the compiled DOPRI5 switching to the Rosenbrock-W step on stiff stretches
  (``dopri5_stiff``, table properties);
- integrators: scipy's ``solve_ivp`` methods driving the same compiled right-hand side
  from Python (:mod:`.ivp`);
- periodic solver: ``solver.periodic = "revolutions" | "shooting"``;
- property backend: every rung names it; HEOS unless the rung is about the
  tabulated properties (alone, with longer steps and with shooting);
- fidelity: cheaper valve models (``options.valves``), the rigid crank
  (``options.mechanics = "pinned"`` for a flexible case) and, for a case with any part
  of the loss chain, the indicated machine (``thermal = "fixed_wall"``, ``motor =
  "lossless"``, ``friction = "off"``, ``speed = "case"``: what the chain costs in time
  and what leaving it out changes); their errors are measured
  against the reference of the case as given, i.e. they show what the simplification
  costs, and they never count as "the cheapest setting";
- the baseline: the same model in pure Python (numba disabled) under ``solve_ivp``
  (:mod:`.baseline`).

A rung whose overrides the case loader rejects (an option not available in this
version) is recorded with status ``unavailable``, so the ladder completes itself as the
options appear.
"""

from __future__ import annotations

import itertools
import math
import re
from dataclasses import dataclass
from typing import Any

from recipsim.case.case import Case
from recipsim.case.case_schema import SOLVER_SPEC
from recipsim.case.overrides import parse_override
from recipsim.errors import RecipsimError
from recipsim.physics.friction_models import NO_FRICTION
from recipsim.physics.mechanics.crank_trains import CRANK_TRAINS, PINNED
from recipsim.physics.mechanics.drives import CONSTANT_SPEED, DRIVES
from recipsim.physics.motor_models import LOSSLESS
from recipsim.physics.speed_models import CASE_SPEED
from recipsim.physics.thermo.pressure_sources import PRESSURE_SOURCES
from recipsim.physics.thermo.property_backends import HEOS, TABLE
from recipsim.physics.thermo.thermal_models import FIXED_WALL
from recipsim.physics.thermo.valve_models import VALVE_MODELS

DOPRI5 = "dopri5"
#: the compiled DOPRI5 switching to the Rosenbrock-W step on stiff stretches
#: (``solver.method = "dopri5_stiff"``, :mod:`recipsim.solve.stiff`)
DOPRI5_STIFF = "dopri5_stiff"
#: integrators run by :func:`recipsim.solve.periodic.solve_periodic`
COMPILED = (DOPRI5, DOPRI5_STIFF)
#: scipy methods on the compiled right-hand side, in the full ladder
IVP_METHODS = ("RK45", "LSODA", "BDF", "Radau")
#: pure-Python baseline methods (what a user would pick: the default and the stiff switcher)
BASELINE_METHODS = ("RK45", "LSODA")
#: valve models from the cheapest up
VALVE_ORDER = tuple(m.name for m in sorted(VALVE_MODELS, key=lambda m: m.fidelity))
#: the exact property model and the tabulated one
HEOS_PROPERTIES = f"options.properties={HEOS.name}"

#: Reference: CoolProp HEOS (the exact property model, whatever the case's backend: the
#: table's interpolation error is part of a table rung's error), tolerances well below
#: anything the ladder asks for, revolutions until the cycle residual is 1e-8 (the floor:
#: at rtol 1e-10 the residual's own noise is ~1e-9).
REFERENCE_OVERRIDES = (
    HEOS_PROPERTIES,
    "solver.rtol=1e-10",
    "solver.atol=1e-10",
    "solver.cycle_tolerance=1e-8",
    "solver.min_revolutions=3",
    "solver.max_revolutions=400",
)
#: The reference's own integration error is judged against this run with ten times
#: tighter tolerances (same cycle tolerance: below 1e-8 the cycle residual stalls on its
#: own noise, e.g. 400 revolutions without reaching 1e-9 on the coupled scene).
SELF_CHECK_OVERRIDES = (
    HEOS_PROPERTIES,
    "solver.rtol=1e-11",
    "solver.atol=1e-11",
    "solver.cycle_tolerance=1e-8",
    "solver.min_revolutions=3",
    "solver.max_revolutions=400",
)


def _revolutions_if_available() -> tuple[str, ...]:
    """``solver.periodic=revolutions`` where the option exists (the reference iterates
    revolutions, the plainest periodic solver), nothing where it does not yet."""
    return ("solver.periodic=revolutions",) if "periodic" in SOLVER_SPEC else ()


def reference_overrides() -> tuple[str, ...]:
    """Overrides of the reference run (:data:`REFERENCE_OVERRIDES`, revolution iteration)."""
    return REFERENCE_OVERRIDES + _revolutions_if_available()


def self_check_overrides() -> tuple[str, ...]:
    """Overrides of the run that checks the reference (:data:`SELF_CHECK_OVERRIDES`)."""
    return SELF_CHECK_OVERRIDES + _revolutions_if_available()


@dataclass(frozen=True)
class Rung:
    """One setting of the ladder.

    Attributes
    ----------
    name : str
        Short label (CSV ``rung`` column, plot labels).
    integrator : str
        ``"dopri5"`` (the compiled integrator) or a ``solve_ivp`` method.
    overrides : tuple of str
        ``KEY=VALUE`` overrides applied after the case's own.
    baseline : bool
        Run in pure Python (numba disabled) in a separate process.
    """

    name: str
    integrator: str = DOPRI5
    overrides: tuple[str, ...] = ()
    baseline: bool = False


def _tol(rtol: float, cycle: float) -> tuple[str, ...]:
    return (f"solver.rtol={rtol:g}", f"solver.atol={rtol:g}", f"solver.cycle_tolerance={cycle:g}")


def _rung(
    integrator: str,
    rtol: float,
    cycle: float,
    *extra: str,
    label: str = "",
    baseline: bool = False,
    properties: str = HEOS.name,
) -> Rung:
    """A rung; the property backend is always explicit (the case's default may change)."""
    prefix = f"baseline {integrator}" if baseline else integrator
    name = f"{prefix}{' ' + label if label else ''} rtol={rtol:g} cyc={cycle:g}"
    overrides = _tol(rtol, cycle) + (f"options.properties={properties}",) + tuple(extra)
    return Rung(name, integrator, overrides, baseline)


def _table(
    rtol: float, cycle: float, *extra: str, label: str = TABLE.name, integrator: str = DOPRI5
) -> Rung:
    return _rung(integrator, rtol, cycle, *extra, label=label, properties=TABLE.name)


#: The loss chain's options of the indicated machine (lossless motor, no friction,
#: adiabatic shell at the line state, the case's speed).
INDICATED = {
    "thermal": FIXED_WALL.name,
    "motor": LOSSLESS.name,
    "friction": NO_FRICTION.name,
    "speed": CASE_SPEED.name,
}


def case_loss_chain(case: Case) -> dict[str, str]:
    """The case's loss-chain options, keyed as :data:`INDICATED`."""
    return {key: str(getattr(case.options, key)) for key in INDICATED}


def lower_fidelity(case: Case) -> list[tuple[str, tuple[str, ...]]]:
    """``(label, overrides)`` that simplify the case's model, one simplification each."""
    out: list[tuple[str, tuple[str, ...]]] = []
    valves = case.options.valves
    for v in VALVE_ORDER[: VALVE_ORDER.index(valves)] if valves in VALVE_ORDER else ():
        out.append((f"valves={v}", (f"options.valves={v}",)))
    if case_loss_chain(case) != INDICATED:
        out.append(("indicated", tuple(f"options.{k}={v}" for k, v in INDICATED.items())))
    solves_gas = PRESSURE_SOURCES[case.options.pressure].solves_gas
    if CRANK_TRAINS[case.options.mechanics].flexible and solves_gas:
        extra: tuple[str, ...] = (f"options.mechanics={PINNED.name}",)
        if DRIVES[case.options.drive].free_speed:  # the rigid crank turns at constant speed
            extra += (f"options.drive={CONSTANT_SPEED.name}",)
        out.append((f"mechanics={PINNED.name}", extra))
    return out


def _fidelity_rungs(case: Case, tolerances: list[tuple[float, float]]) -> list[Rung]:
    return [
        _rung(DOPRI5, rtol, cycle, *extra, label=label)
        for label, extra in lower_fidelity(case)
        for rtol, cycle in tolerances
    ]


def build_ladder(case: Case, quick: bool = False, baseline: bool = True) -> list[Rung]:
    """The rungs for ``case`` (the case as loaded with the command's own overrides).

    Parameters
    ----------
    case : Case
        Decides the fidelity rungs (only simplifications of its own model).
    quick : bool
        A reduced ladder (one or two rungs per axis) for tests and CI.
    baseline : bool
        Include the pure-Python baseline rungs.
    """
    rungs: list[Rung] = []
    if quick:
        rungs += [_rung(DOPRI5, 1e-4, 1e-3), _rung(DOPRI5, 1e-6, 1e-3)]
        rungs.append(_rung("LSODA", 1e-6, 1e-3))
        rungs.append(_rung(DOPRI5, 1e-6, 1e-3, "solver.periodic=shooting", label="shooting"))
        rungs.append(_table(1e-6, 1e-3))
        rungs.append(_table(1e-6, 1e-3, integrator=DOPRI5_STIFF))
        rungs += _fidelity_rungs(case, [(1e-6, 1e-3)])[:1]
        if baseline:
            rungs.append(_rung("LSODA", 1e-5, 1e-2, baseline=True))
        return rungs
    # the compiled integrator with CoolProp HEOS: tolerances, longer steps
    for rtol in (1e-4, 1e-5, 1e-6, 1e-7, 1e-8):
        for cycle in (1e-2, 1e-3, 1e-4, 1e-5):
            rungs.append(_rung(DOPRI5, rtol, cycle))
    for rtol, cycle in ((1e-5, 1e-3), (1e-6, 1e-3), (1e-5, 1e-4), (1e-6, 1e-4)):
        rungs.append(_rung(DOPRI5, rtol, cycle, "solver.max_step=5deg", label="step=5deg"))
    # scipy's integrators on the same compiled right-hand side
    for method in IVP_METHODS:
        for rtol, cycle in ((1e-4, 1e-3), (1e-6, 1e-3), (1e-8, 1e-3), (1e-6, 1e-4)):
            rungs.append(_rung(method, rtol, cycle))
    # periodic solver
    for periodic in ("revolutions", "shooting"):
        for rtol in (1e-5, 1e-6, 1e-7):
            for cycle in (1e-3, 1e-4):
                rungs.append(
                    _rung(DOPRI5, rtol, cycle, f"solver.periodic={periodic}", label=periodic)
                )
    # interpolated properties, alone, with longer steps and with shooting
    for rtol in (1e-4, 1e-5, 1e-6, 1e-7):
        for cycle in (1e-2, 1e-3, 1e-4):
            rungs.append(_table(rtol, cycle))
    for rtol, cycle in ((1e-5, 1e-3), (1e-6, 1e-3)):
        rungs.append(_table(rtol, cycle, "solver.max_step=5deg", label="table step=5deg"))
    for rtol in (1e-5, 1e-6, 1e-7):
        rungs.append(_table(rtol, 1e-3, "solver.periodic=shooting", label="table shooting"))
    # DOPRI5 switching to the Rosenbrock-W step where its stability limits the step
    for rtol in (1e-5, 1e-6, 1e-7):
        for cycle in (1e-3, 1e-4):
            rungs.append(_table(rtol, cycle, integrator=DOPRI5_STIFF))
    for rtol, cycle in itertools.product((1e-5, 1e-6), (1e-3, 1e-4)):
        step = "solver.max_step=5deg"
        rungs.append(_table(rtol, cycle, step, label="table step=5deg", integrator=DOPRI5_STIFF))
    rungs += _fidelity_rungs(case, [(1e-6, 1e-3), (1e-6, 1e-4)])
    # and at the shipped settings, to set beside the case's own rung there
    rungs += [
        _table(1e-6, 1e-4, *extra, label=f"table {label}", integrator=DOPRI5_STIFF)
        for label, extra in lower_fidelity(case)
    ]
    if baseline:
        for method in BASELINE_METHODS:
            for rtol, cycle in ((1e-5, 1e-3), (1e-6, 1e-3), (1e-6, 1e-4)):
                rungs.append(_rung(method, rtol, cycle, baseline=True))
    return rungs


def select_rungs(rungs: list[Rung], pattern: str | None) -> list[Rung]:
    """The rungs whose name matches the regular expression ``pattern`` (all if None).

    Raises
    ------
    RecipsimError
        If ``pattern`` is not a regular expression or matches no rung (the message lists
        the rung names).
    """
    if pattern is None:
        return rungs
    try:
        regex = re.compile(pattern)
    except re.error as exc:
        raise RecipsimError(f"--rungs {pattern!r} is not a regular expression: {exc}") from exc
    kept = [r for r in rungs if regex.search(r.name)]
    if not kept:
        names = "; ".join(r.name for r in rungs)
        raise RecipsimError(f"--rungs {pattern!r} matches no rung of this ladder: {names}")
    return kept


def _degrees(value: Any) -> Any:
    return math.degrees(value) if isinstance(value, float) else value


def case_settings(case: Case, integrator: str) -> dict[str, Any]:
    """The settings columns of a loaded rung (``periodic``: the case's setting)."""
    s = case.solver
    return {
        "integrator": integrator,
        "rtol": s.rtol,
        "atol": s.atol,
        "cycle_tolerance": s.cycle_tolerance,
        "max_step [deg]": _degrees(s.max_step),
        "properties": case.options.properties,
        "periodic": getattr(s, "periodic", "revolutions"),
        "valves": case.options.valves,
        "mechanics": case.options.mechanics,
        **case_loss_chain(case),
    }


_KEYS = {
    ("solver", "rtol"): "rtol",
    ("solver", "atol"): "atol",
    ("solver", "cycle_tolerance"): "cycle_tolerance",
    ("solver", "max_step"): "max_step [deg]",
    ("solver", "periodic"): "periodic",
    ("options", "properties"): "properties",
    ("options", "valves"): "valves",
    ("options", "mechanics"): "mechanics",
    **{("options", key): key for key in INDICATED},
}


def requested_settings(base: Case, rung: Rung) -> dict[str, Any]:
    """The settings columns of a rung that could not be loaded: the base case's values
    with the rung's overrides as written (values the loader rejected stay raw)."""
    out = case_settings(base, rung.integrator)
    for text in rung.overrides:
        path, value = parse_override(text)
        column = _KEYS.get(tuple(path))  # type: ignore[arg-type]
        if column is not None:
            out[column] = value
    return out


def fidelity(base: Case, settings: dict[str, Any]) -> str:
    """``"case"`` when the rung models what the case models, else ``"lower"``."""
    same = settings["valves"] == base.options.valves and (
        settings["mechanics"] == base.options.mechanics
    )
    same = same and all(settings.get(k) == v for k, v in case_loss_chain(base).items())
    return "case" if same else "lower"
