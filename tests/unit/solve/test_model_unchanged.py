"""The solver never writes into the model it is given (issue 13).

A built :class:`~recipsim.model.build.Model` has read-only arrays; every solve entry
point moves a working copy (:meth:`~recipsim.model.build.Model.for_solve`). For each
scene and solver: the model's arrays, plenum states and thermal network state are
bit-identical before and after a solve, and solving it again gives a bit-identical
summary. No compiled function ever received a read-only array (it would be compiled
again for that type).
"""

from __future__ import annotations

import dataclasses
import math
import sys
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from numba.core import types
from numba.core.dispatcher import Dispatcher

from helpers import CASES
from recipsim.case.load import load_case
from recipsim.model.build import Model, WorkingModel, build_model
from recipsim.model.plenum import PlenumState
from recipsim.results.tables import summary_row
from recipsim.solve.drive import build_model_for
from recipsim.solve.motor_speed import solve_at_motor_speed
from recipsim.solve.periodic import solve_periodic
from recipsim.solve.revolution import integrate_revolution
from recipsim.solve.startup import solve_from_rest

#: Caches of pure functions, shared by the model and its working copies.
_CACHES = {"_enthalpy_floor", "_dew"}


def _frozen(value: Any) -> Any:
    """A comparable snapshot of a model field (objects without state by identity)."""
    if isinstance(value, np.ndarray):
        return (value.dtype.str, value.shape, value.tobytes())
    if isinstance(value, PlenumState):
        fields = ("pressure", "temperature", "density", "enthalpy", "kappa", "k0", "viscosity")
        return tuple(getattr(value, name) for name in fields)
    if isinstance(value, float | int | bool | str) or value is None:
        return value
    return id(value)


def snapshot(model: Model) -> dict[str, Any]:
    """Every field of ``model``, and the running state of its thermal network."""
    snap = {
        f.name: _frozen(getattr(model, f.name))
        for f in dataclasses.fields(model)
        if f.name not in _CACHES
    }
    if model.thermal is not None:
        state = vars(model.thermal)
        snap["thermal"] = {k: _frozen(v) for k, v in state.items() if k not in _CACHES}
        snap["loss_sources"] = {k: _frozen(v) for k, v in vars(state["loss_sources"]).items()}
    return snap


def _row(solution) -> dict[str, Any]:
    row, _ = summary_row(solution)
    return {k: v for k, v in row.items() if not k.startswith("wall_time")}


def _same(a: dict[str, Any], b: dict[str, Any]) -> bool:
    def key(v: Any) -> Any:
        return "nan" if isinstance(v, float) and math.isnan(v) else v

    return a.keys() == b.keys() and all(key(a[k]) == key(b[k]) for k in a)


def _readonly_signatures() -> list[str]:
    """Compiled specialisations of recipsim's functions that take a read-only array."""
    found = []
    for name, module in list(sys.modules.items()):
        if not name.startswith("recipsim"):
            continue
        for attr, value in list(vars(module).items()):
            if isinstance(value, Dispatcher):
                for sig in value.signatures:
                    if any(isinstance(t, types.Array) and not t.mutable for t in sig):
                        found.append(f"{name}.{attr}{sig}")
    return found


def _signature_count() -> int:
    return sum(
        len(v.signatures)
        for name, m in list(sys.modules.items())
        if name.startswith("recipsim")
        for v in list(vars(m).values())
        if isinstance(v, Dispatcher)
    )


def _periodic(model: Model) -> dict[str, Any]:
    return _row(solve_periodic(model))


def _from_rest(model: Model) -> dict[str, Any]:
    run = solve_from_rest(model)
    row = _row(run.solution)
    row["windows"], row["transient_nfev"] = run.transient.windows, run.transient.nfev
    return row


SCENES: dict[str, tuple[Any, dict[str, Any], Callable[[Model], dict[str, Any]]]] = {
    "cylinder_rigid": ("reference_r134a_lbp", {}, _periodic),
    "coupled_flexible": ("reference_r134a_lbp_coupled", {}, _periodic),
    "lubricated": ("reference_r134a_lbp_lubricated", {}, _periodic),
    "network_thermal": (
        "reference_r134a_lbp",
        {
            "options.thermal": "network",
            "options.motor": "equivalent_circuit",
            "options.friction": "mean",
        },
        _periodic,
    ),
    "shooting": ("reference_r134a_lbp", {"solver.periodic": "shooting"}, _periodic),
    "startup": (
        CASES / "hard" / "startup_induction_motor.toml",
        {"solver.rtol": 1e-5, "solver.samples_per_revolution": 360},
        _from_rest,
    ),
}


@pytest.mark.parametrize("scene", SCENES)
def test_solving_leaves_the_model_as_built(scene: str) -> None:
    name, overrides, solve = SCENES[scene]
    model = build_model_for(load_case(name, overrides))
    before = snapshot(model)
    readonly = set(_readonly_signatures())  # other tests may have made some (pandas 3's
    # to_numpy gives read-only views): only the solves' own count here
    first = solve(model)
    assert snapshot(model) == before
    count = _signature_count()
    assert _same(solve(model), first), "solving the same model twice"
    assert snapshot(model) == before
    assert _signature_count() == count, "the second solve compiled something"
    assert set(_readonly_signatures()) - readonly == set()


def test_motor_slip_speed_is_the_same_twice() -> None:
    """``options.speed = "motor_slip"``: the nested solves, each warm-started from the
    previous speed's working copy, give the same speeds and summary twice."""
    case = load_case("tles5.7kk3_r600a")
    readonly = set(_readonly_signatures())
    a, b = solve_at_motor_speed(case), solve_at_motor_speed(case)
    assert a.speeds == b.speeds and a.revolutions == b.revolutions
    assert _same(_row(a.solution), _row(b.solution))
    assert set(_readonly_signatures()) - readonly == set()


def test_a_built_model_is_read_only_and_its_working_copy_is_not() -> None:
    model = build_model(load_case("reference_r134a_lbp"))
    for name in ("par", "ipar", "y0", "mode0", "scale", "quadratures"):
        assert not getattr(model, name).flags.writeable, name
    with pytest.raises(ValueError, match="read-only"):
        model.par[0] = 1.0
    before = snapshot(model)
    work = model.for_solve()
    assert isinstance(work, WorkingModel) and not isinstance(model, WorkingModel)
    for name in ("par", "ipar", "y0", "mode0", "scale", "quadratures"):
        assert getattr(work, name).flags.writeable, name
        assert not np.shares_memory(getattr(work, name), getattr(model, name)), name
    work.set_discharge_enthalpy(work.discharge.enthalpy + 1e3)
    work.set_revolution_end(1.0)
    assert work.discharge is not model.discharge
    assert snapshot(model) == before


def test_integrating_a_built_model_is_refused() -> None:
    """The compiled integrator only ever receives a working copy's writable arrays."""
    model = build_model(load_case("reference_r134a_lbp"))
    with pytest.raises(TypeError, match="for_solve"):
        integrate_revolution(model, model.y0.copy(), model.mode0.copy(), 1e-6, 36)
