"""Separate compilation of the integrator and a scene's right-hand side, measured.

Today each compiled integrator entry (:mod:`recipsim.solve.scene_entries`) inlines its
scene's right-hand side, event functions and event actions into one compiled loop, so a
change to any physics module compiles the whole entry again. The alternative measured
here is numbalsoda's: the scene's functions are compiled on their own as ``numba.cfunc``
with fixed signatures (flat float64 and int64 arrays, the property callback), and one
integrator entry, compiled once for every scene, calls them through function pointers
(numba's first-class function type), so each piece compiles and caches on its own.

The separate entry is the loop of :func:`recipsim.solve.integrator.scene_entry` as it
stands, word for word, with the compile-time scene code ``code`` replaced by an argument
``fns``: the tuple ``(rhs, event_values, event_action)`` of first-class functions.
Overloads of :func:`recipsim.model.scenes.rhs_for` (and the two event functions) for a
tuple call through the pointers, so the DOPRI5 step, the W-step, event location and
landing are the project's own code. The cylinder scene is the one wired up (the
reference case's scene); :func:`integrate_separate` stands in for
:func:`recipsim.solve.scene_entries.integrate` where the bench's rung runs.

Run from a source checkout (the venv with recipsim installed)::

    python benchmarks/separate_compilation.py solve [--repeats N] [--case NAME]
    python benchmarks/separate_compilation.py compile

``solve``: the bench's own rung runner (:func:`recipsim.studies.bench.measure.run_rung`)
on the same rungs with the inlined entry and the separate one, alternated, each timed
``N`` times per round (CPU time of the solve, medians), with the right-hand-side
evaluations, the cycle residual and the error against the bench's tight reference.
``compile``: cold compile times (a fresh numba cache, each in its own interpreter) of the
inlined cylinder entry, of the separate entry and of the cylinder scene's cfuncs, then
each again from the cache just written.
"""

from __future__ import annotations

import argparse
import functools
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
import warnings
from typing import Any

import numpy as np
from numba import carray, cfunc, njit, types
from numba.core.errors import NumbaExperimentalFeatureWarning
from numba.extending import intrinsic, overload

from recipsim.model import scenes
from recipsim.model.scenes import (
    N_AUX,
    N_EVENTS,
    SCENE_CYLINDER,
    event_action_for,
    event_values_for,
    rhs_for,
)
from recipsim.physics.thermo.cylinder import I_SCENE
from recipsim.physics.thermo.properties import PROPS_TYPE
from recipsim.physics.thermo.property_slots import SIGNAL_CHECK
from recipsim.solve import revolution, startup
from recipsim.solve.dense_output import hermite, record_samples
from recipsim.solve.dopri5 import stiffness_estimate
from recipsim.solve.events import any_crossing, locate_first_event
from recipsim.solve.integrator import (
    CHATTERING,
    DONE,
    INTERRUPTED,
    MAX_EVENTS_AT_ONE_INSTANT,
    METHOD_AUTO,
    METHOD_AUTO_IN_W,
    METHOD_DOPRI5,
    METHOD_ROSW,
    NEEDS_W_STEP,
    PROPERTY_FAILURE,
    SIGNAL_CHECK_STEPS,
    ST_H,
    ST_STATUS,
    ST_T,
    STEP_UNDERFLOW,
    _advance,
    _apply_event,
    _step,
    _write_stats,
)
from recipsim.solve.scene_entries import _ADDED_COUNTS, ENTRY_SIGNATURE, integrate
from recipsim.solve.step_args import SceneArgs, Tolerance, new_workspace
from recipsim.solve.step_control import (
    STIFF_LIMIT,
    count_stiff_step,
    next_step,
    rejected_step,
    switch_method,
)
from recipsim.solve.w_gate import EXPLICIT, WITH_W_STEP, refresh_jacobian_in

#: numba calls first-class function types experimental; every call here uses them
warnings.simplefilter("ignore", NumbaExperimentalFeatureWarning)

