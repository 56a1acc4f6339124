"""Sphinx extension: a model slot's choices, generated from its registry.

``.. model-slot:: recipsim.physics.thermo.valve_models:VALVE_MODELS`` (or
``...valve_models.VALVE_MODELS``) writes the slot's
case key, what it models, one row per choice (name, what it models, source) and the
report columns each choice adds (its ``outputs``), read from the
:class:`recipsim.slots.Slot` object named: a choice added to the registry appears
without editing the documentation.
"""

from __future__ import annotations

import importlib
from typing import Any

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.application import Sphinx
from sphinx.util.docutils import SphinxDirective


def _cell(text: str) -> str:
    return " ".join(str(text).split()).replace("|", "\\|") or " "


def slot_lines(slot: Any) -> list[str]:
    """One :class:`recipsim.slots.Slot` as reStructuredText lines."""
    default = f" (default ``{slot.default}``)" if slot.default else ""
    lines = [f"``{slot.option}``: {_cell(slot.doc)}{default}.", ""]
    lines += [".. list-table::", "   :header-rows: 1", "   :widths: 15 55 30", ""]
    rows = [("choice", "what it models", "source"), *slot.describe()]
    for choice, summary, source in rows:
        first = choice if choice == "choice" else f"``{choice}``"
        lines += [f"   * - {first}", f"     - {_cell(summary)}", f"     - {_cell(source)}"]
    lines.append("")
    adding = [choice for choice in slot if choice.outputs]
    if adding:
        lines += ["Report columns a choice adds (absent without it):", ""]
        for choice in adding:
            for table in ("cycle", "summary"):
                columns = [f"``{o.column}``" for o in choice.outputs if o.table == table]
                if columns:
                    lines.append(f"- ``{choice.name}``, ``{table}.csv``: {', '.join(columns)}")
        lines.append("")
    return lines


def slot_rst(target: str) -> list[str]:
    """The slot ``module:NAME`` (or ``module.NAME``) as reStructuredText lines."""
    module, _, name = target.rpartition(":") if ":" in target else target.rpartition(".")
    return slot_lines(getattr(importlib.import_module(module), name))


class ModelSlot(SphinxDirective):
    """``.. model-slot:: module:NAME``: the choices of one slot."""

    required_arguments = 1
    has_content = False

    def run(self) -> list[nodes.Node]:
        container = nodes.container()
        lines = slot_rst(self.arguments[0])
        self.state.nested_parse(StringList(lines, source="model-slot"), 0, container)
        return container.children


def setup(app: Sphinx) -> dict[str, Any]:
    app.add_directive("model-slot", ModelSlot)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}


__all__ = ["setup", "slot_lines", "slot_rst"]
