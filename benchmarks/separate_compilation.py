"""Separate compilation of the integrator and a scene's right-hand side, measured.

Until this measurement each compiled integrator entry inlined its scene's right-hand
side, event functions and event actions into one compiled loop, so a change to any
physics module compiled the whole entry again. The alternative is numbalsoda's: the
scene's functions are compiled on their own as ``numba.cfunc`` with fixed signatures, and
one integrator entry, compiled once for every scene, calls them through function pointers
(numba's first-class function type), so each piece compiles and caches on its own.
recipsim now does so for the scenes of
:data:`recipsim.model.scene_functions.POINTER_SCENES` (:mod:`recipsim.model.scene_functions`).

Three ways to reach a scene, each through the project's own loop
(:func:`recipsim.solve.integrator.scene_entry`), DOPRI5 and W-step, event location and
landing:

- ``inlined``: the loop compiled with the scene's code as a compile-time constant, its
  functions inlined (the project's path before; still the path of the other scenes);
- ``pointers``: the scene's functions as cfuncs in numbalsoda's convention, a data
  pointer and a length per array (the project's ``integrate_scene``);
- ``arrays``: the same cfuncs taking numba's array structures (by value), kept here to
  show what the convention costs (cylinder scene only).

Run from a source checkout (the venv with recipsim installed)::

    python benchmarks/separate_compilation.py solve [--case NAME] [--rungs R1,R2]
    python benchmarks/separate_compilation.py compile [--pieces P1,P2]

``solve``: the bench's own rung runner (:func:`recipsim.studies.bench.measure.run_rung`)
on the same rungs through each entry, alternated, each timed ``--repeats`` times a round
at least (CPU time of the solve, medians), with the right-hand-side evaluations, the
cycle residual and the error against the bench's tight reference. ``compile``: cold
compile times (a fresh numba cache, each in its own interpreter) of each piece, then each
again from the cache just written.
"""

from __future__ import annotations

import os

# The inlined entries compile the integrator's shared helpers (event location, the W-step)
# with a scene's code as a constant: kept in a cache of their own, not in recipsim's.
if "NUMBA_CACHE_DIR" not in os.environ:
    os.environ["NUMBA_CACHE_DIR"] = os.path.join(
        os.path.expanduser("~"), ".cache", "recipsim-benchmarks", "numba"
    )

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
import warnings
from functools import cache
from typing import Any

from numba import cfunc, njit, types
from numba.core.errors import NumbaExperimentalFeatureWarning
from numba.extending import overload

from recipsim.model import scenes
from recipsim.model.scene_functions import SCENE_NAMES, scene_functions
from recipsim.model.scenes import SCENE_CYLINDER, event_action_for, event_values_for, rhs_for
from recipsim.physics.thermo.cylinder import I_SCENE
from recipsim.physics.thermo.properties import PROPS_TYPE
from recipsim.solve import revolution, scene_entries, startup
from recipsim.solve.integrator import (
    METHOD_AUTO_IN_W,
    METHOD_DOPRI5,
    METHOD_ROSW,
    NEEDS_W_STEP,
    ST_H,
    ST_STATUS,
    ST_T,
    _named,
    scene_entry,
)
from recipsim.solve.scene_entries import _ADDED_COUNTS, ENTRY_SIGNATURE, SCENE_ENTRY_SIGNATURE
from recipsim.solve.w_gate import EXPLICIT, WITH_W_STEP

#: numba calls a plain tuple of function types experimental (the array convention's)
warnings.simplefilter("ignore", NumbaExperimentalFeatureWarning)

INLINED = "inlined"
POINTERS = "pointers"
ARRAYS = "arrays"
#: the entries compared
ENTRIES = (INLINED, POINTERS, ARRAYS)

# ---- the array convention (cylinder scene) ----------------------------------------------
_F1 = types.Array(types.float64, 1, "C")
_I1 = types.Array(types.int64, 1, "C")
ARRAY_SIGNATURES = (
    # rhs(t, y, mode, par, ipar, props, pbuf, dydt, aux) -> status
    types.int64(types.float64, _F1, _I1, _F1, _I1, PROPS_TYPE, _F1, _F1, _F1),
    # event_values(y, mode, par, ipar, aux, g)
    types.none(_F1, _I1, _F1, _I1, _F1, _F1),
    # event_action(k, y, mode, par, ipar, aux) -> ends the integration
    types.boolean(types.int64, _F1, _I1, _F1, _I1, _F1),
)
ARRAY_FUNCTIONS_TYPE = types.Tuple(tuple(types.FunctionType(sig) for sig in ARRAY_SIGNATURES))
ARRAY_ENTRY_SIGNATURE = (ARRAY_FUNCTIONS_TYPE, *ENTRY_SIGNATURE)