# ---- the fixed signatures of a scene's functions ---------------------------------------
_F1 = types.Array(types.float64, 1, "C")
_I1 = types.Array(types.int64, 1, "C")
_N = types.int64
_PF, _PI = types.CPointer(types.float64), types.CPointer(types.int64)

# Two calling conventions. ``ARRAYS``: numba arrays, as the inlined code passes them
# (each array travels as numba's array structure, by value). ``POINTERS``: numbalsoda's
# C convention, a data pointer and a length per array (``carray`` inside the cfunc).
ARRAYS = "arrays"
POINTERS = "pointers"
SIGNATURES = {
    ARRAYS: (
        # rhs(t, y, mode, par, ipar, props, pbuf, dydt, aux) -> status
        types.int64(types.float64, _F1, _I1, _F1, _I1, PROPS_TYPE, _F1, _F1, _F1),
        # event_values(y, mode, par, ipar, aux, g)
        types.none(_F1, _I1, _F1, _I1, _F1, _F1),
        # event_action(k, y, mode, par, ipar, aux) -> ends the integration
        types.boolean(types.int64, _F1, _I1, _F1, _I1, _F1),
    ),
    POINTERS: (
        # rhs(t, y, n, mode, n_mode, par, n_par, ipar, n_ipar, props, pbuf, n_pbuf, dydt,
        # aux): dydt has n entries, aux N_AUX
        types.int64(
            types.float64, _PF, _N, _PI, _N, _PF, _N, _PI, _N, PROPS_TYPE, _PF, _N, _PF, _PF
        ),
        # event_values(y, n, mode, n_mode, par, n_par, ipar, n_ipar, aux, g): g N_EVENTS
        types.none(_PF, _N, _PI, _N, _PF, _N, _PI, _N, _PF, _PF),
        # event_action(k, y, n, mode, n_mode, par, n_par, ipar, n_ipar, aux)
        types.boolean(types.int64, _PF, _N, _PI, _N, _PF, _N, _PI, _N, _PF),
    ),
}
#: numba's type of a scene's ``(rhs, event_values, event_action)`` tuple, per convention
SCENE_FUNCTIONS_TYPES = {
    abi: types.Tuple(tuple(types.FunctionType(sig) for sig in sigs))
    for abi, sigs in SIGNATURES.items()
}
#: the separate entry's argument types: the scene's functions, then the inlined entry's
SEPARATE_SIGNATURES = {abi: (t, *ENTRY_SIGNATURE) for abi, t in SCENE_FUNCTIONS_TYPES.items()}


def _convention(code: Any) -> str | None:
    """The calling convention of the scene functions' tuple type ``code`` (None for the
    project's compile-time scene code)."""
    for abi, tuple_type in SCENE_FUNCTIONS_TYPES.items():
        if code == tuple_type:
            return abi
    return None


@intrinsic
def _data(typingctx, array):  # type: ignore[no-untyped-def]
    """The data pointer of a numba array."""

    def codegen(context, builder, signature, args):  # type: ignore[no-untyped-def]
        return context.make_array(signature.args[0])(context, builder, args[0]).data

    return types.CPointer(array.dtype)(array), codegen


@overload(rhs_for)
def _rhs_for_pointer(code, t, y, mode, par, ipar, props, pbuf, dydt, aux):  # type: ignore[no-untyped-def]
    abi = _convention(code)
    if abi == ARRAYS:
        return lambda code, t, y, mode, par, ipar, props, pbuf, dydt, aux: code[0](
            t, y, mode, par, ipar, props, pbuf, dydt, aux
        )
    if abi == POINTERS:
        return lambda code, t, y, mode, par, ipar, props, pbuf, dydt, aux: code[0](
            t, _data(y), y.shape[0], _data(mode), mode.shape[0], _data(par), par.shape[0],
            _data(ipar), ipar.shape[0], props, _data(pbuf), pbuf.shape[0], _data(dydt),
            _data(aux),
        )  # fmt: skip
    return None


