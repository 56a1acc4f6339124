"""Sphinx extension: the case-file reference, generated from recipsim's declarations.

The directive ``case-reference`` writes one table per case-file table: every key with
its SI unit, default, allowed range, whether it is required and its meaning, read from
the declarations that validate the files: :mod:`recipsim.schema` ``Field``,
``Choice``, ``Text`` for the tables read by :func:`~recipsim.schema.read_table`, and
``Described`` (unit and range words that the loader's checks and messages use) for the
tables validated in code: ``[mechanism.*]``, ``[bearings.<name>]``
(:mod:`recipsim.case.mechanism_schema`) and ``[oil]`` (:mod:`recipsim.case.lubrication`).
Only the case file's top-level keys are listed by hand. The tables of a refrigerant file,
of the check's ``expectations.toml`` and a sweep file's top level
(:data:`recipsim.studies.sweep.spec.SWEEP_SPEC`) follow. A key added to a declaration
appears here without editing the documentation; a top-level table without a declaration
is listed with a note, and the docs test fails on it.
"""

from __future__ import annotations

from typing import Any

from case_meanings import MEANINGS
from docutils import nodes
from docutils.statemachine import StringList
from sphinx.application import Sphinx
from sphinx.util.docutils import SphinxDirective


def _unit(unit: str) -> str:
    return "-" if unit == "dimensionless" else unit.replace("**", "^")


def _default(field: Any, required: object) -> str:
    default = field.default
    if default is required:
        return ""
    if default is None:
        return "not set"
    if isinstance(default, bool):
        return f"``{str(default).lower()}``"
    if default == "" or default == ():
        return "empty"
    if isinstance(default, float):
        return f"{default:g}"
    return f"``{default}``" if isinstance(default, str) else str(default)


def _cell(text: str) -> str:
    return " ".join(str(text).split()).replace("|", "\\|") or " "


def declared_rows(table: str, spec: Any) -> list[list[str]]:
    """Rows (key, unit, default, allowed, required, meaning) of one declared table."""
    from recipsim.schema import REQUIRED, Choice, Field, Flag, TextList

    rows = []
    for key, field in spec.items():
        meaning = field.doc or MEANINGS.get(f"{table}.{key}", "")
        if isinstance(field, Field):
            allowed = field.allowed() + (", whole number" if field.integer else "")
            unit = _unit(field.unit)
            meaning = _with_plausible(meaning, field)
        elif isinstance(field, Choice):
            allowed = ", ".join(f"``{c}``" for c in field.choices)
            unit = "-"
        elif isinstance(field, Flag):
            allowed, unit = "``true``, ``false``", "-"
        elif isinstance(field, TextList):
            allowed, unit = "a list of strings", "-"
        else:
            allowed, unit = "a string", "-"
        required = "yes" if field.default is REQUIRED else "no"
        rows.append([f"``{key}``", unit, _default(field, REQUIRED), allowed, required, meaning])
    return rows


def _with_plausible(meaning: str, field: Any) -> str:
    """The meaning, followed by the key's plausible range for a calibration and its source."""
    if field.plausible is None:
        return meaning
    low, high = field.plausible
    unit = "" if field.unit == "dimensionless" else f" {_unit(field.unit)}"
    condition = field.plausible_when
    when = f" (with ``{condition[0]} = {condition[1]}``)" if condition else ""
    note = f"Plausible {low:.3g} to {high:.3g}{unit}{when}: {field.plausible_source}."
    return f"{meaning}. {note}" if meaning else note


def described_rows(table: str, spec: Any, keys: tuple[str, ...] | None = None) -> list[list[str]]:
    """Rows of a table validated in code, from its ``Described`` declarations."""
    rows = []
    for key in keys or tuple(spec):
        field = spec[key]
        unit = _unit(field.unit) if field.unit else "-"
        default = field.default or ""
        meaning = field.doc or MEANINGS.get(f"{table}.{key}", "")
        rows.append([f"``{key}``", unit, default, field.allowed, field.requirement(), meaning])
    return rows


