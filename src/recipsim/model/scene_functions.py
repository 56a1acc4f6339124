"""A scene's functions compiled on their own, called by the integrator through pointers.

A scene (:mod:`recipsim.model.scenes`) is a right-hand side, its event functions and its
event actions. Each of the three is compiled (and cached by numba) on its own, as a
``numba.cfunc`` behind a fixed C signature, and the compiled integrator
(:mod:`recipsim.solve.integrator`) receives the three as first-class functions
(:class:`SceneFunctions`) and calls them through their addresses: the integrator is
compiled once for every scene, and a scene's physics compiles without the integrator's
loop. This is numbalsoda's convention: each array travels as a data pointer and a length
(``numba.carray`` makes the array again inside), the state's derivative has the state's
length, ``aux`` :data:`.scenes.N_AUX` entries and the event values
:data:`.scenes.N_EVENTS`:

- ``rhs(t, y, n, mode, n_mode, par, n_par, ipar, n_ipar, props, pbuf, n_pbuf, dydt,
  aux) -> status`` (:data:`RHS_SIGNATURE`; ``props`` the property callback);
- ``event_values(y, n, mode, n_mode, par, n_par, ipar, n_ipar, aux, g)``;
- ``event_action(k, y, n, mode, n_mode, par, n_par, ipar, n_ipar, aux) -> ends``.

Measured on every scene (``benchmarks/separate_compilation.py``, ``docs/speed.md``), the
call through the pointer costs less than the scene compiled into the integrator's loop:
the arrays rebuilt by ``carray`` carry no reference count, which the scene's own slicing
then does not update. The solve is 3-47 % faster, to the same bits. Passing numba's array
structures through the pointer instead is 9-26 % slower than the inlined scene.

Overloads of :func:`.scenes.rhs_for`, :func:`.scenes.event_values_for` and
:func:`.scenes.event_action_for` for :data:`SCENE_FUNCTIONS_TYPE` make the calls, so the
integrator's step, event location and W-step code are written once for either a scene's
functions or its compile-time code. Without the JIT (``NUMBA_DISABLE_JIT=1``)
:func:`scene_functions` hands back the scene's code, and the plain-Python bodies of those
functions dispatch on it.
"""

from __future__ import annotations

from typing import Any, NamedTuple

from numba import carray, cfunc, njit, types
from numba.core import config
from numba.extending import intrinsic, overload

from recipsim.model.scenes import (
    N_AUX,
    N_EVENTS,
    event_action_for,
    event_values_for,
    rhs_for,
)
from recipsim.physics.thermo.properties import PROPS_TYPE

#: each scene's name in its functions' names (numba caches each under its name)
SCENE_NAMES = ("cylinder", "mechanism", "coupled")

_F, _N = types.float64, types.int64
_PF, _PI = types.CPointer(types.float64), types.CPointer(types.int64)
#: ``rhs(t, y, n, mode, n_mode, par, n_par, ipar, n_ipar, props, pbuf, n_pbuf, dydt, aux)``
RHS_SIGNATURE = types.int64(_F, _PF, _N, _PI, _N, _PF, _N, _PI, _N, PROPS_TYPE, _PF, _N, _PF, _PF)
#: ``event_values(y, n, mode, n_mode, par, n_par, ipar, n_ipar, aux, g)``
EVENT_VALUES_SIGNATURE = types.none(_PF, _N, _PI, _N, _PF, _N, _PI, _N, _PF, _PF)
#: ``event_action(k, y, n, mode, n_mode, par, n_par, ipar, n_ipar, aux) -> ends``
EVENT_ACTION_SIGNATURE = types.boolean(_N, _PF, _N, _PI, _N, _PF, _N, _PI, _N, _PF)
SIGNATURES = (RHS_SIGNATURE, EVENT_VALUES_SIGNATURE, EVENT_ACTION_SIGNATURE)


class SceneFunctions(NamedTuple):
    """A scene's three functions as cfuncs, the integrator's first argument (a named
    tuple: numba types a plain tuple of function types through an experimental path that
    warns at every call)."""

    rhs: Any
    event_values: Any
    event_action: Any


#: numba's type of :class:`SceneFunctions`
SCENE_FUNCTIONS_TYPE = types.NamedTuple(
    [types.FunctionType(sig) for sig in SIGNATURES], SceneFunctions
)

_COMPILED: dict[int, Any] = {}


def scene_functions(code: int) -> Any:
    """The scene ``code``'s functions (:class:`SceneFunctions`), compiled (or loaded
    from numba's cache) at the first call; the code itself without the JIT."""
    if getattr(config, "DISABLE_JIT", False):
        return code
    if code not in _COMPILED:
        _COMPILED[code] = _cfuncs(code)
    return _COMPILED[code]