@overload(event_values_for)
def _event_values_for_pointer(code, y, mode, par, ipar, aux, g):  # type: ignore[no-untyped-def]
    abi = _convention(code)
    if abi == ARRAYS:
        return lambda code, y, mode, par, ipar, aux, g: code[1](y, mode, par, ipar, aux, g)
    if abi == POINTERS:
        return lambda code, y, mode, par, ipar, aux, g: code[1](
            _data(y), y.shape[0], _data(mode), mode.shape[0], _data(par), par.shape[0],
            _data(ipar), ipar.shape[0], _data(aux), _data(g),
        )  # fmt: skip
    return None


@overload(event_action_for)
def _event_action_for_pointer(code, k, y, mode, par, ipar, aux):  # type: ignore[no-untyped-def]
    abi = _convention(code)
    if abi == ARRAYS:
        return lambda code, k, y, mode, par, ipar, aux: code[2](k, y, mode, par, ipar, aux)
    if abi == POINTERS:
        return lambda code, k, y, mode, par, ipar, aux: code[2](
            k, _data(y), y.shape[0], _data(mode), mode.shape[0], _data(par), par.shape[0],
            _data(ipar), ipar.shape[0], _data(aux),
        )  # fmt: skip
    return None


# ---- the cylinder scene's functions, compiled on their own ------------------------------
_CYLINDER_RHS = scenes._BY_SCENE["rhs"][SCENE_CYLINDER]
_CYLINDER_EVENT_VALUES = scenes._BY_SCENE["event_values"][SCENE_CYLINDER]
_CYLINDER_EVENT_ACTION = scenes._BY_SCENE["event_action"][SCENE_CYLINDER]


def cylinder_rhs_c(t, y, mode, par, ipar, props, pbuf, dydt, aux):  # type: ignore[no-untyped-def]
    return _CYLINDER_RHS(t, y, mode, par, ipar, props, pbuf, dydt, aux)


def cylinder_event_values_c(y, mode, par, ipar, aux, g):  # type: ignore[no-untyped-def]
    _CYLINDER_EVENT_VALUES(y, mode, par, ipar, aux, g)


def cylinder_event_action_c(k, y, mode, par, ipar, aux):  # type: ignore[no-untyped-def]
    return _CYLINDER_EVENT_ACTION(k, y, mode, par, ipar, aux)


def cylinder_rhs_p(t, y, n, mode, n_mode, par, n_par, ipar, n_ipar, props, pbuf, n_pbuf, dydt, aux):  # type: ignore[no-untyped-def]  # noqa: E501
    return _CYLINDER_RHS(
        t, carray(y, n), carray(mode, n_mode), carray(par, n_par), carray(ipar, n_ipar),
        props, carray(pbuf, n_pbuf), carray(dydt, n), carray(aux, N_AUX),
    )  # fmt: skip


def cylinder_event_values_p(y, n, mode, n_mode, par, n_par, ipar, n_ipar, aux, g):  # type: ignore[no-untyped-def]
    _CYLINDER_EVENT_VALUES(
        carray(y, n), carray(mode, n_mode), carray(par, n_par), carray(ipar, n_ipar),
        carray(aux, N_AUX), carray(g, N_EVENTS),
    )  # fmt: skip


def cylinder_event_action_p(k, y, n, mode, n_mode, par, n_par, ipar, n_ipar, aux):  # type: ignore[no-untyped-def]
    return _CYLINDER_EVENT_ACTION(
        k, carray(y, n), carray(mode, n_mode), carray(par, n_par), carray(ipar, n_ipar),
        carray(aux, N_AUX),
    )  # fmt: skip


_PYTHON_FUNCTIONS = {
    ARRAYS: (cylinder_rhs_c, cylinder_event_values_c, cylinder_event_action_c),
    POINTERS: (cylinder_rhs_p, cylinder_event_values_p, cylinder_event_action_p),
}
_SCENE_FUNCTIONS: dict[tuple[int, str], tuple[Any, ...]] = {}


