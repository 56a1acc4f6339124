"""The garbage collector during a command's start-up (the command line's choice).

A command's start-up (importing numba, pandas and matplotlib; numba's registries of
implementations) allocates hundreds of thousands of objects that live as long as the
process. Python's collector, triggered by those allocations, walked them again and again:
a warm ``recipsim run`` spent 0.09-0.13 s in it, two full collections (0.06-0.09 s) among
them, on the path to its answer. The command line therefore pauses the collector as it
starts (:func:`pause`) and, once the start-up is over, moves every object that exists then
to the collector's permanent generation and lets it run again (:func:`resume`): numba's
runtime once started (:func:`recipsim.physics.compiled_runtime.start_compiled_runtime`),
or in a report process once its imports are done. Later collections walk only what was
made after that; whatever happens, the command's end resumes it.

Only the command line pauses (a library leaves the collector as its caller set it); the
objects are frozen once per process, so a process that calls the command line again and
again (tests, a notebook) freezes what it held at the first start only.
"""

from __future__ import annotations

import gc

_paused = False
_frozen = False


def pause() -> None:
    """Stop the collector until :func:`resume` (a command line starting)."""
    global _paused
    if gc.isenabled():
        gc.disable()
        _paused = True


def resume() -> None:
    """End a :func:`pause`: freeze the objects that exist now (the first time in this
    process) and let the collector run again. Nothing where no pause is in force."""
    global _paused, _frozen
    if not _paused:
        return
    if not _frozen:
        gc.freeze()
        _frozen = True
    _paused = False
    gc.enable()
