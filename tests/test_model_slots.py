"""Model slots keep their promise (:mod:`recipsim.slots`): every ``options.*`` choice of
the case schema is a registered choice, and a choice's name is spelt out as a string
literal in at most three modules of the package (its own, and at most two that must
name it: a shipped default, a study's fixed setting), so that adding a choice touches its
module and its registry, not a list of places that repeat its name. The report columns a
choice declares (``outputs``) carry an SI unit and a meaning, and the column docs document
each of them."""

from __future__ import annotations

import ast
import importlib
import pkgutil
import re
from collections import defaultdict
from functools import cache
from typing import Any

import pytest

import recipsim
from helpers import ROOT
from recipsim.case.case_schema import OPTION_SPEC
from recipsim.physics.mechanics.layout import BEARING_NAMES
from recipsim.results.column_docs import CYCLE_DOCS, documented
from recipsim.results.summary_docs import SUMMARY_DOCS
from recipsim.slots import ModelChoice, Slot

PACKAGE = ROOT / "src" / "recipsim"
MAX_MODULES_PER_NAME = 3

#: Choice names that are also ordinary words or another library's vocabulary (Python's
#: ``"case"``, matplotlib's ``"linear"`` scale, pandas' ``"mean"``, ``"none"``, ``"off"``,
#: ``"table"``, ``"cylinder"``): counted only where they are used as the option, i.e.
#: compared with, or given as, a key named after their slot.
GENERIC_NAMES = frozenset({"case", "none", "off", "mean", "table", "linear", "cylinder"})


def _registered_slots() -> list[Slot[ModelChoice]]:
    """Every :class:`Slot` defined at module level anywhere in the package."""
    slots: dict[int, Slot[ModelChoice]] = {}
    for info in pkgutil.walk_packages(recipsim.__path__, "recipsim."):
        if ".data" in info.name or info.name.endswith("__main__"):
            continue
        module = importlib.import_module(info.name)
        for value in vars(module).values():
            if isinstance(value, Slot):
                slots[id(value)] = value
    return list(slots.values())


def _slot_keys(option: str) -> set[str]:
    """The names a key of ``option`` goes by in code: ``options.valves`` -> ``valves``;
    a bearing's law is its ``law``."""
    key = option.rsplit(".", 1)[-1]
    return {key, "law"} if key == "bearing_law" else {key}


def _names_by_slot() -> dict[str, set[str]]:
    """Each choice name -> the code names of the slots it belongs to."""
    names: dict[str, set[str]] = defaultdict(set)
    for key, choice in OPTION_SPEC.items():
        for name in choice.choices:
            names[name] |= _slot_keys(f"options.{key}")
    for slot in _registered_slots():
        for name in slot.names:
            names[name] |= _slot_keys(slot.option)
    return names


def _used_as_option(node: ast.Constant, parents: dict[ast.AST, ast.AST], keys: set[str]) -> bool:
    """Whether the string ``node`` stands for a choice of one of the slots ``keys``: it
    is compared with (or found in a tuple compared with) an attribute or name of the
    slot, given as the keyword of the slot, or the value of the slot's key in a dict."""
    parent = parents.get(node)
    if isinstance(parent, ast.Tuple | ast.List | ast.Set):
        parent = parents.get(parent)
    if isinstance(parent, ast.Compare):
        for side in (parent.left, *parent.comparators):
            if isinstance(side, ast.Attribute) and side.attr in keys:
                return True
            if isinstance(side, ast.Name) and side.id in keys:
                return True
        return False
    if isinstance(parent, ast.keyword):
        return parent.arg in keys
    if isinstance(parent, ast.Dict):
        for key, value in zip(parent.keys, parent.values, strict=True):
            if value is node and isinstance(key, ast.Constant) and key.value in keys:
                return True
    return False


def _modules_naming(names: dict[str, set[str]]) -> dict[str, set[str]]:
    """Each choice name -> the modules (outside ``data/``) holding it as a literal."""
    found: dict[str, set[str]] = defaultdict(set)
    for path in sorted(PACKAGE.rglob("*.py")):
        relative = path.relative_to(PACKAGE)
        if relative.parts[0] == "data":
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        parents = {child: node for node in ast.walk(tree) for child in ast.iter_child_nodes(node)}
        for node in ast.walk(tree):
            if not (isinstance(node, ast.Constant) and isinstance(node.value, str)):
                continue
            if node.value not in names:
                continue
            if node.value in GENERIC_NAMES and not _used_as_option(
                node, parents, names[node.value]
            ):
                continue
            found[node.value].add(str(relative))
    return found