@overload(rhs_for)
def _rhs_for_arrays(code, t, y, mode, par, ipar, props, pbuf, dydt, aux):  # type: ignore[no-untyped-def]
    if code != ARRAY_FUNCTIONS_TYPE:
        return None
    return lambda code, t, y, mode, par, ipar, props, pbuf, dydt, aux: code[0](
        t, y, mode, par, ipar, props, pbuf, dydt, aux
    )


@overload(event_values_for)
def _event_values_for_arrays(code, y, mode, par, ipar, aux, g):  # type: ignore[no-untyped-def]
    if code != ARRAY_FUNCTIONS_TYPE:
        return None
    return lambda code, y, mode, par, ipar, aux, g: code[1](y, mode, par, ipar, aux, g)


@overload(event_action_for)
def _event_action_for_arrays(code, k, y, mode, par, ipar, aux):  # type: ignore[no-untyped-def]
    if code != ARRAY_FUNCTIONS_TYPE:
        return None
    return lambda code, k, y, mode, par, ipar, aux: code[2](k, y, mode, par, ipar, aux)


_CYLINDER_RHS = scenes._BY_SCENE["rhs"][SCENE_CYLINDER]
_CYLINDER_EVENT_VALUES = scenes._BY_SCENE["event_values"][SCENE_CYLINDER]
_CYLINDER_EVENT_ACTION = scenes._BY_SCENE["event_action"][SCENE_CYLINDER]


def cylinder_rhs_arrays(t, y, mode, par, ipar, props, pbuf, dydt, aux):  # type: ignore[no-untyped-def]
    return _CYLINDER_RHS(t, y, mode, par, ipar, props, pbuf, dydt, aux)


def cylinder_event_values_arrays(y, mode, par, ipar, aux, g):  # type: ignore[no-untyped-def]
    _CYLINDER_EVENT_VALUES(y, mode, par, ipar, aux, g)


def cylinder_event_action_arrays(k, y, mode, par, ipar, aux):  # type: ignore[no-untyped-def]
    return _CYLINDER_EVENT_ACTION(k, y, mode, par, ipar, aux)


@cache
def array_functions(code: int) -> tuple[Any, ...]:
    """The cylinder scene's functions as cfuncs of the array convention."""
    if code != SCENE_CYLINDER:
        raise NotImplementedError("the array convention is wired up for the cylinder only")
    python = (cylinder_rhs_arrays, cylinder_event_values_arrays, cylinder_event_action_arrays)
    return tuple(cfunc(sig, cache=True)(f) for sig, f in zip(ARRAY_SIGNATURES, python, strict=True))


# ---- the entries ------------------------------------------------------------------------
def _with_scene(name: str, code: int, w_entry: int) -> Any:
    """The integrator's loop compiled with scene ``code`` as a compile-time constant (its
    functions inlined, as every entry was before): a loop of its own, named ``name``, under
    an entry that passes the code on as numba's literal (every argument spelled out)."""
    loop = scene_entry(name + "_loop", w_entry)

    @njit(cache=True)
    @_named(name)
    def entry(  # type: ignore[no-untyped-def]
        t0, t1, y, mode, par, ipar, props, pbuf, rtol, atol, scale, n_err, h_init, h_max,
        sample_times, samples, sample_modes, stats, method,
    ):  # fmt: skip
        loop(
            code, t0, t1, y, mode, par, ipar, props, pbuf, rtol, atol, scale, n_err, h_init,
            h_max, sample_times, samples, sample_modes, stats, method,
        )  # fmt: skip

    return entry


@cache
def inlined_entries(code: int) -> tuple[Any, Any]:
    """The loop compiled with scene ``code`` inlined: explicit, and with the W-step."""
    name = f"integrate_{SCENE_NAMES[code]}_inlined"
    return _with_scene(name, code, EXPLICIT), _with_scene(name + "_w", code, WITH_W_STEP)


@cache
def array_entries() -> tuple[Any, Any]:
    """The loop taking the scene's functions of the array convention."""
    return (
        scene_entry("integrate_scene_arrays", EXPLICIT),
        scene_entry("integrate_scene_arrays_w", WITH_W_STEP),
    )


