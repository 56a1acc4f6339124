"""The report's columns that are layout outputs carry the name and unit their layout
entry declares (issue 13, "the report's column registry reads the same table").

``results/cycle.py`` builds ``CYCLE_COLUMNS`` from the output slots it reads; this test
holds each column to its slot's entry. The mechanism's columns
(``results/bearings.py``) are built from ``layout.OUTPUTS`` and checked to read their
own slots.
"""

from __future__ import annotations

import numpy as np

from recipsim.physics.mechanics import layout as mlay
from recipsim.physics.mechanics.bearing_laws import short_journal, skirt_film
from recipsim.physics.thermo import cylinder as cyl
from recipsim.results.bearings import flexible_columns
from recipsim.results.tables import CYCLE_COLUMNS, GAS_COLUMNS


def test_cycle_columns_have_their_output_entrys_name_and_unit() -> None:
    for column, index in CYCLE_COLUMNS:
        entry = cyl.OUTPUTS.entries[index]
        unit = column[column.index("[") + 1 : -1]
        assert unit == entry.unit, f"{column}: the layout declares [{entry.unit}]"
        assert column == entry.column
    names = [c for c, _ in CYCLE_COLUMNS]
    assert len(set(names)) == len(names)
    assert GAS_COLUMNS <= set(names)


def test_mechanism_columns_read_their_own_output_slots() -> None:
    n = 5
    aux = np.arange(n * mlay.N_AUX, dtype=float).reshape(n, mlay.N_AUX)
    par = np.zeros(mlay.N_PAR)
    for i, name in enumerate(mlay.BEARING_NAMES):  # every bearing on a film: all film columns
        row = mlay.P_BEARINGS + i * mlay.N_BEARING_PAR
        piston = name in mlay.PISTON_STATION_NAMES
        par[row + mlay.BP_LAW] = skirt_film.CODE if piston else short_journal.CODE
        par[row + mlay.BP_CLEARANCE] = 1e-5
    cols = flexible_columns(aux, par)
    by_column = {e.column: e for e in mlay.OUTPUTS.entries}
    read = [c for c in cols if c in by_column]
    # forces, x/y displacements, 4 scalars, 4 per-bearing series, the piston film's friction
    assert len(read) == 3 * 6 + 2 * 6 + 4 + 4 * 6 + 2
    for column in read:
        np.testing.assert_array_equal(cols[column], aux[:, by_column[column].index])


def test_drifting_states_are_named_by_the_scene_state_tables() -> None:
    from types import SimpleNamespace

    from recipsim.model import scenes
    from recipsim.results.outcome import _state_names

    cylinder = SimpleNamespace(scene=scenes.SCENE_CYLINDER, n_err=cyl.N_ERR)
    assert _state_names(cylinder)[cyl.Y_T] == "gas_temperature"
    coupled = SimpleNamespace(
        scene=scenes.SCENE_COUPLED, n_err=cyl.N_STATE + mlay.N_STATE, mechanism_offset=cyl.N_STATE
    )
    names = _state_names(coupled)
    assert names[cyl.Y_VD] == "discharge_valve_velocity"
    assert names[cyl.N_STATE + mlay.Y_CRANK_SPEED] == "mechanism_crank_speed"
