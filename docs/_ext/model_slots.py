"""Sphinx extension: a model slot's choices, generated from its registry.

``.. model-slot:: recipsim.physics.mechanics.drives.DRIVES`` writes one table of the
slot (a :class:`recipsim.slots.Slot`): each choice's name, what it models and where its
law comes from, with the slot's case key and default above it. A choice added to the
registry appears here without editing the documentation.
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


def slot_rst(path: str) -> list[str]:
    """The table of the registry at the dotted ``path`` (module, then attribute)."""
    module, _, name = path.rpartition(".")
    slot = getattr(importlib.import_module(module), name)
    default = f"``{slot.default}``" if slot.default is not None else "decided by other keys"
    lines = [
        f"``{slot.option}``: {_cell(slot.doc)}. Default: {default}.",
        "",
        ".. list-table::",
        "   :header-rows: 1",
        "   :widths: 18 47 35",
        "",
        "   * - choice",
        "     - what it models",
        "     - source",
    ]
    for choice, summary, source in slot.describe():
        lines += [f"   * - ``{choice}``", f"     - {_cell(summary)}", f"     - {_cell(source)}"]
    return [*lines, ""]


class ModelSlot(SphinxDirective):
    """``.. model-slot:: dotted.path.REGISTRY``: the slot's table."""

    required_arguments = 1
    has_content = False

    def run(self) -> list[nodes.Node]:
        container = nodes.container()
        rst = StringList(slot_rst(self.arguments[0]), source="model-slot")
        self.state.nested_parse(rst, 0, container)
        return container.children


def setup(app: Sphinx) -> dict[str, Any]:
    app.add_directive("model-slot", ModelSlot)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}


__all__ = ["setup", "slot_rst"]
