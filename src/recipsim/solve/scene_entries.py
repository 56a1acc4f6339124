"""The compiled integrator's two entries, ``integrate_scene`` and ``integrate_scene_w``
(the latter with the Rosenbrock-W step), and :func:`integrate`, which picks them.

Each entry is the loop of :func:`recipsim.solve.integrator.scene_entry`, compiled once
for every scene: the scene's right-hand side, event functions and actions come as its
first argument, compiled on their own (:mod:`recipsim.model.scene_functions`: each
scene's in files of its own in numba's cache) and called through pointers. The explicit
entry compiles none of the W-method (:mod:`.w_gate`). :func:`integrate` runs the explicit
entry and hands over to the entry with the W-step where the W-step takes over
(:data:`METHOD_AUTO` on a stiff stretch, :data:`METHOD_ROSW` from the start), so a case
that never takes a W-step never compiles one. The hand-over repeats what the one loop
does at a switch: the same state, step and samples, the first stage and the event values
evaluated again at the same state (one more right-hand side in ``rhs_evaluations``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from numba import types

from recipsim.model.scene_functions import SCENE_FUNCTIONS_TYPE, scene_functions
from recipsim.physics.mechanics.crank_trains import CRANK_TRAINS
from recipsim.physics.thermo.cylinder import I_SCENE
from recipsim.physics.thermo.pressure_sources import PRESSURE_SOURCES
from recipsim.physics.thermo.properties import PROPS_TYPE
from recipsim.solve.integrator import (
    METHOD_AUTO_IN_W,
    METHOD_DOPRI5,
    METHOD_ROSW,
    NEEDS_W_STEP,
    ST_H,
    ST_NACCEPT,
    ST_NEVENTS,
    ST_NFEV,
    ST_NJAC,
    ST_NREJECT,
    ST_NSTIFF,
    ST_STATUS,
    ST_T,
    scene_entry,
)
from recipsim.solve.w_gate import EXPLICIT, WITH_W_STEP

if TYPE_CHECKING:
    from recipsim.case.sections import Options, SolverSettings


integrate_scene = scene_entry("integrate_scene", EXPLICIT)
integrate_scene_w = scene_entry("integrate_scene_w", WITH_W_STEP)


#: numba's argument types of the entries after the scene's functions, as :func:`integrate`
#: passes them (arrays C-contiguous; ``ipar``, ``mode`` and ``sample_modes`` int64;
#: ``n_err`` and ``method`` int64)
_F1, _F2 = types.Array(types.float64, 1, "C"), types.Array(types.float64, 2, "C")
_I1, _I2 = types.Array(types.int64, 1, "C"), types.Array(types.int64, 2, "C")
_F, _N = types.float64, types.int64
# fmt: off
ENTRY_SIGNATURE = (
    _F, _F, _F1, _I1, _F1, _I1,  # t0, t1, y, mode, par, ipar
    PROPS_TYPE, _F1, _F, _F, _F1, _N,  # props, pbuf, rtol, atol, scale, n_err
    _F, _F, _F1,  # h_init, h_max, sample_times
    _F2, _I2, _F1, _N,  # samples, sample_modes, stats, method
)
# fmt: on
#: every argument of the entries: what :func:`compile_entry` compiles without a case
#: (``recipsim warmup``)
SCENE_ENTRY_SIGNATURE = (SCENE_FUNCTIONS_TYPE, *ENTRY_SIGNATURE)
#: The counters that add up over a hand-over between the two entries.
_ADDED_COUNTS = [ST_NFEV, ST_NACCEPT, ST_NREJECT, ST_NEVENTS, ST_NSTIFF, ST_NJAC]


def integrate(*args: Any, method: int = METHOD_DOPRI5) -> None:
    """Integrate the scene in ``ipar[I_SCENE]`` in place: the arguments of
    :func:`recipsim.solve.integrator.scene_entry`'s entries after the scene's functions,
    which this adds (their first use compiles that scene's functions only). It runs the
    explicit entry, and the entry with the Rosenbrock-W step from where the W-step takes
    over (:data:`METHOD_AUTO` on a stiff stretch, :data:`METHOD_ROSW` from the start): a
    case that never takes a W-step never compiles one."""
    if len(args) == 18:  # method left out
        args = (*args, method)
    scene = scene_functions(int(args[5][I_SCENE]))  # args[5]: ipar
    if args[18] == METHOD_ROSW or args[18] == METHOD_AUTO_IN_W:
        integrate_scene_w(scene, *args)
        return
    integrate_scene(scene, *args)
    stats = args[17]
    if stats[ST_STATUS] != NEEDS_W_STEP:
        return
    counted = stats[_ADDED_COUNTS]
    # t0 and the first step (args[12]) from where the explicit entry stopped
    args = (stats[ST_T], args[1], *args[2:12], stats[ST_H], *args[13:18], METHOD_AUTO_IN_W)
    integrate_scene_w(scene, *args)
    stats[_ADDED_COUNTS] += counted


def entry_name(options: Options, solver: SolverSettings) -> str | None:
    """The compiled entry that a case with these ``[options]`` and ``[solver]`` starts
    with, by name; None where nothing is integrated (pinned mechanism, tabulated
    pressure). ``"dopri5_stiff"`` starts with the explicit entry (the one with the
    W-step compiles where a stretch turns stiff), ``"ros34pw2"`` with the W-step's."""
    solves_gas = PRESSURE_SOURCES[options.pressure].solves_gas
    if not solves_gas and not CRANK_TRAINS[options.mechanics].flexible:
        return None
    return "integrate_scene_w" if solver.method == "ros34pw2" else "integrate_scene"


def compile_entry(name: str) -> None:
    """Compile the entry ``name`` (:func:`entry_name`) for :data:`SCENE_ENTRY_SIGNATURE`
    into numba's cache, without running it: no case, no properties needed (nothing under
    ``NUMBA_DISABLE_JIT=1``). A scene's functions compile at its first integration."""
    entry = globals()[name]
    if hasattr(entry, "compile"):
        entry.compile(SCENE_ENTRY_SIGNATURE)