def _pointer_wrappers(code: int) -> tuple[Any, Any, Any]:
    """The pointer convention's wrappers of any scene's functions (closures: compiled,
    not cached; the cylinder scene's module-level ones above are cached)."""
    rhs, values, action = (scenes._BY_SCENE[k][code] for k in scenes._BY_SCENE)

    def rhs_p(t, y, n, mode, n_mode, par, n_par, ipar, n_ipar, props, pbuf, n_pbuf, dydt, aux):  # type: ignore[no-untyped-def]  # noqa: E501
        return rhs(
            t, carray(y, n), carray(mode, n_mode), carray(par, n_par), carray(ipar, n_ipar),
            props, carray(pbuf, n_pbuf), carray(dydt, n), carray(aux, N_AUX),
        )  # fmt: skip

    def values_p(y, n, mode, n_mode, par, n_par, ipar, n_ipar, aux, g):  # type: ignore[no-untyped-def]
        values(
            carray(y, n), carray(mode, n_mode), carray(par, n_par), carray(ipar, n_ipar),
            carray(aux, N_AUX), carray(g, N_EVENTS),
        )  # fmt: skip

    def action_p(k, y, n, mode, n_mode, par, n_par, ipar, n_ipar, aux):  # type: ignore[no-untyped-def]
        return action(
            k, carray(y, n), carray(mode, n_mode), carray(par, n_par), carray(ipar, n_ipar),
            carray(aux, N_AUX),
        )  # fmt: skip

    return rhs_p, values_p, action_p


def scene_functions(code: int = SCENE_CYLINDER, abi: str = ARRAYS) -> tuple[Any, ...]:
    """The scene's ``(rhs, event_values, event_action)`` as cfuncs of the calling
    convention ``abi`` (compiled, or loaded from numba's cache, at the first call):
    every scene in the pointer convention, the cylinder scene in both."""
    if (code, abi) not in _SCENE_FUNCTIONS:
        if code == SCENE_CYLINDER:
            functions, cache = _PYTHON_FUNCTIONS[abi], True
        elif abi == POINTERS:
            functions, cache = _pointer_wrappers(code), False
        else:
            raise NotImplementedError("the array convention is wired up for the cylinder only")
        _SCENE_FUNCTIONS[code, abi] = tuple(
            cfunc(sig, cache=cache)(function)
            for sig, function in zip(SIGNATURES[abi], functions, strict=True)
        )
    return _SCENE_FUNCTIONS[code, abi]


# ---- the integrator entry, one for every scene -------------------------------------------
def _named(name: str) -> Any:
    def rename(function: Any) -> Any:
        function.__name__ = function.__qualname__ = name
        return function

    return rename


