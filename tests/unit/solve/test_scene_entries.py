"""Each scene compiles on its own: the scene reaches the integrator as its own compiled
functions, called through pointers, computing what the scene compiled into the loop
computes; a pinned case compiles no flexible crank train nor, where no stretch turns
stiff, the Rosenbrock-W step, and a second process loads the compiled integrator from
numba's cache instead of compiling it again."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest
from numba import types
from numba.core.errors import TypingError

from recipsim.model import scenes
from recipsim.solve import w_gate

_CHILD = r"""
import json
from recipsim.case.load import load_case
from recipsim.pipeline import simulate_case
from recipsim.solve import scene_entries
from recipsim.model import scenes
from recipsim.model.scene_functions import scene_functions
case = load_case("reference_r134a_lbp").with_(
    {"solver.min_revolutions": 1, "solver.max_revolutions": 1})
simulate_case(case)
entry = scene_entries.integrate_scene
print(json.dumps({
    "signatures_as_ahead": entry.signatures == [scene_entries.SCENE_ENTRY_SIGNATURE],
    "hits": sum(entry.stats.cache_hits.values()),
    "misses": sum(entry.stats.cache_misses.values()),
    "compiled": {f.__name__: len(f.signatures) for f in (
        scene_entries.integrate_scene_w, scenes.mechanism_rhs, scenes.coupled_rhs)},
    "scene_hits": [f.cache_hits for f in scene_functions(scenes.SCENE_CYLINDER)],
}))
"""


def test_the_scene_function_is_chosen_at_compile_time() -> None:
    """A literal scene code resolves to that scene's function; a runtime one is refused."""
    for code, rhs in enumerate((scenes.cylinder_rhs, scenes.mechanism_rhs, scenes.coupled_rhs)):
        assert scenes._scene_function("rhs", types.IntegerLiteral(code)) is rhs
    with pytest.raises(TypingError, match="compile-time constant"):
        scenes._scene_function("rhs", types.int64)


# The same loop with the cylinder scene compiled into it (its code a literal), and the
# project's entry through the scene's functions, on one revolution. In a fresh cache: the
# loop's shared helpers compiled with a scene's code are not the integrator's to keep.
_POINTERS_AGAINST_INLINED = r"""
import numpy as np
from numba import njit
from recipsim.case.load import load_case
from recipsim.model.build import build_model
from recipsim.model.scenes import SCENE_CYLINDER
from recipsim.solve import scene_entries
from recipsim.solve.integrator import METHOD_DOPRI5, N_STATS, ST_NEVENTS, ST_STATUS, scene_entry
from recipsim.solve.w_gate import EXPLICIT

loop = scene_entry("integrate_cylinder_inlined_test", EXPLICIT)
code = SCENE_CYLINDER

@njit
def inlined(t0, t1, y, mode, par, ipar, props, pbuf, rtol, atol, scale, n_err, h_init,
            h_max, sample_times, samples, sample_modes, stats, method):
    loop(code, t0, t1, y, mode, par, ipar, props, pbuf, rtol, atol, scale, n_err, h_init,
         h_max, sample_times, samples, sample_modes, stats, method)

model = build_model(load_case("reference_r134a_lbp_ideal")).for_solve()
runs = []
for entry in (scene_entries.integrate, inlined):
    y, mode, stats = model.y0.copy(), model.mode0.copy(), np.zeros(N_STATS)
    times = np.linspace(0.0, model.period, 73)[:-1]
    samples = np.zeros((72, y.shape[0]))
    sample_modes = np.zeros((72, mode.shape[0]), dtype=np.int64)
    entry(0.0, model.period, y, mode, model.par, model.ipar, model.props, model.props.buffer,
          1e-6, 1e-6, model.scale, model.n_err, 1e-4 * model.period, model.period / 72, times,
          samples, sample_modes, stats, METHOD_DOPRI5)
    runs.append((y, mode, samples, sample_modes, stats))
assert runs[0][4][ST_STATUS] == 0 and runs[0][4][ST_NEVENTS] > 0, runs[0][4]
print("same" if all(np.array_equal(a, b) for a, b in zip(*runs)) else "different")
"""


@pytest.mark.slow
def test_the_scene_through_pointers_computes_what_the_inlined_scene_does(tmp_path) -> None:
    """A revolution of the cylinder scene (valve events, impacts, samples) through its
    separately compiled functions ends on the state, modes, samples and counters of the
    same loop with the scene compiled into it, to the bit: the same operations in the same
    order, only the call differs."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "numba"))
    env.pop("NUMBA_DISABLE_JIT", None)
    out = subprocess.run(
        [sys.executable, "-c", _POINTERS_AGAINST_INLINED],
        env=env,
        capture_output=True,
        text=True,
    )
    assert out.returncode == 0, out.stderr[-3000:]
    assert out.stdout.split()[-1] == "same"


def test_the_w_step_flag_is_chosen_at_compile_time() -> None:
    """The W-step flag of an entry is a literal too: the explicit entry's compiles to a
    constant, a runtime flag is refused."""
    assert w_gate._takes_w_steps(types.IntegerLiteral(w_gate.WITH_W_STEP))
    assert not w_gate._takes_w_steps(types.IntegerLiteral(w_gate.EXPLICIT))
    with pytest.raises(TypingError, match="compile-time constant"):
        w_gate._takes_w_steps(types.int64)


@pytest.mark.slow
def test_a_pinned_case_compiles_its_scene_only_and_a_second_process_loads_it(tmp_path) -> None:
    """Fresh numba cache: the first process compiles the integrator and the cylinder
    scene's functions (no flexible crank train, no other scene), the second loads both."""
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
    # and the scene's functions, compiled on their own, are loaded too
    assert first["scene_hits"] == [0, 0, 0] and second["scene_hits"] == [1, 1, 1]
    names = {p.name.split("-")[0] for p in (tmp_path / "numba").rglob("*.nbi")}
    assert {"integrator.integrate_scene", "scene_functions.cylinder_rhs_cfunc"} <= names
    assert not {"scenes.mechanism_rhs", "scenes.coupled_rhs"} & names
    other_scenes = ("scene_functions.coupled_", "scene_functions.mechanism_")
    assert not any(name.startswith(other_scenes) for name in names)
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
