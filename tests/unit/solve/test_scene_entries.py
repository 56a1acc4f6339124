"""Each scene compiles on its own: the scene reaches the integrator as a compile-time
constant or as its own compiled functions (the cylinder scene, through pointers), a
pinned case compiles no flexible crank train nor, where no stretch turns stiff, the
Rosenbrock-W step, and a second process loads the compiled integrator from numba's cache
instead of compiling it again."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest
from numba import types
from numba.core.errors import TypingError

from recipsim.model import scenes
from recipsim.solve import scene_entries, w_gate

_CHILD = r"""
import json
from recipsim.case.load import load_case
from recipsim.pipeline import simulate_case
from recipsim.solve import scene_entries
from recipsim.model import scenes
case = load_case("reference_r134a_lbp").with_(
    {"solver.min_revolutions": 1, "solver.max_revolutions": 1})
simulate_case(case)
entry = scene_entries.integrate_scene
print(json.dumps({
    "signatures_as_ahead": entry.signatures == [scene_entries.SCENE_ENTRY_SIGNATURE],
    "hits": sum(entry.stats.cache_hits.values()),
    "misses": sum(entry.stats.cache_misses.values()),
    "compiled": {f.__name__: len(f.signatures) for f in (
        scene_entries.integrate_mechanism, scene_entries.integrate_coupled,
        scenes.mechanism_rhs, scenes.coupled_rhs)},
}))
"""


def test_the_scene_function_is_chosen_at_compile_time() -> None:
    """A literal scene code resolves to that scene's function; a runtime one is refused."""
    for code, rhs in enumerate((scenes.cylinder_rhs, scenes.mechanism_rhs, scenes.coupled_rhs)):
        assert scenes._scene_function("rhs", types.IntegerLiteral(code)) is rhs
    with pytest.raises(TypingError, match="compile-time constant"):
        scenes._scene_function("rhs", types.int64)
    coupled = scenes.SCENE_COUPLED
    assert scene_entries.SCENE_INTEGRATORS[coupled] is scene_entries.integrate_coupled
    assert scene_entries.W_SCENE_INTEGRATORS[coupled] is scene_entries.integrate_coupled_w


def test_the_w_step_flag_is_chosen_at_compile_time() -> None:
    """The W-step flag of an entry is a literal too: the explicit entry's compiles to a
    constant, a runtime flag is refused."""
    assert w_gate._takes_w_steps(types.IntegerLiteral(w_gate.WITH_W_STEP))
    assert not w_gate._takes_w_steps(types.IntegerLiteral(w_gate.EXPLICIT))
    with pytest.raises(TypingError, match="compile-time constant"):
        w_gate._takes_w_steps(types.int64)


@pytest.mark.slow
def test_a_pinned_case_compiles_its_scene_only_and_a_second_process_loads_it(tmp_path) -> None:
    """Fresh numba cache: the first process compiles the cylinder scene (no flexible crank
    train, no coupled or tabulated-pressure integrator), the second loads it."""
    import json

    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "numba"))
    env.pop("NUMBA_DISABLE_JIT", None)
    runs = []
    for _ in range(2):
        out = subprocess.run(
            [sys.executable, "-c", _CHILD], env=env, capture_output=True, text=True, check=True
        )
        runs.append(json.loads(out.stdout.splitlines()[-1]))
    first, second = runs
    # a run calls the entry with the types the first run's child compiles ahead
    assert first["signatures_as_ahead"] and second["signatures_as_ahead"]
    assert first["misses"] == 1 and first["hits"] == 0
    assert set(first["compiled"].values()) == {0}
    assert second["hits"] == 1 and second["misses"] == 0
    names = {p.name.split("-")[0] for p in (tmp_path / "numba").rglob("*.nbi")}
    assert {"integrator.integrate_scene", "scene_functions.cylinder_rhs_pointer"} <= names
    other_scenes = {"integrator.integrate_coupled", "scenes.mechanism_rhs", "scenes.coupled_rhs"}
    assert not other_scenes & names
    assert not any(name.startswith("scene_functions.coupled_") for name in names)
    # "dopri5_stiff", whose stiffness test never fires on this case: no W-method compiled
    assert not {"integrator.integrate_scene_w", "stiff.w_step", "stiff.jacobian_fd"} & names
    assert not any(name.startswith("flexible.") for name in names)


_PURE_PYTHON = r"""
import numpy as np
from recipsim.case.load import load_case
from recipsim.model.build import build_model
from recipsim.solve.integrator import N_STATS, ST_NACCEPT, ST_STATUS, METHOD_AUTO, METHOD_ROSW
from recipsim.solve.scene_entries import compile_entry, integrate
compile_entry("integrate_scene")  # nothing to compile
m = build_model(load_case("reference_r134a_lbp")).for_solve()
for method in (METHOD_AUTO, METHOD_ROSW):
    y, mode, stats = m.y0.copy(), m.mode0.copy(), np.zeros(N_STATS)
    integrate(0.0, 0.1 * m.period, y, mode, m.par, m.ipar, m.props, m.props.buffer, 1e-6,
              1e-6, m.scale, m.n_err, 1e-4 * m.period, m.period / 72, np.zeros(0),
              np.zeros((0, y.shape[0])), np.zeros((0, mode.shape[0]), dtype=np.int64),
              stats, method)
    assert stats[ST_STATUS] == 0 and stats[ST_NACCEPT] > 0, stats
print("ok")
"""


def test_the_entries_run_without_the_jit() -> None:
    """Under NUMBA_DISABLE_JIT=1 the entries are plain functions: integrate runs them, the
    hand-over and the W entry included, and compile_entry has nothing to do."""
    env = dict(os.environ, NUMBA_DISABLE_JIT="1")
    out = subprocess.run(
        [sys.executable, "-c", _PURE_PYTHON], env=env, capture_output=True, text=True
    )
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.strip().endswith("ok")