def separate_entry(name: str, w_entry: int) -> Any:
    """:func:`recipsim.solve.integrator.scene_entry`'s loop with the scene's functions
    an argument (``fns``) instead of a compile-time scene code."""

    @njit(cache=True)
    @_named(name)
    def entry(  # type: ignore[no-untyped-def]
        fns,
        t0,
        t1,
        y,
        mode,
        par,
        ipar,
        props,
        pbuf,
        rtol,
        atol,
        scale,
        n_err,
        h_init,
        h_max,
        sample_times,
        samples,
        sample_modes,
        stats,
        method,
    ):
        scene = SceneArgs(mode, par, ipar, props, pbuf)
        tol = Tolerance(rtol, atol, scale, n_err)
        work = new_workspace(y.shape[0], n_err)
        # the arrays the loop touches on every step, taken out of the bundle once
        k1 = work.stages[0]
        k6 = work.stages[5]
        k7 = work.stages[6]
        ynew = work.ynew
        ytmp = work.ytmp
        yint = work.yint
        aux = work.aux
        g_old = work.g_old
        g_new = work.g_new
        # counts: evaluations, accepted, rejected, events, W-steps, Jacobians
        counts = np.zeros(6, dtype=np.int64)
        n_samples = sample_times.shape[0]
        i_sample = 0
        while i_sample < n_samples and sample_times[i_sample] < t0:
            i_sample += 1

        t = t0
        h = min(h_init, h_max)
        h_min = 1e-14 * max(1.0, abs(t1))
        status = rhs_for(fns, t, y, mode, par, ipar, props, pbuf, k1, aux)
        counts[0] += 1
        if status != 0:
            stats[ST_STATUS] = PROPERTY_FAILURE
            stats[ST_T] = t
            return
        event_values_for(fns, y, mode, par, ipar, aux, g_old)
        events_here = 0
        t_last_event = -1e300
        result = DONE
        property_failed = False  # the last trial step failed in the property call
        use_w = method == METHOD_ROSW or method == METHOD_AUTO_IN_W
        if method == METHOD_AUTO_IN_W:
            method = METHOD_AUTO
        n_stiff = 0  # DOPRI5 steps that looked stiff
        n_nonstiff = 0  # DOPRI5 steps that did not (W: steps DOPRI5 could have taken)
        jac_age = -1  # accepted steps since the Jacobian was built (-1: none for this y)
        jac_life = 1  # accepted steps a Jacobian is kept
        rho_jac = 0.0
        # An event located in a step is landed on by re-taking the step from its start to
        # the event (the states and quadratures then see a smooth right-hand side, no
        # interpolation across the kink), through the one step call below: its code is
        # compiled once (a second call site would compile the step again).
        landing = False
        h_accepted = h  # the accepted step [s] while its event is landed on
        k_event = -1  # the event located in the accepted step, and its time [s]
        t_event = t0
        last = False  # the step ends at t1
        while t < t1:
            if not landing:
                if use_w and w_entry == EXPLICIT:
                    result = NEEDS_W_STEP  # the entry with the W-step goes on from t
                    break
                if h < h_min:
                    result = PROPERTY_FAILURE if property_failed else STEP_UNDERFLOW
                    break
                last = False
                if t + h >= t1:
                    h = t1 - t
                    last = True
                if use_w and (jac_age < 0 or jac_age >= jac_life):
                    stj, nj, jac_life, rho_jac = refresh_jacobian_in(
                        w_entry, fns, t, y, scene, tol, work
                    )
                    counts[0] += nj
                    counts[5] += 1
                    jac_age = 0
                    if stj != 0:
                        result = PROPERTY_FAILURE
                        break
            if landing and h <= 0.0:
                st, err, ne = 1, 0.0, 0  # the event at the step's start: no re-step
            else:
                st, err, ne = _step(w_entry, use_w, fns, t, h, y, ynew, scene, tol, work)
            counts[0] += ne
            if landing:
                # the re-step's end, or the interpolant if it failed
                landing = False
                h = h_accepted
                terminal = _apply_event(fns, st == 0, t_event, k_event, y, scene, work)
                counts[0] += 1
                counts[3] += 1
                jac_age = -1  # new mode or impact: the Jacobian is rebuilt if needed
                if t_event - t_last_event < 1e-12 * max(1.0, abs(t_event)):
                    events_here += 1
                    if events_here > MAX_EVENTS_AT_ONE_INSTANT:
                        result = CHATTERING
                        t = t_event
                        break
                else:
                    events_here = 0
                t_last_event = t_event
                t = t_event
                st = rhs_for(fns, t, y, mode, par, ipar, props, pbuf, k1, aux)
                counts[0] += 1
                if st != 0:
                    result = PROPERTY_FAILURE
                    break
                # a new mode's events fire only on a fresh crossing from <= 0 to > 0
                event_values_for(fns, y, mode, par, ipar, aux, g_old)
                if t >= t1 or terminal:
                    break
                continue
            property_failed = st > 0
            if st != 0 or not (err <= 1.0):  # also catches NaN
                counts[2] += 1
                h = rejected_step(h, st, err, use_w)
                if use_w and jac_age > 0:
                    jac_age = -1  # a stale Jacobian may be why: refresh it
                continue
            if method == METHOD_AUTO and not use_w:
                stiff_step = stiffness_estimate(h, y, ynew, ytmp, k6, k7, tol) > STIFF_LIMIT
                n_stiff, n_nonstiff = count_stiff_step(stiff_step, n_stiff, n_nonstiff)

            event_values_for(fns, ynew, mode, par, ipar, aux, g_new)
            k_event = -1
            t_event = t + h
            if any_crossing(g_old, g_new):
                k_event, t_event, ne = locate_first_event(fns, t, h, y, ynew, scene, work)
                counts[0] += ne
            t_end = t + h if k_event < 0 else t_event
            i_sample = record_samples(
                t, h, y, k1, ynew, k7, t_end, t1, mode, sample_times, i_sample, samples,
                sample_modes, yint,
            )  # fmt: skip
            counts[1] += 1
            if counts[1] % SIGNAL_CHECK_STEPS == 0 and props(SIGNAL_CHECK, 0.0) != 0:
                result = INTERRUPTED
                break
            if use_w:
                counts[4] += 1
                jac_age += 1
            if k_event < 0:
                t = _advance(t, h, last, t1, y, ynew, k1, k7, g_old, g_new)
            else:
                # the fallback first (the re-step overwrites the stages), then the re-step
                hermite(t, h, y, k1, ynew, k7, t_event, yint)
                landing = True
                h_accepted = h
                h = t_event - t
                continue
            h = next_step(h, err, use_w, h_max)
            use_w, n_stiff, n_nonstiff, to_w = switch_method(
                method, use_w, h, rho_jac, n_stiff, n_nonstiff
            )
            if to_w:
                jac_age = -1

        _write_stats(stats, result, t, h, i_sample, counts)

    return entry