def tables() -> list[tuple[str, str, list[list[str]]]]:
    """(heading, note, rows) of every table of a case file, a refrigerant file, the check's
    expectations and a sweep file."""
    from recipsim.case import case_schema, mechanism_schema
    from recipsim.case.envelope_table import ENVELOPE_SPEC
    from recipsim.case.friction import FRICTION_SPEC
    from recipsim.case.lubrication import OIL_SPEC
    from recipsim.case.mechanism import PISTON_BEARING_KEYS
    from recipsim.case.motor import MOTOR_SPEC
    from recipsim.case.refrigerant import LIMITS_SPEC, RATING_POINT_SPEC, REFRIGERANT_SPEC
    from recipsim.case.thermal import THERMAL_SPEC
    from recipsim.studies.check.expectations import EXPECTATION_SPEC, MINIMUM_SPEC

    coded = (
        "Validated in :mod:`recipsim.case.mechanism` against the declarations of "
        ":mod:`recipsim.case.mechanism_schema` (the rules that involve other keys are "
        "checked in code, their words are these)."
    )
    declared = [
        ("[options]", "", case_schema.OPTION_SPEC),
        ("[operating_point]", _OP_NOTE, case_schema.OPERATING_POINT_SPEC),
        (
            "[geometry]",
            "Give exactly one of ``clearance_ratio`` and ``clearance_volume``.",
            case_schema.GEOMETRY_SPEC,
        ),
        ("[valves]", "", case_schema.VALVES_TOP_SPEC),
        (
            "[valves.suction], [valves.discharge]",
            'Required unless ``options.valves = "ideal"``.',
            case_schema.VALVE_SPEC,
        ),
        ("[leakage]", "", case_schema.LEAKAGE_SPEC),
        (
            "[heat_transfer]",
            '``wall_temperature`` is required unless ``options.heat_transfer = "adiabatic"``.',
            case_schema.HEAT_TRANSFER_SPEC,
        ),
        ("[solver]", "", case_schema.SOLVER_SPEC),
        ("[motor]", 'Required with ``options.drive = "induction_motor"``.', MOTOR_SPEC),
        (
            "[thermal]",
            'Used with ``options.thermal = "network"`` (:mod:`recipsim.case.thermal`: '
            "what each default conductance stands for).",
            THERMAL_SPEC,
        ),
        (
            "[friction]",
            'Used with ``options.friction = "mean"`` (:mod:`recipsim.case.friction`: '
            "the household compressor each default describes).",
            FRICTION_SPEC,
        ),
        (
            "[pressure_curve]",
            '``file`` is required with ``options.pressure = "tabulated"``.',
            case_schema.PRESSURE_CURVE_SPEC,
        ),
    ]
    out = [("Top level", _TOP_NOTE, top_rows())]
    out += [
        (head, note, declared_rows(head.split(".")[0].split(",")[0].strip("[]"), spec))
        for head, note, spec in declared
    ]
    journals = [n for n in _bearing_names() if n not in ("pin", "piston_top", "piston_skirt")]
    out += [
        (
            "[mechanism.piston]",
            coded,
            described_rows("mechanism.piston", mechanism_schema.PISTON_SPEC),
        ),
        (
            "[mechanism.connecting_rod]",
            coded,
            described_rows("mechanism.connecting_rod", mechanism_schema.ROD_SPEC),
        ),
        (
            "[mechanism.rotor]",
            coded + " Give ``counterweight_radius`` (and optionally its angle and z) only with "
            "``counterweight_mass > 0``.",
            described_rows("mechanism.rotor", mechanism_schema.ROTOR_SPEC),
        ),
        (
            "[bearings.<name>]",
            coded
            + " ``<name>``: "
            + ", ".join(f"``{n}``" for n in _bearing_names())
            + ". The film keys (``diameter`` to ``contact_friction``) are read for a "
            "bearing on a film law (and kept on a linear journal that gives them, so "
            "``options.bearing_law`` can switch it); the journals ("
            + ", ".join(f"``{n}``" for n in journals)
            + ") take all of them, the piston bearings only "
            + ", ".join(f"``{k}``" for k in PISTON_BEARING_KEYS[3:])
            + " (the piston film's diameter is the bore, its length the piston's).",
            described_rows("bearings", mechanism_schema.BEARING_SPEC),
        ),
        (
            "[oil]",
            "Validated in :func:`recipsim.case.lubrication.parse_oil`; read when a bearing "
            "runs on a film law (and checked whenever present). Without ``law`` only "
            "``name`` and ``film_temperature`` may be given.",
            described_rows("oil", OIL_SPEC),
        ),
        (
            "Refrigerant file: top level",
            "``refrigerants/<name>.toml``; its tables follow.",
            declared_rows("refrigerant", REFRIGERANT_SPEC),
        ),
        (
            "Refrigerant file: [limits]",
            "In ``refrigerants/<name>.toml``; each limit narrows CoolProp's range.",
            declared_rows("limits", LIMITS_SPEC),
        ),
        (
            "Refrigerant file: [rating_points.<name>]",
            "Named by ``operating_point.rating_point``.",
            declared_rows("rating_points", RATING_POINT_SPEC),
        ),
        (
            "Refrigerant file: [envelope]",
            "Where the compressor is meant to run; a case outside it is refused unless "
            '``solver.envelope = "ignore"``.',
            declared_rows("envelope", ENVELOPE_SPEC),
        ),
        (
            "Check expectations: [defaults], [cases.<name>]",
            "In ``expectations.toml`` beside the cases of ``recipsim check`` (the hard cases': "
            "``cases/hard/expectations.toml``); a ``[cases.<name>]`` table names a case "
            "file beside it and keeps what it leaves out from ``[defaults]``.",
            declared_rows("expectations", EXPECTATION_SPEC),
        ),
        (
            "Check expectations: minimum",
            "A sub-table of ``[defaults]`` or ``[cases.<name>]``: lower bounds on the metrics "
            "of a converged run.",
            declared_rows("minimum", MINIMUM_SPEC),
        ),
        (
            "Sweep file: top level",
            "A ``recipsim sweep`` file (:doc:`sweeps`), read by "
            ":func:`recipsim.studies.sweep.spec.load_sweep`. Its tables ``[set]`` (dotted "
            "case key = value), ``[axes]`` (dotted case key = list of values) and "
            "``[[points]]`` (tables of dotted case key = value) hold case keys, checked "
            "against the tables above when the points are planned.",
            sweep_rows(),
        ),
    ]
    # what the sections above describe: the top level's keys and every table's first part
    known = {row[0].strip("`") for row in top_rows()}
    known |= {head.strip("[").split("]")[0].split(".")[0] for head, _, _ in out}
    # a table added later, not documented here yet
    for extra in sorted(case_schema.TOP_KEYS - known):
        out.append((f"[{extra}]", "Accepted by the loader; not described here yet.", []))
    return out


