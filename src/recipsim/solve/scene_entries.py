"""The compiled integrator's entries: one per scene, and one per scene with the
Rosenbrock-W step, and :func:`integrate`, which picks them.

Each entry is the loop of :func:`recipsim.solve.integrator.scene_entry` compiled with
its scene and W-step flag as compile-time constants: it compiles (and numba caches, in
its own file) that scene's code only, and the explicit entry none of the W-method
(:mod:`.w_gate`). The scenes of :data:`~recipsim.model.scene_functions.POINTER_SCENES`
share two entries (``integrate_scene``, ``integrate_scene_w``) that take the scene's
functions as their first argument, compiled on their own and called through pointers
(:mod:`recipsim.model.scene_functions`). :func:`integrate` runs a scene's explicit entry
and hands over to its entry with the W-step where the W-step takes over
(:data:`METHOD_AUTO` on a stiff stretch, :data:`METHOD_ROSW` from the start), so a case
that never takes a W-step never compiles one. The hand-over repeats what the one loop
does at a switch: the same state, step and samples, the first stage and the event values
evaluated again at the same state (one more right-hand side in ``rhs_evaluations``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from numba import types

from recipsim.model.scene_functions import POINTER_SCENES, SCENE_FUNCTIONS_TYPE, scene_functions
from recipsim.model.scenes import SCENE_COUPLED, SCENE_MECHANISM
from recipsim.physics.mechanics.crank_trains import CRANK_TRAINS
from recipsim.physics.thermo.cylinder import I_SCENE
from recipsim.physics.thermo.pressure_sources import PRESSURE_SOURCES
from recipsim.physics.thermo.properties import PROPS_TYPE
from recipsim.solve.integrator import (
    METHOD_AUTO_IN_W,
    METHOD_DOPRI5,
    METHOD_ROSW,
    NEEDS_W_STEP,
    SCENE_AS_ARGUMENT,
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


#: every scene of POINTER_SCENES: its functions the first argument
integrate_scene = scene_entry("integrate_scene", SCENE_AS_ARGUMENT, EXPLICIT)
integrate_mechanism = scene_entry("integrate_mechanism", SCENE_MECHANISM, EXPLICIT)
integrate_coupled = scene_entry("integrate_coupled", SCENE_COUPLED, EXPLICIT)
integrate_scene_w = scene_entry("integrate_scene_w", SCENE_AS_ARGUMENT, WITH_W_STEP)
integrate_mechanism_w = scene_entry("integrate_mechanism_w", SCENE_MECHANISM, WITH_W_STEP)
integrate_coupled_w = scene_entry("integrate_coupled_w", SCENE_COUPLED, WITH_W_STEP)


#: numba's argument types of every entry, as :func:`integrate` passes them (arrays
#: C-contiguous; ``ipar``, ``mode`` and ``sample_modes`` int64; ``n_err`` and ``method``
#: int64): what :func:`compile_entry` compiles without a case (``recipsim warmup``)
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
#: the same, after the scene's functions, for ``integrate_scene`` and ``integrate_scene_w``
SCENE_ENTRY_SIGNATURE = (SCENE_FUNCTIONS_TYPE, *ENTRY_SIGNATURE)

#: The explicit compiled entry of each scene, indexed by its code.
SCENE_INTEGRATORS = (integrate_scene, integrate_mechanism, integrate_coupled)
#: The entry of each scene with the Rosenbrock-W step, indexed by its code.
W_SCENE_INTEGRATORS = (integrate_scene_w, integrate_mechanism_w, integrate_coupled_w)
#: The counters that add up over a hand-over between the two entries.
_ADDED_COUNTS = [ST_NFEV, ST_NACCEPT, ST_NREJECT, ST_NEVENTS, ST_NSTIFF, ST_NJAC]


def integrate(*args: Any, method: int = METHOD_DOPRI5) -> None:
    """Integrate the scene in ``ipar[I_SCENE]`` in place: the arguments of
    :func:`recipsim.solve.integrator.scene_entry`'s entries. It runs the scene's
    explicit entry (the first call for a scene compiles that scene only), and its entry
    with the Rosenbrock-W step from where the W-step takes over (:data:`METHOD_AUTO`
    on a stiff stretch, :data:`METHOD_ROSW` from the start): a case that never takes a
    W-step never compiles one."""
    if len(args) == 18:  # method left out
        args = (*args, method)
    code = int(args[5][I_SCENE])  # args[5]: ipar
    scene = (scene_functions(code),) if code in POINTER_SCENES else ()
    if args[18] == METHOD_ROSW or args[18] == METHOD_AUTO_IN_W:
        _w_entry(code)(*scene, *args)
        return
    SCENE_INTEGRATORS[code](*scene, *args)
    stats = args[17]
    if stats[ST_STATUS] != NEEDS_W_STEP:
        return
    counted = stats[_ADDED_COUNTS]
    # t0 and the first step (args[12]) from where the explicit entry stopped
    args = (stats[ST_T], args[1], *args[2:12], stats[ST_H], *args[13:18], METHOD_AUTO_IN_W)
    _w_entry(code)(*scene, *args)
    stats[_ADDED_COUNTS] += counted


def _w_entry(code: int) -> Any:
    """The entry of scene ``code`` with the W-step (its first compilation is announced
    and timed by :mod:`recipsim.progress`, as every compilation is)."""
    return W_SCENE_INTEGRATORS[code]


def entry_name(options: Options, solver: SolverSettings) -> str | None:
    """The compiled entry that a case with these ``[options]`` and ``[solver]`` starts
    with, by name; None where nothing is integrated (pinned mechanism, tabulated
    pressure). ``"dopri5_stiff"`` starts with the explicit entry (the one with the
    W-step compiles where a stretch turns stiff), ``"ros34pw2"`` with the W-step's."""
    if not PRESSURE_SOURCES[options.pressure].solves_gas:
        if not CRANK_TRAINS[options.mechanics].flexible:
            return None
        scene = "integrate_mechanism"
    else:
        flexible = CRANK_TRAINS[options.mechanics].flexible
        scene = "integrate_coupled" if flexible else "integrate_scene"
    return scene + "_w" if solver.method == "ros34pw2" else scene


def compile_entry(name: str) -> None:
    """Compile the entry ``name`` (:func:`entry_name`) for :data:`ENTRY_SIGNATURE` into
    numba's cache, without running it: no case, no properties needed (nothing under
    ``NUMBA_DISABLE_JIT=1``). ``integrate_scene`` and ``integrate_scene_w`` compile for
    :data:`SCENE_ENTRY_SIGNATURE`, with the functions of every scene that they serve."""
    entry = globals()[name]
    if not hasattr(entry, "compile"):
        return
    if name.startswith("integrate_scene"):
        entry.compile(SCENE_ENTRY_SIGNATURE)
        for code in POINTER_SCENES:
            scene_functions(code)
    else:
        entry.compile(ENTRY_SIGNATURE)
