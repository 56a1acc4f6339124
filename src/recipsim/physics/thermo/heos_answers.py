"""HEOS's answers to the liquid-line questions a property table cannot answer, kept on disk.

A run with ``properties = "table"`` asks HEOS (:mod:`recipsim.physics.thermo.fluid`) only
what its table has no answer for (:mod:`.table_states`). For R744 that is the liquid
line at the gas-cooler exit, a dense supercritical state (660 kg/m3 at 90 bar and
35 C) in table cells that miss the table's tolerance: one question a run, the same
inputs every run of the case, and answering it imports CoolProp (1.9 s, about two
thirds of a warm R744 run). :class:`HeosAnswers` keeps such answers in
``<cache>/heos_answers/<CoolProp version>/<fluid>.json``: the question and its inputs
(``repr`` of each float) to the answer, exact through JSON, at most
:data:`MOST_ANSWERS` per fluid, written atomically. A file that is unreadable,
malformed or holds anything but finite numbers is ignored and replaced; an unwritable
cache only costs the question's HEOS evaluation.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

from recipsim.cache_dirs import cache_dir
from recipsim.physics.json_cache import read_json, write_record
from recipsim.physics.thermo.coolprop_info import coolprop_version

#: Most answers kept per fluid (a sweep over gas-cooler exits adds one a point).
MOST_ANSWERS = 4096

#: Larger files are not answer files.
_MOST_BYTES = 1_000_000


class HeosAnswers:
    """Remembered HEOS answers of one fluid (see the module docstring).

    Parameters
    ----------
    fluid : str
        CoolProp name of the fluid.
    """

    def __init__(self, fluid: str) -> None:
        safe = "".join(c if c.isalnum() else "_" for c in fluid)
        self.path = cache_dir() / "heos_answers" / coolprop_version() / f"{safe}.json"
        self._answers: dict[str, float] | None = None

    def answer(self, question: str, inputs: tuple[float, ...], ask: Callable[[], float]) -> float:
        """The remembered answer to ``question`` at ``inputs``, else ``ask()``'s, kept.

        Parameters
        ----------
        question : str
            The question's name, e.g. ``"liquid_enthalpy"``.
        inputs : tuple of float
            Its inputs, SI.
        ask : callable
            Evaluates the answer with HEOS.

        Returns
        -------
        float
            The answer, bit for bit what ``ask()`` returned when it was kept.
        """
        key = _key(question, inputs)
        answers = self._load()
        if key in answers:
            return answers[key]
        value = float(ask())
        if math.isfinite(value) and len(answers) < MOST_ANSWERS:
            answers[key] = value
            self._save(answers)
        return value

    def remembered(self, question: str, inputs: tuple[float, ...]) -> bool:
        """Whether an answer to ``question`` at ``inputs`` is kept."""
        return _key(question, inputs) in self._load()

    def _load(self) -> dict[str, float]:
        if self._answers is None:
            self._answers = _read(self.path)
        return self._answers

    def _save(self, answers: dict[str, float]) -> None:
        try:
            write_record(self.path, answers)
        except OSError:
            pass  # an unwritable cache costs the HEOS evaluation next time, nothing else


def _key(question: str, inputs: tuple[float, ...]) -> str:
    """A question at its inputs, the floats exactly (``repr``)."""
    return f"{question}({', '.join(repr(float(x)) for x in inputs)})"


def _read(path: Path) -> dict[str, float]:
    """The kept answers, or none if the file is missing, too large or malformed."""
    data = read_json(path, _MOST_BYTES)
    if not isinstance(data, dict):
        return {}
    if not all(
        isinstance(v, float) and math.isfinite(v) and isinstance(k, str) for k, v in data.items()
    ):
        return {}
    return data
