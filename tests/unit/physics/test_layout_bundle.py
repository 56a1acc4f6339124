"""``Layout.bundle``: a laid-out array read by slot name, the same values as the index
constants give, for 1-D arrays, 2-D sample arrays and blocks of a larger layout."""

from __future__ import annotations

import numpy as np

from recipsim.model import scenes
from recipsim.physics.layout_table import Layout
from recipsim.physics.thermo import cylinder as cyl


def test_fields_are_the_slot_names_in_index_order() -> None:
    end = cyl.STATES.bundle(np.arange(float(cyl.N_STATE)))
    assert end._fields == tuple(e.name for e in cyl.STATES.entries)
    assert end.suction_mass_in == cyl.Q_MSUC_IN
    assert end.discharge_enthalpy_out == cyl.Q_HDIS_OUT
    assert end.shaft_work == cyl.Q_SHAFT
    assert isinstance(end.gas_temperature, float)


def test_two_dimensional_values_give_columns() -> None:
    samples = np.random.default_rng(3).normal(size=(7, cyl.N_STATE))
    named = cyl.STATES.bundle(samples)
    for entry in cyl.STATES.entries:
        assert np.array_equal(getattr(named, entry.name), samples[:, entry.index])


def test_a_block_of_a_larger_layout_by_offset() -> None:
    """The mechanism quadratures sit after the mechanism states in the coupled scene."""
    y = np.arange(float(scenes.state_size(scenes.SCENE_COUPLED)))
    offset = scenes.mechanism_state_offset(scenes.SCENE_COUPLED) + scenes.lay.N_STATE
    quad = scenes.MECH_QUAD.bundle(y, offset)
    assert quad.drive_work == offset + scenes.MQ_DRIVE
    whole = scenes.named_state(scenes.SCENE_COUPLED, y)
    assert whole.drive_work == quad.drive_work
    assert whole.gas_work_on_piston == offset + scenes.MQ_GAS


def test_the_type_follows_a_table_that_grows() -> None:
    table = Layout("growing table")
    table.add("a", "m", "first")
    first = table.bundle(np.array([1.0, 2.0]))
    assert first._fields == ("a",)
    table.add("b", "s", "second")
    second = table.bundle(np.array([1.0, 2.0]))
    assert second._fields == ("a", "b") and second.b == 2.0
    assert type(second).__name__ == "GrowingTable"
    assert table.bundle(np.array([3.0, 4.0])).__class__ is type(second)  # made once
