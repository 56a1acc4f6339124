"""What every report column means: one table of (name, unit, meaning) per file.

The columns that are slots of a layout table take name, unit and meaning from the
table's entry (:class:`~recipsim.physics.layout_table.Entry`): in ``cycle.csv`` the
cylinder's outputs (:data:`recipsim.physics.thermo.cylinder.OUTPUTS`) and the
mechanism's (:data:`recipsim.physics.mechanics.layout.OUTPUTS`), in ``startup.csv`` the
start-up trace (:data:`recipsim.solve.startup.TRACE`). The columns computed from them
(crank angle in degrees, force magnitudes, film thickness) are declared here, the
summary's in :mod:`.summary_docs`. ``reports/README.md``'s column tables are generated
from these tables (:mod:`recipsim.report.column_readme`), and a test checks that every
column a run writes is in them.

A name may hold a placeholder standing for one column each: ``<name>`` a bearing
(:data:`~recipsim.physics.mechanics.layout.BEARING_NAMES`), ``<node>`` a node of the
shell thermal network (:data:`~recipsim.physics.thermo.shell_nodes.NODES`).
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass

from recipsim.physics.layout_table import Entry
from recipsim.physics.mechanics import layout as lay
from recipsim.physics.thermo import cylinder as cyl
from recipsim.physics.thermo.shell_nodes import NODES
from recipsim.results.cycle import CYCLE_COLUMNS
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


def _mechanism(first: int, count: int) -> list[Entry]:
    return list(lay.OUTPUTS.entries[first : first + count])


_NB = lay.N_BEARINGS

#: ``cycle.csv``, in the order the report writes the columns.
CYCLE_DOCS: tuple[ColumnDoc, ...] = (
    column("crank_angle [deg]", "crank angle from top dead centre"),
    column(
        "time [s]", "time from top dead centre (integral of 1 / crank speed over the crank angle)"
    ),
    *(from_entry(cyl.OUTPUTS.entries[i]) for _, i in CYCLE_COLUMNS),
    column(
        "suction_valve_state [-]",
        "mode of the suction valve: reed 0 seated, 1 moving, 2 on the stop; ideal 0 closed, 1 open",
    ),
    column("discharge_valve_state [-]", "mode of the discharge valve, as above"),
    *_first_bearing(_mechanism(lay.A_BEARING_FORCE, 3 * _NB)),
    column("bearing_force_<name> [N]", "magnitude of that force"),
    *_first_bearing(_mechanism(lay.A_BEARING_DISPLACEMENT, 3 * _NB)[:2]),
    *(
        from_entry(lay.OUTPUTS.entries[i])
        for i in (lay.A_CRANK_SPEED, lay.A_PISTON_LATERAL, lay.A_PISTON_TILT, lay.A_BEARING_POWER)
    ),
    column(
        "film_thickness_<name> [m]",
        "film thickness at the thinnest point of a lubricated bearing, radial clearance - "
        "displacement",
    ),
    column("eccentricity_ratio_<name> [-]", "displacement over the radial clearance"),
    from_entry(lay.OUTPUTS.entries[lay.A_BEARING_TORQUE]),  # the journal side's
    *_first_bearing(_mechanism(lay.A_BEARING_DISSIPATION, _NB)),
    *_first_bearing(_mechanism(lay.A_BEARING_CONTACT, _NB)),
    *_first_bearing(_mechanism(lay.A_BEARING_PEAK_PRESSURE, _NB)),
    from_entry(lay.OUTPUTS.entries[lay.A_PISTON_FRICTION]),
    from_entry(lay.OUTPUTS.entries[lay.A_PISTON_FRICTION_POWER]),
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
