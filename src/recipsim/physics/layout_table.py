"""Layout tables: each slot of a compiled array declared once, with its unit and meaning.

The compiled (numba) code indexes its state vector, parameter arrays and outputs with
module-level integer constants, which numba reads as compile-time constants. A
:class:`Layout` hands those integers out in declaration order and records what each
slot holds, so a constant is written once, next to its unit and meaning::

    STATES = Layout("cylinder states")
    Y_T = STATES.add("gas_temperature", "K", "gas temperature in the cylinder")
    Y_RHO = STATES.add("gas_density", "kg/m3", "gas density in the cylinder")
    N_STATE = STATES.size

The constants stay plain ints (numba, mypy and ruff see them as such); the table's
:attr:`Layout.entries` give name, unit, meaning and index to the report, the docs and
the tests. Units are written as in the report's column names (``kg/m3``,
``W/(m2 K)``, ``N m``, ``-`` for dimensionless); integer slots use ``code`` (an option
code), ``index`` (an offset into an array) or ``count`` (a length).

Constants that are not slots (aliases such as the number of error-controlled states,
option codes such as ``VALVES_REED``) stay plain constants beside the table.

This module imports nothing from recipsim: every layer may use it.
"""

from __future__ import annotations

from collections import namedtuple
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class Entry:
    """One slot of a layout.

    Attributes
    ----------
    name : str
        Unique name in its table (snake case; the report's column name where the
        report writes the slot).
    unit : str
        Unit in the report's notation (``m``, ``kg/m3``, ``N m``, ``-``), or ``code``,
        ``index``, ``count`` for integer slots.
    meaning : str
        What the slot holds, one line.
    index : int
        Position in the array.
    """

    name: str
    unit: str
    meaning: str
    index: int

    @property
    def column(self) -> str:
        """The name with its unit, as a report column: ``"cylinder_pressure [Pa]"``."""
        return f"{self.name} [{self.unit}]"


class Layout:
    """An ordered table of slots; :meth:`add` returns each slot's index.

    Parameters
    ----------
    title : str
        What the table lays out (``"cylinder states"``), for messages and docs.
    """

    def __init__(self, title: str) -> None:
        self.title = title
        self._entries: list[Entry] = []
        self._by_name: dict[str, Entry] = {}
        self._bundle_type: Any = None

    def add(self, name: str, unit: str, meaning: str) -> int:
        """Declare the next slot; returns its index.

        Parameters
        ----------
        name : str
            Unique name in this table.
        unit : str
            Its unit (see :class:`Entry`).
        meaning : str
            What it holds.

        Returns
        -------
        int
            The slot's index (the table's size before the call).

        Raises
        ------
        ValueError
            If the name is taken or empty.
        """
        if not name or name in self._by_name:
            raise ValueError(f"{self.title}: slot name {name!r} is empty or declared twice")
        entry = Entry(name, unit, meaning, len(self._entries))
        self._entries.append(entry)
        self._by_name[name] = entry
        self._bundle_type = None  # the bundle's fields follow the table
        return entry.index

    def add_series(self, pattern: str, labels: Iterable[str], unit: str, meaning: str) -> int:
        """Declare consecutive slots of one kind, one per label; returns the first index.

        Parameters
        ----------
        pattern : str
            Name with one ``{}`` that each label fills (``"bearing_force_{}"``).
        labels : iterable of str
            One label per slot, in order.
        unit, meaning : str
            Shared by the slots.

        Returns
        -------
        int
            Index of the first slot.
        """
        first = self.size
        for label in labels:
            self.add(pattern.format(label), unit, meaning)
        return first

    def add_rows(self, row: Layout, labels: Iterable[str]) -> int:
        """Declare one copy of ``row``'s slots per label (``"<label>_<slot>"``); returns
        the first index. Slot ``k`` of row ``i`` sits at ``first + i * row.size + k``.

        Parameters
        ----------
        row : Layout
            The row's own table (its indices are offsets within a row).
        labels : iterable of str
            One label per row, in order.

        Returns
        -------
        int
            Index of the first slot of the first row.
        """
        first = self.size
        for label in labels:
            for e in row.entries:
                self.add(f"{label}_{e.name}", e.unit, e.meaning)
        return first

    def include(self, other: Layout, prefix: str = "") -> int:
        """Declare ``other``'s slots here, in order, names prefixed; returns the offset.

        Parameters
        ----------
        other : Layout
            A table whose slots form one block of this one.
        prefix : str
            Put before each name (keeps names unique across blocks).

        Returns
        -------
        int
            Index here of ``other``'s slot 0.
        """
        first = self.size
        for e in other.entries:
            self.add(prefix + e.name, e.unit, e.meaning)
        return first

    @property
    def size(self) -> int:
        """Number of slots declared so far."""
        return len(self._entries)

    @property
    def entries(self) -> tuple[Entry, ...]:
        """The slots in index order."""
        return tuple(self._entries)

    def entry(self, name: str) -> Entry:
        """The slot called ``name``.

        Raises
        ------
        KeyError
            If there is none.
        """
        return self._by_name[name]

    def column(self, index: int) -> str:
        """Report column name of slot ``index``: ``"<name> [<unit>]"``."""
        return self._entries[index].column

    def bundle(self, values: Any, offset: int = 0) -> Any:
        """The slots of a laid-out array by name: a named tuple whose fields are the
        slot names, in index order.

        The Python layers read states, parameters and outputs through it instead of
        index constants (``end.suction_mass_in`` for ``y[Q_MSUC_IN]``). The compiled
        code keeps the arrays: a named tuple of the coupled scene's 165 parameters
        slows both a kernel that reads them and a call from Python
        (``benchmarks/parameter_bundles.py`` in the source repository measures it).

        Parameters
        ----------
        values : array_like
            1-D: slot ``k`` at ``values[offset + k]`` (the fields are floats); 2-D
            (samples, slots): slot ``k`` is column ``offset + k`` (the fields are
            columns).
        offset : int
            Index of slot 0 in ``values`` (a block of a larger layout).

        Returns
        -------
        NamedTuple
            Of :attr:`size` fields; the type is made once per table.
        """
        if self._bundle_type is None:
            typename = "".join(w.capitalize() for w in self.title.replace("-", " ").split())
            fields = [e.name for e in self._entries]
            self._bundle_type = namedtuple(typename, fields)  # type: ignore[misc]
        block = values[..., offset : offset + self.size]
        if getattr(block, "ndim", 1) == 1:
            return self._bundle_type._make(block.tolist())
        return self._bundle_type._make(block.T)

    def __len__(self) -> int:
        return len(self._entries)

    def __repr__(self) -> str:
        return f"Layout({self.title!r}, {self.size} slots)"
