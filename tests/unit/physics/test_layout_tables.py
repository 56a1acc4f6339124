"""The layout tables: every slot of the compiled arrays declared once, the index constants
handed out by the tables (issue 13, "layouts declared once"): the scenes' arrays, the
property buffer and tables, the journal tables, the pinned mechanism's outputs, the shell
network's nodes, the integrator's counters and the start-up trace.

Each table's indices run 0..n-1 in order, its names are unique, its units parse as
units (or are one of the integer kinds), and the module-level constants are the
table's indices: every slot has exactly one constant (or lies in a declared row or
series), and no slot constant is written by hand.
"""

from __future__ import annotations

import ast
import inspect
import re
from functools import cache
from types import ModuleType
from typing import Any

import pytest

from recipsim.model import scenes
from recipsim.physics.layout_table import Layout
from recipsim.physics.mechanics import journal_table as jt
from recipsim.physics.mechanics import layout as mlay
from recipsim.physics.mechanics import pinned
from recipsim.physics.thermo import cylinder as cyl
from recipsim.physics.thermo import property_slots as ps
from recipsim.physics.thermo import property_table as pt
from recipsim.physics.thermo import shell_network as sn
from recipsim.physics.thermo import shell_nodes
from recipsim.solve import integrator, startup

#: Units of integer slots (and the dimensionless "-"), not physical units.
NON_PHYSICAL_UNITS = {"-", "code", "index", "count"}

TABLES: list[tuple[str, Layout]] = [
    ("cyl.STATES", cyl.STATES),
    ("cyl.IPAR", cyl.IPAR),
    ("cyl.VALVE", cyl.VALVE),
    ("cyl.PAR", cyl.PAR),
    ("cyl.OUTPUTS", cyl.OUTPUTS),
    ("mlay.BEARING", mlay.BEARING),
    ("mlay.PAR", mlay.PAR),
    ("mlay.STATES", mlay.STATES),
    ("mlay.OUTPUTS", mlay.OUTPUTS),
    ("scenes.IPAR", scenes.IPAR),
    ("scenes.PAR", scenes.PAR),
    ("scenes.MECH_QUAD", scenes.MECH_QUAD),
    ("scenes.MECHANISM_STATES", scenes.MECHANISM_STATES),
    ("scenes.COUPLED_STATES", scenes.COUPLED_STATES),
    ("scenes.OUTPUTS", scenes.OUTPUTS),
    ("property_slots.PROPS", ps.PROPS),
    ("property_table.HEADER", pt.HEADER),
    ("property_table.GRID", pt.GRID),
    ("property_table.SAT", pt.SAT),
    ("journal_table.HEADER", jt.HEADER),
    ("journal_table.QUANTITIES", jt.QUANTITIES),
    ("journal_table.NODE", jt.NODE),
    ("pinned.OUTPUTS", pinned.OUTPUTS),
    ("shell_nodes.TEMPERATURES", shell_nodes.TEMPERATURES),
    ("shell_nodes.PRESSURES", shell_nodes.PRESSURES),
    ("integrator.STATS", integrator.STATS),
    ("startup.TRACE", startup.TRACE),
]


@cache
def _units() -> Any:
    import pint

    return pint.UnitRegistry()


def _parses(unit: str) -> bool:
    """Whether a unit in the report's notation (``kg/m3``, ``W/(m2 K)``) is a unit."""
    text = re.sub(r"([A-Za-z])(\d+)", r"\1**\2", unit)
    try:
        _units().parse_units(text)
    except Exception:  # pint raises several types for an unknown unit
        return False
    return True


@pytest.mark.parametrize(("label", "table"), TABLES, ids=[t[0] for t in TABLES])
def test_table_is_ordered_unique_and_described(label: str, table: Layout) -> None:
    entries = table.entries
    assert [e.index for e in entries] == list(range(table.size)), label
    names = [e.name for e in entries]
    assert len(set(names)) == len(names), f"{label}: duplicate names"
    for e in entries:
        assert re.fullmatch(r"[a-z][a-z0-9_]*", e.name), f"{label}: name {e.name!r}"
        assert e.meaning.strip(), f"{label}: {e.name} has no meaning"
        assert e.unit in NON_PHYSICAL_UNITS or _parses(e.unit), f"{label}: {e.name} [{e.unit}]"
        assert table.entry(e.name) is e
        assert table.column(e.index) == f"{e.name} [{e.unit}]"