def _entries(entry: str, code: int) -> tuple[tuple[Any, ...], Any, Any]:
    """``(leading arguments, explicit entry, entry with the W-step)`` of ``entry``."""
    if entry == INLINED:
        return (), *inlined_entries(code)
    if entry == POINTERS:
        functions = scene_functions(code)
        return (functions,), scene_entries.integrate_scene, scene_entries.integrate_scene_w
    return (array_functions(code),), *array_entries()


def integrate_through(entry: str, *args: Any, method: int = METHOD_DOPRI5) -> None:
    """:func:`recipsim.solve.scene_entries.integrate` through ``entry`` (one of
    :data:`ENTRIES`), for any scene: the explicit entry, handing a stiff stretch over to
    the one with the W-step."""
    if len(args) == 18:
        args = (*args, method)
    lead, explicit, with_w = _entries(entry, int(args[5][I_SCENE]))
    if args[18] == METHOD_ROSW or args[18] == METHOD_AUTO_IN_W:
        with_w(*lead, *args)
        return
    explicit(*lead, *args)
    stats = args[17]
    if stats[ST_STATUS] != NEEDS_W_STEP:
        return
    counted = stats[_ADDED_COUNTS]
    args = (stats[ST_T], args[1], *args[2:12], stats[ST_H], *args[13:18], METHOD_AUTO_IN_W)
    with_w(*lead, *args)
    stats[_ADDED_COUNTS] += counted


def use_entries(entry: str) -> None:
    """Have the periodic solve (and the start-up) integrate through ``entry``."""

    def chosen(*args: Any, method: int = METHOD_DOPRI5) -> None:
        integrate_through(entry, *args, method=method)

    revolution.integrate = chosen  # type: ignore[attr-defined]
    startup.integrate_scene = chosen  # type: ignore[attr-defined]


# ---- the solve: the bench's rungs through each entry -----------------------------------
#: the rungs measured (names of the bench's full ladder): the case as shipped (table
#: properties, DOPRI5 with the W-step on stiff stretches, 5 deg steps at most) and pure
#: DOPRI5 on both property backends
RUNGS = (
    "dopri5_stiff table step=5deg rtol=1e-06 cyc=0.0001",
    "dopri5 table rtol=1e-06 cyc=0.0001",
    "dopri5 rtol=1e-06 cyc=0.0001",
)


def measure_solves(
    case_name: str,
    rounds: int,
    repeats: int,
    rungs: tuple[str, ...] = RUNGS,
    entries: tuple[str, ...] = ENTRIES,
) -> list[dict[str, Any]]:
    """Each rung of :data:`RUNGS`, ``rounds`` times through each entry (the order
    rotating), ``repeats`` timed solves each at least (the bench's minimum time per
    rung); errors against the bench's reference."""
    from recipsim.case.files import find_case_file
    from recipsim.case.load import load_case
    from recipsim.cli.bench import MIN_TIME
    from recipsim.studies.bench.errors import MAX_ERROR, error_columns
    from recipsim.studies.bench.ladder import Rung, build_ladder, reference_overrides
    from recipsim.studies.bench.measure import run_rung

    path = find_case_file(case_name)
    base = load_case(path)
    ladder = {r.name: r for r in build_ladder(base, baseline=False)}
    use_entries(INLINED)
    ref = run_rung(path, [], Rung("reference", overrides=reference_overrides()), base, 1)
    print(f"reference: {ref.status}, {ref.revolutions} revolutions", flush=True)
    rows = []
    for name in rungs:
        warmed: dict[str, set[tuple[str, ...]]] = {entry: set() for entry in entries}
        outcomes: dict[str, list[Any]] = {entry: [] for entry in entries}
        for k in range(rounds):
            shift = k % len(entries)
            for entry in entries[shift:] + entries[:shift]:
                use_entries(entry)
                out = run_rung(
                    path,
                    [],
                    ladder[name],
                    base,
                    repeats,
                    warmed=warmed[entry],
                    min_time=MIN_TIME,
                )
                outcomes[entry].append(out)
        for entry in entries:
            rows.append(_solve_row(name, entry, outcomes[entry], ref, error_columns, MAX_ERROR))
            print(json.dumps({k: v for k, v in rows[-1].items() if k != "quantities"}), flush=True)
        inlined = rows[-len(entries)]["quantities"]
        diff = max(
            abs(row["quantities"][q] / inlined[q] - 1.0)
            for row in rows[-len(entries) :]
            for q in inlined
            if inlined[q]
        )
        print(f"  {name}: largest relative difference from the inlined entry {diff:.1e}")
    return rows


