"""Property buffers made by ``PropertyTable.property_buffer``: the same content as the
concatenation they replace, their memory reused only once nothing else holds it (the
table's tail is not copied again: a solve writes only the outputs, checked here on a
real solve), and freed by a dropped ``HeosProperties`` without waiting for the cyclic
collector."""

from __future__ import annotations

import gc

import numpy as np

from recipsim.physics.thermo.properties import N_PROPS, PROP_PRESSURE, HeosProperties
from recipsim.physics.thermo.property_table import H_TRANSPORT, PropertyTable


def _table() -> PropertyTable:
    return PropertyTable("R134a", np.linspace(1.0, 2.0, 64))


def _concatenated(table: PropertyTable, transport: bool) -> np.ndarray:
    return np.concatenate([np.zeros(N_PROPS), table.buffer_tail(transport)])


def test_buffer_is_the_concatenation_bit_for_bit() -> None:
    table = _table()
    for transport in (False, True):
        buf = table.property_buffer(transport)
        assert buf.tobytes() == _concatenated(table, transport).tobytes()
        assert buf[N_PROPS + H_TRANSPORT] == (1.0 if transport else 0.0)


def test_a_dropped_buffer_is_reused_with_its_outputs_cleared() -> None:
    """The old owner's outputs are gone from the reused buffer, which equals a new one."""
    table = _table()
    first = table.property_buffer(True)
    address = first.ctypes.data
    first[:N_PROPS] = -7.0  # outputs written by a solve
    del first
    again = table.property_buffer(False)
    assert again.ctypes.data == address  # the same memory
    assert again.tobytes() == _concatenated(table, False).tobytes()


def test_a_solve_writes_only_the_outputs_of_its_buffer() -> None:
    """The contract that lets a reused buffer keep its tail: after a periodic solve of
    the reference case (table interpolation, HEOS fallbacks and the Python side's state
    calls all through the buffer), its tail is still the table, bit for bit."""
    from recipsim.case.load import load_case
    from recipsim.model.build import build_model
    from recipsim.solve.periodic import solve_periodic

    model = build_model(load_case("reference_r134a_lbp"))
    table = model.props.table
    assert table is not None
    solution = solve_periodic(model)
    assert solution.converged
    tail = model.props.buffer[N_PROPS:]
    transport = bool(model.props.buffer[N_PROPS + H_TRANSPORT])
    assert tail.tobytes() == table.buffer_tail(transport).tobytes()


def test_a_held_buffer_is_never_handed_out_twice() -> None:
    table = _table()
    held = [table.property_buffer(True) for _ in range(6)]  # more than the table keeps
    addresses = {b.ctypes.data for b in held}
    assert len(addresses) == 6
    view = held[0][:N_PROPS]  # a view keeps its base alive
    del held
    fresh = [table.property_buffer(True) for _ in range(4)]
    assert view.base is not None and view.base.ctypes.data not in {b.ctypes.data for b in fresh}


def test_dropped_properties_free_their_buffer_without_the_collector() -> None:
    """HeosProperties' ctypes callback lives in a reference cycle: it holds the buffer
    weakly, so the buffer is free as soon as the object is dropped. The callback still
    fills the buffer while the object lives: HEOS pressure at (300 K, 5 kg/m3)."""
    import CoolProp.CoolProp as CP

    table = _table()
    gc.disable()
    try:
        props = HeosProperties("R134a", False, 200.0, 450.0, buffer=table.property_buffer(False))
        assert props(300.0, 5.0) == 0
        expected = CP.PropsSI("P", "T", 300.0, "Dmass", 5.0, "R134a")
        assert props.buffer[PROP_PRESSURE] == expected
        address = props.buffer.ctypes.data
        del props
        assert table.property_buffer(False).ctypes.data == address
    finally:
        gc.enable()