def test_layout_hands_out_indices_in_order() -> None:
    row = Layout("row")
    assert row.add("a", "m", "first") == 0
    assert row.add("b", "-", "second") == 1
    table = Layout("table")
    assert table.add("x", "K", "scalar") == 0
    assert table.add_rows(row, ("left", "right")) == 1
    assert table.add_series("f_{}", "xyz", "N", "force") == 5
    assert table.include(row, "inner_") == 8
    assert [e.name for e in table.entries] == [
        "x",
        "left_a",
        "left_b",
        "right_a",
        "right_b",
        "f_x",
        "f_y",
        "f_z",
        "inner_a",
        "inner_b",
    ]
    with pytest.raises(ValueError, match="twice"):
        table.add("x", "K", "again")


def _slot_constants(module: ModuleType, prefixes: tuple[str, ...]) -> dict[str, int]:
    return {
        name: value
        for name, value in vars(module).items()
        if name.startswith(prefixes) and type(value) is int
    }


def _covered(table: Layout, constants: dict[str, int], blocks: dict[str, int], label: str) -> None:
    """Each slot of ``table`` is named by exactly one constant, or lies in one block
    (a row or series whose first slot the constant in ``blocks`` names, with its length)."""
    seen: list[int] = []
    for name, value in constants.items():
        seen.extend(range(value, value + blocks.get(name, 1)))
    assert sorted(seen) == list(range(table.size)), f"{label}: slots and constants differ"


def test_cylinder_constants_are_the_tables_indices() -> None:
    assert (cyl.N_STATE, cyl.N_IPAR, cyl.N_PAR, cyl.N_AUX, cyl.VALVE_BLOCK) == (
        cyl.STATES.size,
        cyl.IPAR.size,
        cyl.PAR.size,
        cyl.OUTPUTS.size,
        cyl.VALVE.size,
    )
    # the error-controlled states come first; the quadratures after them
    assert cyl.N_ERR == cyl.Q_MSUC_IN
    _covered(cyl.STATES, _slot_constants(cyl, ("Y_", "Q_")), {}, "states")
    _covered(cyl.IPAR, _slot_constants(cyl, ("I_",)), {}, "ipar")
    _covered(cyl.VALVE, _slot_constants(cyl, ("V_",)), {}, "valve row")
    _covered(cyl.PAR, _slot_constants(cyl, ("C_",)), {"C_VALVE0": 2 * cyl.VALVE_BLOCK}, "par")
    _covered(cyl.OUTPUTS, _slot_constants(cyl, ("A_",)), {}, "outputs")
    for i, valve in enumerate(("suction_valve", "discharge_valve")):
        for e in cyl.VALVE.entries:
            slot = cyl.PAR.entries[cyl.C_VALVE0 + i * cyl.VALVE_BLOCK + e.index]
            assert (slot.name, slot.unit) == (f"{valve}_{e.name}", e.unit)


