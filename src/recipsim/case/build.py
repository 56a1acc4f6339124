"""The validation of a case's raw TOML data as steps (:data:`STEPS`), in the order the
checks run: the header and refrigerant, options, operating point, geometry, valves,
leakage, heat transfer, solver, mechanism, then the checks across sections
(:mod:`.consistency`), the pressure curve, motor and shell. Each step names the
top-level tables it reads and the steps whose results it uses.

:func:`case_sections` runs every step: the keyword arguments of
:class:`~recipsim.case.case.Case`, which :func:`recipsim.case.case.case_from_dict` builds.
:func:`derived_sections` runs only the steps that some changed tables reach, taking the
others' results from a case already validated (:meth:`recipsim.case.case.Case.with_`:
a sweep point changes one to three keys of the operating point).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from collections.abc import Set as AbstractSet
from dataclasses import dataclass, replace
from functools import lru_cache
from typing import Any, NamedTuple

from recipsim.case import builders
from recipsim.case.case_schema import HEADER_SPEC, LEAKAGE_SPEC, OPTION_SPEC, TOP_KEYS
from recipsim.case.consistency import (
    check_buildable,
    check_shell_pressure,
    check_solver,
    check_supported,
)
from recipsim.case.friction import parse_friction
from recipsim.case.mechanism import MechanismSpec, mechanism_from_dict
from recipsim.case.motor import case_motor, check_motor_speed
from recipsim.case.motor_losses import friction_option
from recipsim.case.operating_point import operating_point
from recipsim.case.refrigerant import case_fluid, load_refrigerant
from recipsim.case.sections import Geometry, Leakage, Options
from recipsim.case.thermal import parse_thermal
from recipsim.schema import check_keys, read_table


def case_sections(
    raw: dict[str, Any], file: str, *, allow_external_paths: bool = False
) -> dict[str, Any]:
    """Validate the raw TOML data of a case: the keyword arguments of its ``Case``
    (all but ``raw`` and ``source_text``)."""
    check_keys(raw, TOP_KEYS, file, "")
    build = _Build(raw, file, allow_external_paths)
    for step in STEPS:
        build.run(step)
    return {"path": file, **build.fields()}


def derived_sections(
    base: Mapping[str, Any], raw: dict[str, Any], touched: AbstractSet[str]
) -> dict[str, Any]:
    """The sections of ``base`` that change when its raw data becomes ``raw``, where only
    the top-level tables (or keys) ``touched`` differ: the steps that read them, and the
    steps that use what those build, run again; the others' results are ``base``'s.

    Parameters
    ----------
    base : mapping
        The fields of a validated case (``vars(case)``), built from its ``raw``.
    raw : dict
        ``base.raw`` with some top-level tables changed.
    touched : set of str
        The top-level keys of ``raw`` that may differ from ``base.raw``.

    Returns
    -------
    dict
        Keyword arguments of ``dataclasses.replace(base, ...)``: the changed sections.

    Raises
    ------
    CaseError
        Where validating ``raw`` raises; not necessarily the same error that
        :func:`case_sections` raises first (validate the whole case for that message).
    """
    check_keys(raw, TOP_KEYS, base["path"], "")
    build = _Build(raw, base["path"], base["allow_external_paths"], base)
    for step in _reached(frozenset(touched)):
        build.run(step)
    return build.fields()


@lru_cache(maxsize=64)
def _reached(touched: frozenset[str]) -> tuple[_Step, ...]:
    """The steps that read a table of ``touched`` or use the result of such a step
    (found once per set of tables: a sweep's points change the same few)."""
    reached: list[_Step] = []
    for step in STEPS:
        if step.reads & touched or any(used.name in step.uses for used in reached):
            reached.append(step)
    return tuple(reached)


class _In(NamedTuple):
    """What every step reads: the raw data, the case file, whether files outside its
    folder may be read."""

    raw: dict[str, Any]
    file: str
    allow_external: bool


@dataclass(frozen=True)
class _Step:
    """One step of the validation: ``run(source, *results of uses)``; ``reads``: the
    top-level tables of the raw data it reads itself; ``kept``: the case holds its result
    (else it is an intermediate, or a check whose result is None)."""

    name: str
    run: Callable[..., Any]
    reads: frozenset[str] = frozenset()
    uses: tuple[str, ...] = ()
    kept: bool = True


def _liner_step(_: _In, geometry: Geometry, mechanism: MechanismSpec) -> Geometry:
    return builders.with_liner_length(geometry, mechanism)


def _friction_step(source: _In, options: Options, mechanism: MechanismSpec) -> Options:
    return replace(options, friction=friction_option(options, mechanism, source.file))


#: The validation of a case, in the order its checks run (the first error is the one
#: reported); a step's ``reads`` and ``uses`` must name everything it depends on.
STEPS: tuple[_Step, ...] = (
    _Step("top", lambda s: builders.header(s.raw, s.file), frozenset(HEADER_SPEC)),
    _Step(
        "refrigerant",
        lambda s, top: load_refrigerant(
            top["refrigerant"], s.file, "refrigerant", list(builders.refrigerant_search(s.file))
        ),
        uses=("top",),
    ),
    _Step(
        "options0",
        lambda s: Options(**read_table(s.raw.get("options"), OPTION_SPEC, s.file, "options")),
        frozenset({"options"}),
        kept=False,
    ),
    _Step("properties", lambda s, opt: opt.properties, uses=("options0",)),
    _Step(
        "fluid",
        lambda s, ref, properties: case_fluid(ref, properties),
        uses=("refrigerant", "properties"),
        kept=False,
    ),
    _Step(
        "operating_point",
        lambda s, ref, fluid: operating_point(s.raw.get("operating_point"), ref, fluid, s.file),
        frozenset({"operating_point"}),
        ("refrigerant", "fluid"),
    ),
    _Step(
        "valves",
        lambda s, opt: builders.valves(s.raw.get("valves"), opt, s.file),
        frozenset({"valves"}),
        ("options0",),
    ),
    _Step(
        "geometry0",
        lambda s, valves: builders.geometry(
            s.raw.get("geometry"), s.file, valves.discharge.port_diameter
        ),
        frozenset({"geometry"}),
        ("valves",),
        kept=False,
    ),
    _Step(
        "leakage",
        lambda s: Leakage(**read_table(s.raw.get("leakage"), LEAKAGE_SPEC, s.file, "leakage")),
        frozenset({"leakage"}),
    ),
    _Step(
        "heat_transfer",
        lambda s, opt: builders.heat_transfer(s.raw.get("heat_transfer"), opt, s.file),
        frozenset({"heat_transfer"}),
        ("options0",),
    ),
    _Step(
        "solver",
        lambda s: builders.solver_settings(s.raw.get("solver"), s.file),
        frozenset({"solver"}),
    ),
    _Step(
        "solver_check",
        lambda s, sv, opt: check_solver(sv, opt, s.file),
        uses=("solver", "options0"),
        kept=False,
    ),
    _Step(
        "mechanism",
        lambda s, geo, opt: mechanism_from_dict(
            s.raw, s.file, bore=geo.bore, default_law=opt.bearing_law
        ),
        frozenset({"mechanism", "bearings", "oil"}),
        ("geometry0", "options0"),
    ),
    _Step("geometry", _liner_step, uses=("geometry0", "mechanism")),
    _Step("options", _friction_step, uses=("options0", "mechanism")),
    _Step(
        "supported_check",
        lambda s, opt: check_supported(opt, s.file),
        uses=("options",),
        kept=False,
    ),
    _Step(
        "buildable_check",
        lambda s, geo, valves, opt: check_buildable(geo, valves, opt, s.file),
        uses=("geometry", "valves", "options"),
        kept=False,
    ),
    _Step(
        "pressure_curve",
        lambda s, opt: builders.pressure_curve(
            s.raw.get("pressure_curve"), opt, s.file, s.allow_external
        ),
        frozenset({"pressure_curve"}),
        ("options",),
    ),
    _Step(
        "motor",
        lambda s, opt, geo: case_motor(
            s.raw.get("motor"), opt.drive, opt.motor, s.file, geo.swept_volume
        ),
        frozenset({"motor"}),
        ("options", "geometry"),
    ),
    _Step(
        "motor_speed_check",
        lambda s, pair, opt, op: check_motor_speed(pair[1], opt.drive, op.shaft_speed, s.file),
        uses=("motor", "options", "operating_point"),
        kept=False,
    ),
    _Step("thermal", lambda s: parse_thermal(s.raw.get("thermal"), s.file), frozenset({"thermal"})),
    _Step(
        "friction",
        lambda s: parse_friction(s.raw.get("friction"), s.file),
        frozenset({"friction"}),
    ),
    _Step(
        "shell_check",
        lambda s, op, opt: check_shell_pressure(op, opt, s.file),
        uses=("operating_point", "options"),
        kept=False,
    ),
)
_BY_NAME = {step.name: step for step in STEPS}


class _Build:
    """The results of the steps run so far; a step not run takes the base case's result
    (or, for an intermediate, runs on the base's inputs when a changed step needs it)."""

    def __init__(
        self,
        raw: dict[str, Any],
        file: str,
        allow_external: bool,
        base: Mapping[str, Any] | None = None,
    ) -> None:
        self.source = _In(raw, file, allow_external)
        self.base = base
        self.results: dict[str, Any] = {}
        self.changed: list[str] = []

    def run(self, step: _Step) -> None:
        self.results[step.name] = step.run(self.source, *map(self.result, step.uses))
        self.changed.append(step.name)

    def result(self, name: str) -> Any:
        if name not in self.results:
            step = _BY_NAME[name]
            if step.kept and self.base is not None:
                self.results[name] = _base_result(self.base, name)
            else:  # an intermediate of unchanged inputs
                self.results[name] = step.run(self.source, *map(self.result, step.uses))
        return self.results[name]

    def fields(self) -> dict[str, Any]:
        """Keyword arguments of ``Case`` from the steps that ran."""
        out: dict[str, Any] = {}
        for name in self.changed:
            if name in _TO_CASE:
                out.update(_TO_CASE[name](self.results[name]))
            elif _BY_NAME[name].kept:
                out[name] = self.results[name]
        return out


def _base_result(base: Mapping[str, Any], name: str) -> Any:
    """The result of step ``name`` (kept) in the case of fields ``base``."""
    return _FROM_CASE[name](base) if name in _FROM_CASE else base[name]


#: the fields of the case from a kept step's result, where not the field of its name
_TO_CASE: dict[str, Callable[[Any], dict[str, Any]]] = {
    "top": lambda top: {"name": top["name"], "description": top["description"]},
    "properties": lambda _: {},  # held by the options
    "motor": lambda pair: {"motor": pair[0], "motor_circuit": pair[1]},
}
#: a kept step's result from the fields of the case, where not the field of its name
_FROM_CASE: dict[str, Callable[[Mapping[str, Any]], Any]] = {
    # the header's refrigerant is used only by a step that runs after the header ran
    "top": lambda case: {"name": case["name"], "description": case["description"]},
    "properties": lambda case: case["options"].properties,  # the friction step keeps it
    "motor": lambda case: (case["motor"], case["motor_circuit"]),
}