integrate_separate_explicit = separate_entry("integrate_separate_explicit", EXPLICIT)
integrate_separate_w = separate_entry("integrate_separate_w", WITH_W_STEP)


def integrate_separate(*args: Any, method: int = METHOD_DOPRI5, abi: str = ARRAYS) -> None:
    """:func:`recipsim.solve.scene_entries.integrate` through the separate entries with
    the scene's functions of calling convention ``abi``: the explicit entry, handing a
    stiff stretch over to the one with the W-step."""
    if len(args) == 18:
        args = (*args, method)
    fns = scene_functions(int(args[5][I_SCENE]), abi)
    if args[18] == METHOD_ROSW or args[18] == METHOD_AUTO_IN_W:
        integrate_separate_w(fns, *args)
        return
    integrate_separate_explicit(fns, *args)
    stats = args[17]
    if stats[ST_STATUS] != NEEDS_W_STEP:
        return
    counted = stats[_ADDED_COUNTS]
    args = (stats[ST_T], args[1], *args[2:12], stats[ST_H], *args[13:18], METHOD_AUTO_IN_W)
    integrate_separate_w(fns, *args)
    stats[_ADDED_COUNTS] += counted


INLINED = "inlined"
#: the entries compared: the project's, and the separate one in either convention
ENTRIES = (INLINED, ARRAYS, POINTERS)


def use_entries(entry: str) -> None:
    """Have the periodic solve (and the start-up) integrate through ``entry`` (one of
    :data:`ENTRIES`)."""
    chosen = integrate if entry == INLINED else functools.partial(integrate_separate, abi=entry)
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
    "inlined": "the project's explicit cylinder entry (loop + scene inlined)",
    "inlined_w": "the project's cylinder entry with the W-step",
    "separate_arrays": "the separate explicit entry (every scene), array convention",
    "separate_pointers": "the separate explicit entry (every scene), pointer convention",
    "separate_w_arrays": "the separate entry with the W-step, array convention",
    "scene_arrays": "the cylinder scene's three cfuncs, array convention",
    "scene_pointers": "the cylinder scene's three cfuncs, pointer convention",
}


def _compile_piece(piece: str) -> None:
    """Compile ``piece`` (or load it from the cache) and print its wall and CPU time."""
    from recipsim.solve.scene_entries import compile_entry

    t0, c0 = time.perf_counter(), time.process_time()
    if piece.startswith("inlined"):
        compile_entry(piece.replace("inlined", "integrate_cylinder"))
    elif piece.startswith("separate_w_"):
        integrate_separate_w.compile(SEPARATE_SIGNATURES[piece.removeprefix("separate_w_")])
    elif piece.startswith("separate_"):
        abi = piece.removeprefix("separate_")
        integrate_separate_explicit.compile(SEPARATE_SIGNATURES[abi])
    elif piece.startswith("scene_"):
        scene_functions(SCENE_CYLINDER, piece.removeprefix("scene_"))
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