def test_mechanism_constants_are_the_tables_indices() -> None:
    nb = mlay.N_BEARINGS
    assert (mlay.N_STATE, mlay.N_PAR, mlay.N_AUX, mlay.N_BEARING_PAR) == (
        mlay.STATES.size,
        mlay.PAR.size,
        mlay.OUTPUTS.size,
        mlay.BEARING.size,
    )
    _covered(mlay.BEARING, _slot_constants(mlay, ("BP_",)), {}, "bearing row")
    _covered(
        mlay.PAR, _slot_constants(mlay, ("P_",)), {"P_BEARINGS": nb * mlay.N_BEARING_PAR}, "par"
    )
    _covered(mlay.STATES, _slot_constants(mlay, ("Y_",)), {}, "states")
    series = {
        "A_BEARING_FORCE": 3 * nb,
        "A_BEARING_DISPLACEMENT": 3 * nb,
        "A_BEARING_TORQUE": 2 * nb,
        "A_BEARING_DISSIPATION": nb,
        "A_BEARING_CONTACT": nb,
        "A_BEARING_PEAK_PRESSURE": nb,
        "A_SKIRT_CACHE_ROWS": 2 * mlay.N_FILM_CACHE,
    }
    _covered(mlay.OUTPUTS, _slot_constants(mlay, ("A_",)), series, "outputs")
    cache_blocks = {
        "FC_ARGUMENTS": mlay.N_FILM_ARGUMENTS,
        "FC_RESULTS": mlay.N_FILM_CACHE - mlay.FC_RESULTS,
    }
    _covered(mlay.FILM_CACHE, _slot_constants(mlay, ("FC_",)), cache_blocks, "film cache")
    for i, bearing in enumerate(mlay.BEARING_NAMES):
        row = mlay.P_BEARINGS + i * mlay.N_BEARING_PAR
        assert mlay.PAR.entries[row + mlay.BP_LAW].name == f"{bearing}_law"
        assert mlay.OUTPUTS.entries[mlay.A_BEARING_FORCE + 3 * i + 2].name == (
            f"bearing_force_{bearing}_z"
        )
        assert mlay.OUTPUTS.entries[mlay.A_BEARING_TORQUE + 2 * i].name == (
            f"friction_torque_{bearing}"
        )
    # the rates follow the coordinates in the same order
    for coord in mlay.STATES.entries[: mlay.N_COORD]:
        rate = mlay.STATES.entries[mlay.N_COORD + coord.index]
        assert rate.meaning == f"d {coord.name} / dt"
    assert mlay.Y_CRANK_SPEED == mlay.N_COORD + mlay.Y_CRANK_ANGLE
    assert mlay.STATE_NAMES == tuple(e.column for e in mlay.STATES.entries)


def test_scene_tables_compose_the_blocks() -> None:
    assert [e.name for e in scenes.IPAR.entries[: cyl.N_IPAR]] == [e.name for e in cyl.IPAR.entries]
    assert scenes.N_IPAR == scenes.IPAR.size
    # the cylinder's I_* live in cyl; the scene's follow them
    scene_ipar = _slot_constants(scenes, ("I_",))
    assert sorted(scene_ipar.values()) == list(range(cyl.N_IPAR, scenes.N_IPAR))
    assert scenes.P_MECH == cyl.N_PAR
    assert scenes.P_SCENE == cyl.N_PAR + mlay.N_PAR
    assert scenes.P_TABLES == scenes.PAR.size == scenes.P_SCENE + scenes.N_SCENE_PAR
    assert scenes.PAR.entries[scenes.P_MECH + mlay.P_SPEED].name == "mechanism_speed"
    assert scenes.PAR.entries[scenes.P_THETA_END].unit == "rad"
    assert scenes.A_MECH == cyl.N_AUX
    assert scenes.N_AUX == scenes.OUTPUTS.size == cyl.N_AUX + mlay.N_AUX
    for scene in (scenes.SCENE_CYLINDER, scenes.SCENE_MECHANISM, scenes.SCENE_COUPLED):
        table = scenes.STATES[scene]
        assert scenes.state_size(scene) == table.size
        if scene != scenes.SCENE_CYLINDER:
            m0 = scenes.mechanism_state_offset(scene)
            assert table.entries[m0 + mlay.Y_CRANK_ANGLE].name == "mechanism_crank_angle"
            q = m0 + mlay.N_STATE
            assert table.entries[q + scenes.MQ_GAS].name == "gas_work_on_piston"
    assert scenes.MECH_Y[scenes.SCENE_COUPLED] == cyl.N_STATE


#: Slot-constant prefixes of each module whose constants come from tables.
SLOT_PREFIXES: dict[ModuleType, tuple[str, ...]] = {
    cyl: ("Y_", "Q_", "I_", "C_", "V_", "A_"),
    mlay: ("Y_", "P_", "BP_", "A_"),
    scenes: ("I_", "P_", "MQ_", "A_"),
    ps: ("PROP_",),
    pt: ("H_", "G_", "S_"),
    jt: ("H_", "JQ_"),
    pinned: ("PIN_",),
    shell_nodes: ("GP_", "SM", "SG", "CW", "DC", "DM", "MO", "OIL", "SH"),
    integrator: ("ST_",),
    startup: ("TR_",),
}


@pytest.mark.parametrize("module", list(SLOT_PREFIXES), ids=lambda m: m.__name__)
def test_no_slot_constant_is_written_by_hand(module: ModuleType) -> None:
    """Slot constants come from a table call or from other constants, never a literal."""
    prefixes = SLOT_PREFIXES[module]
    tree = ast.parse(inspect.getsource(module))
    for node in tree.body:
        if not (isinstance(node, ast.Assign) and len(node.targets) == 1):
            continue
        target = node.targets[0]
        if isinstance(target, ast.Name) and target.id.startswith(prefixes):
            assert not isinstance(node.value, ast.Constant), (
                f"{module.__name__}.{target.id} is a literal; declare it in its table"
            )