def test_every_option_is_a_registered_slot():
    slots = {slot.option: slot for slot in _registered_slots()}
    missing = sorted(f"options.{key}" for key in OPTION_SPEC if f"options.{key}" not in slots)
    assert not missing, f"options without a registry (recipsim.slots.Slot): {missing}"
    for key, choice in OPTION_SPEC.items():
        assert set(choice.choices) <= set(slots[f"options.{key}"].names), key


def test_a_choice_name_is_spelt_out_in_at_most_three_modules():
    names = _names_by_slot()
    found = _modules_naming(names)
    over = {
        name: sorted(modules)
        for name, modules in found.items()
        if len(modules) > MAX_MODULES_PER_NAME
    }
    assert not over, (
        "choice names spelt out as string literals in more than "
        f"{MAX_MODULES_PER_NAME} modules (ask the slot's registry or the entry instead): {over}"
    )


def test_the_literal_count_sees_option_uses_of_generic_words():
    source = (
        "def f(opts, scale):\n"
        "    a = opts.bearing_law == 'linear'\n"
        "    b = scale == 'linear'\n"
        "    c = dict(law='linear')\n"
        "    d = {'law': 'linear', 'axis': 'linear'}\n"
        "    e = opts.law in ('linear', 'x')\n"
    )
    tree = ast.parse(source)
    parents = {child: node for node in ast.walk(tree) for child in ast.iter_child_nodes(node)}
    keys = _slot_keys("options.bearing_law")
    verdicts = [
        _used_as_option(node, parents, keys)
        for node in ast.walk(tree)
        if isinstance(node, ast.Constant) and node.value == "linear"
    ]
    assert sorted(verdicts) == [False, False, True, True, True, True]


@pytest.mark.parametrize("slot", _registered_slots(), ids=lambda s: s.option)
def test_each_choice_says_what_it_models(slot):
    for choice in slot:
        assert choice.summary.strip(), f"{slot.option}: {choice.name} has no summary"
        assert slot.by_code(choice.code) is choice


@cache
def _units() -> Any:
    import pint

    return pint.UnitRegistry()


def _si_unit(unit: str) -> bool:
    """Whether ``unit``, in the report's notation (``kg/m3``, ``W/(m2 K)``, ``N m``,
    ``-`` for a ratio), is a coherent SI unit: one of its base units' products, factor 1."""
    if unit == "-":
        return True
    try:
        quantity = _units().Quantity(1.0, re.sub(r"([A-Za-z])(\d+)", r"\1**\2", unit))
    except Exception:  # pint raises several types for an unknown unit
        return False
    return bool(quantity.to_base_units().magnitude == 1.0)


def test_the_unit_check_tells_si_from_other_units():
    assert all(map(_si_unit, ("-", "m", "N m", "Pa*s", "kg/m3", "W/(m2 K)", "K", "rad/s")))
    assert not any(map(_si_unit, ("rpm", "deg", "mm", "kJ", "degC", "bar", "furlong")))


@pytest.mark.parametrize("slot", _registered_slots(), ids=lambda s: s.option)
def test_declared_outputs_have_si_units_and_meanings(slot):
    for choice in slot:
        for output in choice.outputs:
            label = f"{slot.option} = {choice.name}: {output.column}"
            assert re.fullmatch(r"[a-z][a-z0-9_]*(<name>[a-z0-9_]*)?", output.name), label
            assert _si_unit(output.unit), f"{label}: not an SI unit"
            assert output.meaning.strip(), f"{label}: no meaning"


def test_every_declared_output_is_documented():
    """The column docs read every registry whose choices add columns."""
    docs = {"cycle": documented(CYCLE_DOCS), "summary": documented(SUMMARY_DOCS)}
    missing = [
        f"{slot.option} = {choice.name}: {column} ({output.table})"
        for slot in _registered_slots()
        for choice in slot
        for output in choice.outputs
        for column in {output.column_of(bearing) for bearing in BEARING_NAMES}
        if column not in docs[output.table]
    ]
    assert not missing