def _bearing_names() -> tuple[str, ...]:
    from recipsim.physics.mechanics.layout import BEARING_NAMES

    return tuple(BEARING_NAMES)


def sweep_rows() -> list[list[str]]:
    """Rows of a sweep file's top level; its ``name`` follows the case's name rule."""
    from recipsim.studies.sweep.spec import SWEEP_SPEC

    rows = declared_rows("sweep", SWEEP_SPEC)
    case_rows = {row[0]: row for row in top_rows()}
    for row in rows:
        if row[0] == "``name``":  # checked_name's rule, the file's stem by default
            row[2], row[3] = case_rows["``name``"][2], case_rows["``name``"][3]
        elif row[0] == "``base``":  # resolved as a case's extends
            row[3] = case_rows["``extends``"][3]
    return rows


def top_rows() -> list[list[str]]:
    return [
        ["``refrigerant``", "-", "", "a refrigerant file's name", "yes", MEANINGS["refrigerant"]],
        [
            "``name``",
            "-",
            "the file's stem",
            "letters, digits, ``.``, ``_``, ``-``; at most "
            f"{_max_name()} characters, not starting with ``.``",
            "no",
            MEANINGS["name"],
        ],
        ["``description``", "-", "empty", "a string", "no", MEANINGS["description"]],
        [
            "``extends``",
            "-",
            "not set",
            "a case file beside this one or a shipped case name",
            "no",
            MEANINGS["extends"],
        ],
    ]


def _max_name() -> int:
    from recipsim.atomic import MAX_NAME_LENGTH

    return MAX_NAME_LENGTH


_TOP_NOTE = (
    "Validated by hand in :func:`recipsim.case.build.case_sections`. Quantities may "
    'carry units (``"3500 rpm"``, ``"-23.3 degC"``, ``"22 mm"``); bare numbers '
    "are in the SI unit of the key."
)
_OP_NOTE = (
    "Give ``rating_point`` (its values fill the keys not given) or the temperatures; "
    "exactly one of ``evaporating_temperature`` and ``suction_pressure``, and of "
    "``condensing_temperature`` and ``discharge_pressure``; ``suction_temperature`` "
    "and ``liquid_temperature`` are needed either way."
)


def reference_rst() -> list[str]:
    """The reference as reStructuredText lines."""
    lines: list[str] = []
    for heading, note, rows in tables():
        lines += [heading, "-" * max(len(heading), 3), ""]
        if note:
            lines += [note, ""]
        if not rows:
            continue
        lines += [".. list-table::", "   :header-rows: 1", "   :widths: 18 10 10 22 7 33", ""]
        header = ["key", "unit (SI)", "default", "allowed", "required", "meaning"]
        for row in [header, *rows]:
            lines.append(f"   * - {_cell(row[0])}")
            lines += [f"     - {_cell(c)}" for c in row[1:]]
        lines.append("")
    return lines


class CaseReference(SphinxDirective):
    """``.. case-reference::``: the generated tables."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        container = nodes.container()
        self.state.nested_parse(
            StringList(reference_rst(), source="case-reference"),
            0,
            container,
            match_titles=True,
        )
        return container.children


def setup(app: Sphinx) -> dict[str, Any]:
    app.add_directive("case-reference", CaseReference)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}


__all__ = ["reference_rst", "setup"]