#: (module, table, constant prefixes, series: first constant -> length, size constant)
BUFFERS = [
    (ps, ps.PROPS, ("PROP_",), {}, "N_PROPS"),
    (pt, pt.HEADER, ("H_",), {}, "N_HEADER"),
    (pt, pt.GRID, ("G_",), {}, "N_GRID"),
    (pt, pt.SAT, ("S_",), {}, "N_SAT"),
    (jt, jt.HEADER, ("H_",), {}, "N_HEADER"),
    (jt, jt.QUANTITIES, ("JQ_",), {}, "N_QUANTITIES"),
    (pinned, pinned.OUTPUTS, ("PIN_",), {"PIN_BEARING_FORCE": 3 * mlay.N_BEARINGS}, "N_PIN_OUT"),
    (shell_nodes, shell_nodes.PRESSURES, ("GP_",), {}, None),
    (integrator, integrator.STATS, ("ST_",), {}, "N_STATS"),
    (startup, startup.TRACE, ("TR_",), {"TR_BEARING_LOAD": mlay.N_BEARINGS}, "N_TRACE"),
]


@pytest.mark.parametrize(
    ("module", "table", "prefixes", "series", "size"),
    BUFFERS,
    ids=[f"{b[0].__name__}:{b[1].title}" for b in BUFFERS],
)
def test_buffer_constants_are_the_tables_indices(
    module: ModuleType,
    table: Layout,
    prefixes: tuple[str, ...],
    series: dict[str, int],
    size: str | None,
) -> None:
    if size is not None:
        assert getattr(module, size) == table.size, f"{module.__name__}.{size}"
    _covered(table, _slot_constants(module, prefixes), series, table.title)


def test_buffer_sizes_are_unchanged() -> None:
    """The sizes the arrays are allocated with (the compiled code and the cached tables
    depend on them), and how the blocks compose."""
    assert (ps.N_PROPS, pt.N_HEADER, pt.N_GRID, pt.N_SAT) == (12, 24, 7, 20)
    assert (jt.N_HEADER, jt.N_QUANTITIES, jt.N_NODE_VALUES) == (8, 3, jt.NODE.size)
    assert jt.N_NODE_VALUES == 4 * jt.N_QUANTITIES
    for k, part in enumerate(("value", "d_du", "d_dtheta0", "d2_du_dtheta0")):
        slot = jt.NODE.entries[k * jt.N_QUANTITIES + jt.JQ_PEAK]
        assert slot.name == f"{part}_peak_pressure_ratio"
    # the pinned row: the bearing forces laid out as the flexible mechanism's outputs
    assert pinned.N_PIN_OUT == 3 * mlay.N_BEARINGS + 4
    for i, bearing in enumerate(mlay.BEARING_NAMES):
        name = pinned.OUTPUTS.entries[pinned.PIN_BEARING_FORCE + 3 * i + 2].name
        assert name == mlay.OUTPUTS.entries[mlay.A_BEARING_FORCE + 3 * i + 2].name
        assert name == f"bearing_force_{bearing}_z"
    assert integrator.N_STATS == 11
    assert startup.N_TRACE == startup.TR_BEARING_LOAD + mlay.N_BEARINGS


def test_shell_network_nodes_are_the_tables() -> None:
    nodes = shell_nodes.TEMPERATURES
    assert sn.N_NODES == nodes.size == 8
    assert sn.NODES == tuple(e.name for e in nodes.entries)
    indices = (sn.SM, sn.SG, sn.CW, sn.DC, sn.DM, sn.MO, sn.OIL, sn.SH)
    assert indices == tuple(range(nodes.size))
    # the gas-node pressures follow GAS_NODES slot by slot
    gas = [nodes.entries[n].name for n in sn.GAS_NODES]
    assert gas == [e.name for e in shell_nodes.PRESSURES.entries]
    assert sn.GAS_NODES[shell_nodes.GP_SM] == sn.SM
    assert sn.GAS_NODES[shell_nodes.GP_DC] == sn.DC
