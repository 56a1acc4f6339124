"""Model slots: one registry per ``options.*`` choice of a case.

A *slot* is a place in the model where a case picks one of several submodels: the valve
model (``options.valves``), the journal bearings' law (``options.bearing_law`` and each
bearing's ``law``), the in-cylinder heat transfer, the leakage, the friction, the motor,
the drive, the crank train, the thermal model, the speed, the pressure source and the
property backend. Each slot is one :class:`Slot` object, and each of its choices is one
:class:`ModelChoice` (or a slot's own subclass of it) declared **once, in the module that
implements it**, next to its physics.

What a choice declares
----------------------
``name``
    The value a case writes (``options.valves = "reed"``); nowhere else in the package is
    it spelt out: code asks the registry (``VALVE_MODELS[name]``) or the entry itself
    (``entry.moves_reeds``), never compares names.
``code``
    The integer the compiled kernels dispatch on (stored as a float in the parameter
    arrays, unique within the slot).
``summary`` and ``source``
    One line for the docs, ``recipsim cases --options`` and error messages, and where
    its law comes from (a paper, a textbook, a stated estimate).
``keys``
    The case keys it adds, as :mod:`recipsim.schema` declarations (unit, default,
    range, meaning) by table (``{"bearings.<name>": {"stiffness": ...}}``): the
    case-file reference and the validation read them. Keys every choice of a slot
    shares (a journal's film geometry) are the slot's, declared once with the table.
``outputs``
    The report columns it adds, those a report has with this choice and lacks without
    it (:class:`Output`: name, SI unit, meaning, and the table, ``cycle.csv`` or
    ``summary.csv``). The results read them where the columns depend on the choice (the
    cycle table writes the gas's columns of the case's pressure source; a bearing on an
    oil film gets its law's cycle and summary columns), the column docs
    (``reports/README.md``) document every declared column from them, naming the
    choices that add it, and ``tests/unit/results/test_choice_outputs.py`` holds real
    runs to them. A capability several choices share declares its tuple once (the film
    laws' columns, ``bearing_laws.law.FILM_OUTPUTS``) and each of those choices carries
    it. Columns every choice of a slot writes (NaN where one does not apply) are not
    outputs of a choice.

A slot's own subclass adds what its model builder and compiled code need: a parameter
writer with a stated signature, the compiled functions, capability flags.

Adding a choice to a slot (the extension contract)
--------------------------------------------------
1. Write its module beside the slot's others (the slot's registry module names the
   folder): the compiled functions with the slot's signature, its entry object (with
   the report columns it adds, if any, as ``outputs``).
2. Register it: the slot's registry module imports the entry and lists it, and where the
   slot's compiled dispatch is an ``if`` chain on codes, adds one branch.
3. Test it (against a closed form or another choice's limit) and show it in a shipped
   case or a docs page.

Nothing else changes: the case schema, the model builder, the summary, the bench ladder,
the CLI's choices, the docs and the report's column docs read the registry.
``tests/test_model_slots.py`` fails if a choice's name appears as a string literal in
more than three modules.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any, Generic, TypeVar

from recipsim.schema import Choice

#: The report tables a choice's output goes to: ``cycle.csv`` (a value per crank-angle
#: sample) and ``summary.csv`` (one row per run).
OUTPUT_TABLES = ("cycle", "summary")
#: In an output's name, one column per bearing that runs on the choice: the bearing's name.
PER_BEARING = "<name>"


@dataclass(frozen=True)
class Output:
    """A report column a choice adds: present with the choice, absent without it.

    Attributes
    ----------
    name : str
        The column's name as written, without its unit; :data:`PER_BEARING` (``<name>``)
        stands for the bearing's name in a column written once per bearing on the choice
        (``film_thickness_<name>``).
    unit : str
        Its SI unit, as the column writes it (``m``, ``Pa*s``, ``-``).
    meaning : str
        What it holds, one line (Markdown) without the choices, which the docs add.
    table : str
        The file it goes to, one of :data:`OUTPUT_TABLES`.

    Raises
    ------
    ValueError
        If ``table`` is not a report table.
    """

    name: str
    unit: str
    meaning: str
    table: str

    def __post_init__(self) -> None:
        if self.table not in OUTPUT_TABLES:
            raise ValueError(f"{self.name}: table {self.table!r} is not one of {OUTPUT_TABLES}")

    @property
    def column(self) -> str:
        """The column as written: ``"name [unit]"`` (a per-bearing one with ``<name>``)."""
        return f"{self.name} [{self.unit}]"

    @property
    def per_bearing(self) -> bool:
        """Whether it is written once per bearing on the choice."""
        return PER_BEARING in self.name

    def column_of(self, bearing: str) -> str:
        """The column of bearing ``bearing`` (a per-bearing output's; others as they are)."""
        return self.column.replace(PER_BEARING, bearing)


@dataclass(frozen=True)
class ModelChoice:
    """One choice of a model slot (see the module docstring for each field)."""

    name: str
    code: int
    summary: str
    source: str = ""
    keys: Mapping[str, Mapping[str, Any]] = field(default_factory=dict)
    outputs: tuple[Output, ...] = ()


C = TypeVar("C", bound=ModelChoice)


class Slot(Generic[C]):
    """The registry of one model slot: its choices by name and by code.

    Parameters
    ----------
    option : str
        The case key that picks the choice, e.g. ``"options.valves"``.
    doc : str
        One line: what the slot models.
    choices : iterable of ModelChoice
        The choices, in the order the docs list them.
    default : str or None
        The choice a case gets when it names none (None: decided by other keys, said in
        ``doc``).

    Raises
    ------
    ValueError
        If two choices share a name or a code, or ``default`` is not a choice.
    """

    def __init__(self, option: str, doc: str, choices: Iterable[C], default: str | None):
        self.option = option
        self.doc = doc
        self._choices: dict[str, C] = {}
        codes: dict[int, str] = {}
        for choice in choices:
            if choice.name in self._choices:
                raise ValueError(f"{option}: two choices named {choice.name!r}")
            if choice.code in codes:
                raise ValueError(
                    f"{option}: {choice.name!r} and {codes[choice.code]!r} share code {choice.code}"
                )
            self._choices[choice.name] = choice
            codes[choice.code] = choice.name
        if default is not None and default not in self._choices:
            raise ValueError(f"{option}: default {default!r} is not a choice")
        self.default = default

    @property
    def names(self) -> tuple[str, ...]:
        """The choices' names, in registration order."""
        return tuple(self._choices)

    def __iter__(self) -> Iterator[C]:
        return iter(self._choices.values())

    def __len__(self) -> int:
        return len(self._choices)

    def __contains__(self, name: object) -> bool:
        return name in self._choices

    def __getitem__(self, name: str) -> C:
        try:
            return self._choices[name]
        except KeyError:
            close = difflib.get_close_matches(str(name), self._choices, n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            raise KeyError(
                f"{self.option}: unknown choice {name!r}{hint}; choices: {', '.join(self.names)}"
            ) from None

    def by_code(self, code: int) -> C:
        """The choice whose compiled code is ``code``."""
        for choice in self._choices.values():
            if choice.code == code:
                return choice
        raise KeyError(f"{self.option}: no choice has code {code}")

    def code(self, name: str) -> int:
        """The compiled code of the choice ``name``."""
        return self[name].code

    def schema_choice(self, names: Iterable[str] | None = None, doc: str | None = None) -> Choice:
        """The case schema's declaration of this slot's key (a :class:`~recipsim.schema.Choice`
        of ``names``, all choices by default)."""
        allowed = tuple(self.names if names is None else names)
        return Choice(allowed, self.default, self.doc if doc is None else doc)

    def describe(self) -> list[tuple[str, str, str]]:
        """``(name, summary, source)`` of every choice, for docs and ``--help``."""
        return [(c.name, c.summary, c.source) for c in self]
