"""Sphinx extension: the case-file reference, generated from recipsim's declarations.

The directive ``case-reference`` writes one table per case-file table: every key with
its SI unit, default, allowed range, whether it is required and its meaning, read from
the :mod:`recipsim.case.schema` declarations (``Field``, ``Choice``, ``Text``) that
validate the files. Tables validated by hand instead (``[mechanism.*]``, ``[bearings.*]``,
the top-level keys, the refrigerant file's top) list their keys from the parser's key
tuples, their units from :data:`recipsim.report.resolved_case.MECHANISM_UNITS`, and say
that the ranges are checked in code. A key added to a declaration appears here without
editing the documentation.
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
    if default == "":
        return "empty"
    if isinstance(default, float):
        return f"{default:g}"
    return f"``{default}``" if isinstance(default, str) else str(default)


def _cell(text: str) -> str:
    return " ".join(str(text).split()).replace("|", "\\|") or " "


def declared_rows(table: str, spec: Any) -> list[list[str]]:
    """Rows (key, unit, default, allowed, required, meaning) of one declared table."""
    from recipsim.case.schema import REQUIRED, Choice, Field

    rows = []
    for key, field in spec.items():
        meaning = field.doc or MEANINGS.get(f"{table}.{key}", "")
        if isinstance(field, Field):
            allowed = field.allowed() + (", whole number" if field.integer else "")
            unit = _unit(field.unit)
        elif isinstance(field, Choice):
            allowed = ", ".join(f"``{c}``" for c in field.choices)
            unit = "-"
        else:
            allowed, unit = "a string", "-"
        required = "yes" if field.default is REQUIRED else "no"
        rows.append([f"``{key}``", unit, _default(field, REQUIRED), allowed, required, meaning])
    return rows


def hand_rows(table: str, keys: tuple[str, ...], optional: dict[str, str]) -> list[list[str]]:
    """Rows of a table validated by hand: unit from MECHANISM_UNITS, range in code."""
    from recipsim.report.resolved_case import MECHANISM_UNITS

    rows = []
    for key in keys:
        unit = _unit(MECHANISM_UNITS.get(key, "dimensionless"))
        if key == "law":
            unit, allowed = "-", "``linear``"
        else:
            allowed = "checked in code (positive masses, inertias, stiffnesses)"
        default = optional.get(key, "")
        required = "no" if key in optional else "yes"
        meaning = MEANINGS.get(f"{table}.{key}", "")
        rows.append([f"``{key}``", unit, default, allowed, required, meaning])
    return rows


def tables() -> list[tuple[str, str, list[list[str]]]]:
    """(heading, note, rows) of every table of a case file and of a refrigerant file."""
    from recipsim.case import load, mechanism
    from recipsim.case.motor import MOTOR_SPEC
    from recipsim.case.refrigerant import LIMITS_SPEC, RATING_POINT_SPEC
    from recipsim.case.thermal import THERMAL_SPEC

    hand = "Validated by hand in :mod:`recipsim.case.mechanism`, not by a declaration."
    declared = [
        ("[options]", "", load.OPTION_SPEC),
        ("[operating_point]", _OP_NOTE, load.OPERATING_POINT_SPEC),
        (
            "[geometry]",
            "Give exactly one of ``clearance_ratio`` and ``clearance_volume``.",
            load.GEOMETRY_SPEC,
        ),
        ("[valves]", "", load.VALVES_TOP_SPEC),
        (
            "[valves.suction], [valves.discharge]",
            'Required unless ``options.valves = "ideal"``.',
            load.VALVE_SPEC,
        ),
        ("[leakage]", "", load.LEAKAGE_SPEC),
        (
            "[heat_transfer]",
            '``wall_temperature`` is required unless ``options.heat_transfer = "adiabatic"``.',
            load.HEAT_TRANSFER_SPEC,
        ),
        ("[solver]", "", load.SOLVER_SPEC),
        ("[motor]", 'Required with ``options.drive = "induction_motor"``.', MOTOR_SPEC),
        (
            "[thermal]",
            'Used with ``options.thermal = "network"`` (:mod:`recipsim.case.thermal`: '
            "what each default conductance stands for).",
            THERMAL_SPEC,
        ),
        (
            "[pressure_curve]",
            '``file`` is required with ``options.pressure = "tabulated"``.',
            load.PRESSURE_CURVE_SPEC,
        ),
    ]
    out = [("Top level", _TOP_NOTE, top_rows())]
    out += [
        (head, note, declared_rows(head.split(".")[0].split(",")[0].strip("[]"), spec))
        for head, note, spec in declared
    ]
    piston_optional = {
        "centre_of_mass_from_crown": "length / 2",
        "transverse_inertia": "solid cylinder of the bore",
    }
    out += [
        (
            "[mechanism.piston]",
            hand,
            hand_rows("mechanism.piston", mechanism._PISTON_KEYS, piston_optional),
        ),
        (
            "[mechanism.connecting_rod]",
            hand,
            hand_rows("mechanism.connecting_rod", mechanism._ROD_KEYS, {}),
        ),
        ("[mechanism.rotor]", hand, hand_rows("mechanism.rotor", mechanism._ROTOR_KEYS, {})),
        (
            "[bearings.<name>]",
            hand
            + " ``<name>``: "
            + ", ".join(f"``{n}``" for n in _bearing_names())
            + "; ``position_from_crown`` only for the "
            "piston bearings.",
            hand_rows("bearings", mechanism._PISTON_BEARING_KEYS, {}),
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
    ]
    known = {
        "name",
        "description",
        "refrigerant",
        "options",
        "operating_point",
        "geometry",
        "valves",
        "leakage",
        "heat_transfer",
        "solver",
        "mechanism",
        "bearings",
        "pressure_curve",
        "motor",
    }
    for extra in sorted(load.TOP_KEYS - known):  # a table added later, not documented here yet
        out.append((f"[{extra}]", "Accepted by the loader; not described here yet.", []))
    return out


def _bearing_names() -> tuple[str, ...]:
    from recipsim.physics.mechanics.layout import BEARING_NAMES

    return tuple(BEARING_NAMES)


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
    "Validated by hand in :func:`recipsim.case.load.case_from_dict`. Quantities may "
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
            StringList(reference_rst(), source="case-reference"), 0, container, match_titles=True
        )
        return container.children


def setup(app: Sphinx) -> dict[str, Any]:
    app.add_directive("case-reference", CaseReference)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}


__all__ = ["reference_rst", "setup"]
