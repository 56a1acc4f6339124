"""What every report column means: one table of (name, unit, meaning) per file.

The columns that are slots of a layout table take name, unit and meaning from the
table's entry (:class:`~recipsim.physics.layout_table.Entry`): in ``cycle.csv`` the
cylinder's outputs (:data:`recipsim.physics.thermo.cylinder.OUTPUTS`) and the
mechanism's (:data:`recipsim.physics.mechanics.layout.OUTPUTS`), in ``startup.csv`` the
start-up trace (:data:`recipsim.solve.startup.TRACE`). The columns computed from them
(crank angle in degrees, force magnitudes) are declared here, the summary's in
:mod:`.summary_docs`. The columns that only some choices of a model slot add are
documented from those choices' declarations (:attr:`recipsim.slots.ModelChoice.outputs`,
:func:`choice_docs`), each line naming the choices that add the column: a new choice's
columns need no line here. ``reports/README.md``'s column tables are generated from
these tables (:mod:`recipsim.report.column_readme`), and a test checks that every column
a run writes is in them.

A name may hold a placeholder standing for one column each: ``<name>`` a bearing
(:data:`~recipsim.physics.mechanics.layout.BEARING_NAMES`), ``<node>`` a node of the
shell thermal network (:data:`~recipsim.physics.thermo.shell_nodes.NODES`).
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

from recipsim.physics.friction_models import FRICTION_MODELS
from recipsim.physics.layout_table import Entry
from recipsim.physics.mechanics import layout as lay
from recipsim.physics.mechanics.bearing_laws.registry import BEARING_LAWS
from recipsim.physics.mechanics.crank_trains import CRANK_TRAINS
from recipsim.physics.thermo import cylinder as cyl
from recipsim.physics.thermo.pressure_sources import PRESSURE_SOURCES
from recipsim.physics.thermo.shell_nodes import NODES
from recipsim.results.cycle import CYCLE_COLUMNS
from recipsim.slots import Output, Slot
from recipsim.solve import startup as su

#: What each placeholder of a column name stands for.
PLACEHOLDERS: dict[str, tuple[str, ...]] = {"<name>": lay.BEARING_NAMES, "<node>": NODES}


@dataclass(frozen=True)
class ColumnDoc:
    """One column of a report file (or one per bearing or node, see the placeholders).

    Attributes
    ----------
    name : str
        Column name without its unit, placeholders allowed (``bearing_rms_<name>``).
    unit : str or None
        Unit as written in the column name (``kg/s``, ``-``); None for a text column.
    meaning : str
        What it holds (Markdown: the README shows it as written).
    """

    name: str
    unit: str | None
    meaning: str

    @property
    def column(self) -> str:
        """The column as written in the file: ``"name [unit]"`` (text columns: ``name``)."""
        return self.name if self.unit is None else f"{self.name} [{self.unit}]"

    def columns(self) -> tuple[str, ...]:
        """The concrete columns: the placeholder filled with each of its values."""
        for placeholder, values in PLACEHOLDERS.items():
            if placeholder in self.name:
                return tuple(self.column.replace(placeholder, v) for v in values)
        return (self.column,)


def column(text: str, meaning: str) -> ColumnDoc:
    """A column declared as it is written: ``column("suction_pressure [Pa]", "...")``.

    Parameters
    ----------
    text : str
        ``"name [unit]"``, or a bare name for a text column.
    meaning : str
        What it holds.
    """
    match = re.fullmatch(r"(.+) \[([^\]]+)\]", text)
    if match is None:
        return ColumnDoc(text, None, meaning)
    return ColumnDoc(match.group(1), match.group(2), meaning)


def _bearing_pattern(name: str) -> str:
    """``name`` with a bearing name (a whole ``_``-separated part) put as ``<name>``."""
    for bearing in sorted(lay.BEARING_NAMES, key=len, reverse=True):
        pattern = re.sub(rf"(^|_){bearing}(_|$)", r"\g<1><name>\g<2>", name, count=1)
        if pattern != name:
            return pattern
    return name


def from_entry(entry: Entry) -> ColumnDoc:
    """The column of a layout slot: its name (a bearing's as ``<name>``), unit, meaning."""
    return ColumnDoc(_bearing_pattern(entry.name), entry.unit, entry.meaning)


def _first_bearing(entries: Iterable[Entry]) -> list[ColumnDoc]:
    """Columns of the slots of a per-bearing series, once (those of the first bearing)."""
    first = lay.BEARING_NAMES[0]
    return [from_entry(e) for e in entries if re.search(rf"(^|_){first}(_|$)", e.name)]


def documented(docs: Iterable[ColumnDoc]) -> set[str]:
    """Every concrete column the tables ``docs`` document."""
    return {c for doc in docs for c in doc.columns()}


#: The model slots whose choices add report columns, in the order the docs list their
#: columns, each with how a doc line names the case key that picks the choice.
OUTPUT_SLOTS: tuple[tuple[Slot[Any], str], ...] = (
    (PRESSURE_SOURCES, "`options.pressure`"),
    (CRANK_TRAINS, "`options.mechanics`"),
    (BEARING_LAWS, "the bearing's `law`"),
    (FRICTION_MODELS, "`options.friction`"),
)


def choice_names(names: list[str]) -> str:
    """Names in backticks, the last after "or"."""
    quoted = [f"`{name}`" for name in names]
    return ", ".join(quoted[:-1]) + " or " + quoted[-1] if len(quoted) > 1 else quoted[0]


def choice_docs(
    table: str, slots: tuple[tuple[Slot[Any], str], ...] = OUTPUT_SLOTS
) -> dict[str, ColumnDoc]:
    """The doc of every column the choices of ``slots`` add to ``table`` (``"cycle"`` or
    ``"summary"``), by column, in the order they are declared.

    Each declaration's meaning is followed by the choices that carry it (``(with
    `options.friction` = `mean`)``); a column that choices of two slots add, or that two
    declarations give different meanings, has each in turn, separated by semicolons.
    """
    carriers: dict[str, dict[tuple[str, Output], list[str]]] = {}
    for slot, key in slots:
        for choice in slot:
            for output in choice.outputs:
                if output.table == table:
                    by_meaning = carriers.setdefault(output.column, {})
                    by_meaning.setdefault((key, output), []).append(choice.name)
    docs = {}
    for column_name, by_meaning in carriers.items():
        first = next(iter(by_meaning))[1]
        meaning = "; ".join(
            f"{output.meaning} (with {key} = {choice_names(names)})"
            for (key, output), names in by_meaning.items()
        )
        docs[column_name] = ColumnDoc(first.name, first.unit, meaning)
    return docs


def _mechanism(first: int, count: int) -> list[Entry]:
    return list(lay.OUTPUTS.entries[first : first + count])


_NB = lay.N_BEARINGS
#: The cycle columns that only some choices add: the pressure source's (the gas's, among
#: the cylinder's outputs, and the valves' modes after them), then the others' (the film
#: bearings', after the mechanism's).
_SOURCE_DOCS = choice_docs("cycle", tuple(s for s in OUTPUT_SLOTS if s[0] is PRESSURE_SOURCES))
_OTHER_CHOICE_DOCS = choice_docs(
    "cycle", tuple(s for s in OUTPUT_SLOTS if s[0] is not PRESSURE_SOURCES)
)
_CYLINDER_DOCS = [from_entry(cyl.OUTPUTS.entries[i]) for _, i in CYCLE_COLUMNS]
_CYLINDER_COLUMNS = {doc.column for doc in _CYLINDER_DOCS}

#: ``cycle.csv``, in the order the report writes the columns.
CYCLE_DOCS: tuple[ColumnDoc, ...] = (
    column("crank_angle [deg]", "crank angle from top dead centre"),
    column(
        "time [s]", "time from top dead centre (integral of 1 / crank speed over the crank angle)"
    ),
    *(_SOURCE_DOCS.get(doc.column, doc) for doc in _CYLINDER_DOCS),
    *(doc for key, doc in _SOURCE_DOCS.items() if key not in _CYLINDER_COLUMNS),
    *_first_bearing(_mechanism(lay.A_BEARING_FORCE, 3 * _NB)),
    column("bearing_force_<name> [N]", "magnitude of that force"),
    *_first_bearing(_mechanism(lay.A_BEARING_DISPLACEMENT, 3 * _NB)[:2]),
    *(
        from_entry(lay.OUTPUTS.entries[i])
        for i in (lay.A_CRANK_SPEED, lay.A_PISTON_LATERAL, lay.A_PISTON_TILT, lay.A_BEARING_POWER)
    ),
    *_OTHER_CHOICE_DOCS.values(),
)

#: ``startup.csv``: the start-up trace's slots, the crank angle in degrees (wrapped) and
#: the speed in rpm added.
STARTUP_DOCS: tuple[ColumnDoc, ...] = (
    from_entry(su.TRACE.entries[su.TR_TIME]),
    column(
        "crank_angle [deg]",
        "crank angle from top dead centre, in [0, 360) (the crank starts at 0)",
    ),
    from_entry(su.TRACE.entries[su.TR_SPEED]),
    column("crank_speed [rpm]", "the same in revolutions per minute"),
    *(from_entry(e) for e in su.TRACE.entries[su.TR_MOTOR_TORQUE : su.TR_BEARING_LOAD]),
    from_entry(su.TRACE.entries[su.TR_BEARING_LOAD]),
)
