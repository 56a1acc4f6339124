"""A model choice's declared outputs (:attr:`recipsim.slots.ModelChoice.outputs`) are the
report columns it adds: a run with the choice has them, the same run with another choice of
the slot lacks them, and no other column differs.

Each pair of runs differs in one slot (the lubricated case also in the oil-film data its
laws read, which adds no column); the solves are the cheap ones of the shipped cases: two
revolutions where the crank is flexible (which columns are written does not depend on
convergence), the pinned crank under a tabulated pressure integrates nothing.
"""

from __future__ import annotations

from typing import Any

import pytest

from recipsim.case.load import load_case
from recipsim.physics.friction_models import FRICTION_MODELS
from recipsim.physics.mechanics.bearing_laws.law import FILM_OUTPUTS
from recipsim.physics.mechanics.bearing_laws.registry import BEARING_LAWS
from recipsim.physics.mechanics.crank_trains import CRANK_TRAINS
from recipsim.physics.mechanics.layout import BEARING_NAMES
from recipsim.physics.thermo.pressure_sources import PRESSURE_SOURCES
from recipsim.pipeline import simulate_case
from recipsim.slots import ModelChoice, Output

_SHORT = {"solver.min_revolutions": 2, "solver.max_revolutions": 2}


def _columns(name: str, overrides: dict[str, Any]) -> dict[str, set[str]]:
    """The cycle and summary columns of the shipped case ``name`` with ``overrides``."""
    run = simulate_case(load_case(name).with_(overrides))
    return {"cycle": set(run.cycle.columns), "summary": set(run.row)}


def _added(with_: dict[str, set[str]], without: dict[str, set[str]]) -> dict[str, set[str]]:
    """The columns ``with_`` has and ``without`` lacks, by table; ``without`` has no
    column that ``with_`` lacks."""
    for table in ("cycle", "summary"):
        assert without[table] <= with_[table], (table, without[table] - with_[table])
    return {table: with_[table] - without[table] for table in ("cycle", "summary")}


def _declared(choice: ModelChoice, table: str, bearings: tuple[str, ...] = ()) -> set[str]:
    """The columns ``choice`` declares for ``table``, a per-bearing one for each of
    ``bearings``."""
    return {
        column
        for output in choice.outputs
        if output.table == table
        for column in (
            [output.column_of(b) for b in bearings] if output.per_bearing else [output.column]
        )
    }


@pytest.fixture(scope="module")
def ideal() -> dict[str, set[str]]:
    """The reference compressor as an ideal machine: pinned crank, cylinder, no friction."""
    return _columns("reference_r134a_lbp_ideal", {})


def test_the_cylinder_pressure_source_adds_the_gas_columns(ideal) -> None:
    # the same machine under its tabulated pressure curve (nothing integrated)
    tabulated = _columns(
        "paper_tabulated", {"options.mechanics": "pinned", "options.drive": "constant_speed"}
    )
    added = _added(ideal, tabulated)
    cylinder = PRESSURE_SOURCES["cylinder"]
    assert added["cycle"] == _declared(cylinder, "cycle")
    assert added["summary"] == _declared(cylinder, "summary") == set()
    assert not PRESSURE_SOURCES["tabulated"].outputs  # it adds nothing to the cylinder's


def test_the_flexible_crank_adds_its_mechanical_balance(ideal) -> None:
    flexible = _columns("reference_r134a_lbp_ideal", {"options.mechanics": "flexible", **_SHORT})
    added = _added(flexible, ideal)
    assert added == {
        "cycle": _declared(CRANK_TRAINS["flexible"], "cycle"),
        "summary": _declared(CRANK_TRAINS["flexible"], "summary"),
    }
    assert added["summary"]  # the test sees the declaration


def test_film_bearings_add_their_laws_columns() -> None:
    """Journals on the finite law and the piston on its skirt film against the same
    coupled machine on linear bearings."""
    case = load_case("reference_r134a_lbp_lubricated")
    laws = {name: BEARING_LAWS[case.mechanism.bearing(name).law] for name in BEARING_NAMES}
    films = {name: law for name, law in laws.items() if law.film}
    assert 0 < len(films) < len(BEARING_NAMES)  # films, and a linear bearing among them
    assert "skirt_film" in {law.name for law in films.values()}
    lubricated = _columns("reference_r134a_lbp_lubricated", _SHORT)
    linear = _columns("reference_r134a_lbp_coupled", _SHORT)
    added = _added(lubricated, linear)
    for table in ("cycle", "summary"):
        expected = set().union(*(_declared(law, table, (name,)) for name, law in films.items()))
        assert added[table] == expected, table


def test_mean_friction_adds_its_terms(ideal) -> None:
    """The per-journal term is written for the journals with film data, so each added
    column is one of a declared output's, and each declared output is written."""
    mean = _columns("reference_r134a_lbp_ideal", {"options.friction": "mean"})
    added = _added(mean, ideal)
    assert added["cycle"] == set()
    declared = [o for o in FRICTION_MODELS["mean"].outputs if o.table == "summary"]
    per_output = {
        output: added["summary"] & _declared(_only(output), "summary", BEARING_NAMES)
        for output in declared
    }
    assert all(per_output.values()), [o.column for o, found in per_output.items() if not found]
    assert set().union(*per_output.values()) == added["summary"]
    assert not FRICTION_MODELS["off"].outputs and not FRICTION_MODELS["films"].outputs


def _only(output: Output) -> ModelChoice:
    """A choice declaring ``output`` alone."""
    return ModelChoice("only", 0, "one output", outputs=(output,))


def test_every_film_law_carries_the_film_outputs() -> None:
    """The results write a film bearing's columns from its law's declaration, and the
    film friction sums the absorbed power they hold: every film law declares them."""
    for law in BEARING_LAWS:
        carried = set(FILM_OUTPUTS) <= set(law.outputs)
        assert carried == law.film, law.name
