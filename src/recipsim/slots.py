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
    The output columns it adds (:class:`Output`: name, unit, meaning).

A slot's own subclass adds what its model builder and compiled code need: a parameter
writer with a stated signature, the compiled functions, capability flags.

Adding a choice to a slot (the extension contract)
--------------------------------------------------
1. Write its module beside the slot's others (the slot's registry module names the
   folder): the compiled functions with the slot's signature, its entry object.
2. Register it: the slot's registry module imports the entry and lists it, and where the
   slot's compiled dispatch is an ``if`` chain on codes, adds one branch.
3. Test it (against a closed form or another choice's limit) and show it in a shipped
   case or a docs page.

Nothing else changes: the case schema, the model builder, the summary, the bench ladder,
the CLI's choices and the docs read the registry. ``tests/test_architecture.py`` fails
if a choice's name appears as a string literal in more than three modules.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any, Generic, TypeVar

from recipsim.schema import Choice


@dataclass(frozen=True)
class Output:
    """An output column a choice adds: ``name``, SI ``unit`` and ``meaning``."""

    name: str
    unit: str
    meaning: str


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