# The scene's functions behind the pointer signatures, for a scene code that is a
# compile-time constant (numba's literal, passed on by the cfuncs below): compiled and
# cached once per scene, and announced as this module's (recipsim.progress).
@njit(cache=True)
def rhs_pointer(
    code, t, y, n, mode, n_mode, par, n_par, ipar, n_ipar, props, pbuf, n_pbuf, dydt, aux
):  # type: ignore[no-untyped-def]  # noqa: E501
    return rhs_for(
        code, t, carray(y, n), carray(mode, n_mode), carray(par, n_par), carray(ipar, n_ipar),
        props, carray(pbuf, n_pbuf), carray(dydt, n), carray(aux, N_AUX),
    )  # fmt: skip


@njit(cache=True)
def event_values_pointer(code, y, n, mode, n_mode, par, n_par, ipar, n_ipar, aux, g):  # type: ignore[no-untyped-def]  # noqa: E501
    event_values_for(
        code, carray(y, n), carray(mode, n_mode), carray(par, n_par), carray(ipar, n_ipar),
        carray(aux, N_AUX), carray(g, N_EVENTS),
    )  # fmt: skip


@njit(cache=True)
def event_action_pointer(code, k, y, n, mode, n_mode, par, n_par, ipar, n_ipar, aux):  # type: ignore[no-untyped-def]  # noqa: E501
    return event_action_for(
        code, k, carray(y, n), carray(mode, n_mode), carray(par, n_par), carray(ipar, n_ipar),
        carray(aux, N_AUX),
    )  # fmt: skip


def _cfuncs(code: int) -> SceneFunctions:
    """Scene ``code``'s three functions as cfuncs of :data:`SIGNATURES`, named after the
    scene (``cylinder_rhs_pointer``, ...): numba caches each in a file of its own. Each
    closes over the scene's code only: numba keys a cached closure on what it closes
    over, which must be the same in the next process."""

    def rhs(t, y, n, mode, n_mode, par, n_par, ipar, n_ipar, props, pbuf, n_pbuf, dydt, aux):  # type: ignore[no-untyped-def]  # noqa: E501
        return rhs_pointer(
            code, t, y, n, mode, n_mode, par, n_par, ipar, n_ipar, props, pbuf, n_pbuf, dydt, aux
        )  # noqa: E501

    def event_values(y, n, mode, n_mode, par, n_par, ipar, n_ipar, aux, g):  # type: ignore[no-untyped-def]  # noqa: E501
        event_values_pointer(code, y, n, mode, n_mode, par, n_par, ipar, n_ipar, aux, g)

    def event_action(k, y, n, mode, n_mode, par, n_par, ipar, n_ipar, aux):  # type: ignore[no-untyped-def]  # noqa: E501
        return event_action_pointer(code, k, y, n, mode, n_mode, par, n_par, ipar, n_ipar, aux)

    functions = (rhs, event_values, event_action)
    return SceneFunctions(
        *(
            cfunc(signature, cache=True)(_named(function, code))
            for signature, function in zip(SIGNATURES, functions, strict=True)
        )
    )


def _named(function: Any, code: int) -> Any:
    """``function`` renamed after scene ``code`` (``rhs`` -> ``cylinder_rhs_cfunc``)."""
    function.__name__ = function.__qualname__ = f"{SCENE_NAMES[code]}_{function.__name__}_cfunc"
    return function


@intrinsic
def _data(typingctx, array):  # type: ignore[no-untyped-def]
    """The data pointer of a numba array (``CPointer`` of its dtype)."""

    def codegen(context, builder, signature, args):
        return context.make_array(signature.args[0])(context, builder, args[0]).data

    return types.CPointer(array.dtype)(array), codegen


def _through_pointers(code: Any) -> bool:
    """Whether ``code`` (a numba type) is a scene's functions' tuple."""
    return bool(code == SCENE_FUNCTIONS_TYPE)


@overload(rhs_for)
def _rhs_through_pointer(code, t, y, mode, par, ipar, props, pbuf, dydt, aux):  # type: ignore[no-untyped-def]
    if not _through_pointers(code):
        return None
    return lambda code, t, y, mode, par, ipar, props, pbuf, dydt, aux: code.rhs(
        t, _data(y), y.shape[0], _data(mode), mode.shape[0], _data(par), par.shape[0],
        _data(ipar), ipar.shape[0], props, _data(pbuf), pbuf.shape[0], _data(dydt), _data(aux),
    )  # fmt: skip


@overload(event_values_for)
def _event_values_through_pointer(code, y, mode, par, ipar, aux, g):  # type: ignore[no-untyped-def]
    if not _through_pointers(code):
        return None
    return lambda code, y, mode, par, ipar, aux, g: code.event_values(
        _data(y), y.shape[0], _data(mode), mode.shape[0], _data(par), par.shape[0],
        _data(ipar), ipar.shape[0], _data(aux), _data(g),
    )  # fmt: skip


@overload(event_action_for)
def _event_action_through_pointer(code, k, y, mode, par, ipar, aux):  # type: ignore[no-untyped-def]
    if not _through_pointers(code):
        return None
    return lambda code, k, y, mode, par, ipar, aux: code.event_action(
        k, _data(y), y.shape[0], _data(mode), mode.shape[0], _data(par), par.shape[0],
        _data(ipar), ipar.shape[0], _data(aux),
    )  # fmt: skip