def _solve_row(  # type: ignore[no-untyped-def]
    name: str, entry: str, runs: list[Any], ref: Any, error_columns, max_error: str
) -> dict[str, Any]:
    last = runs[-1]
    errors = error_columns(last.quantities, ref.quantities, last.trace, ref.trace)
    cpu = [c for out in runs for c in out.cpu_times]
    wall = [w for out in runs for w in out.wall_times]
    return {
        "rung": name,
        "entry": entry,
        "status": last.status,
        "median_cpu_time [s]": statistics.median(cpu),
        "median_wall_time [s]": statistics.median(wall),
        "solves": len(cpu),
        "rhs_evaluations": last.rhs_evaluations,
        "revolutions": last.revolutions,
        "cycle_residual": last.residual,
        "max_error [-]": errors[max_error],
        "quantities": last.quantities,
    }


# ---- compile times: each piece in its own interpreter, a fresh numba cache ---------------
#: what each piece compiles
PIECES = {
    "inlined": "the explicit cylinder entry, the scene inlined",
    "inlined_w": "the cylinder entry with the W-step, the scene inlined",
    "scene_entry": "the explicit entry taking any scene's functions (pointers)",
    "scene_entry_w": "the entry with the W-step taking any scene's functions (pointers)",
    "scene_functions": "the cylinder scene's three cfuncs (pointers)",
    "array_entry": "the explicit entry taking the functions of the array convention",
    "array_functions": "the cylinder scene's three cfuncs of the array convention",
}


def _compile_piece(piece: str) -> None:
    """Compile ``piece`` (or load it from the cache) and print its wall and CPU time."""
    t0, c0 = time.perf_counter(), time.process_time()
    if piece == "inlined":
        inlined_entries(SCENE_CYLINDER)[0].compile(ENTRY_SIGNATURE)
    elif piece == "inlined_w":
        inlined_entries(SCENE_CYLINDER)[1].compile(ENTRY_SIGNATURE)
    elif piece == "scene_entry":
        scene_entries.integrate_scene.compile(SCENE_ENTRY_SIGNATURE)
    elif piece == "scene_entry_w":
        scene_entries.integrate_scene_w.compile(SCENE_ENTRY_SIGNATURE)
    elif piece == "scene_functions":
        scene_functions(SCENE_CYLINDER)
    elif piece == "array_entry":
        array_entries()[0].compile(ARRAY_ENTRY_SIGNATURE)
    elif piece == "array_functions":
        array_functions(SCENE_CYLINDER)
    else:
        raise ValueError(piece)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    print(json.dumps({"piece": piece, "wall [s]": wall, "cpu [s]": cpu}))


def measure_compiles(pieces: tuple[str, ...]) -> list[dict[str, Any]]:
    """Each piece cold (a fresh cache directory) and then warm (from that cache)."""
    rows = []
    for piece in pieces:
        with tempfile.TemporaryDirectory() as cache:
            env = {**os.environ, "NUMBA_CACHE_DIR": cache}
            for state in ("cold", "cached"):
                done = subprocess.run(
                    [sys.executable, __file__, "_piece", piece],
                    env=env,
                    capture_output=True,
                    text=True,
                    check=True,
                )
                row = {**json.loads(done.stdout.strip().splitlines()[-1]), "cache": state}
                print(json.dumps(row), flush=True)
                rows.append(row)
    return rows


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("what", choices=("solve", "compile", "_piece"))
    parser.add_argument("piece", nargs="?", default="")
    parser.add_argument("--case", default="reference_r134a_lbp_ideal")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument(
        "--pieces", default=",".join(PIECES), help="comma-separated, of: " + ", ".join(PIECES)
    )
    parser.add_argument("--rungs", default=",".join(RUNGS), help="comma-separated rung names")
    parser.add_argument(
        "--entries", default=",".join(ENTRIES), help="comma-separated, of: " + ", ".join(ENTRIES)
    )
    parser.add_argument("--json", help="also write the rows to this file")
    args = parser.parse_args(argv)
    if args.what == "_piece":
        _compile_piece(args.piece)
        return
    if args.what == "solve":
        rungs, entries = tuple(args.rungs.split(",")), tuple(args.entries.split(","))
        rows = measure_solves(args.case, args.rounds, args.repeats, rungs, entries)
    else:
        rows = measure_compiles(tuple(args.pieces.split(",")))
    if args.json:
        with open(args.json, "w", encoding="utf-8") as handle:
            json.dump(rows, handle, indent=1, default=float)


if __name__ == "__main__":
    main()
