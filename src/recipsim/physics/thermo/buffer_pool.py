"""Reuse of large work arrays (property buffers of 11 MB): a list of the arrays handed
out, and the first that nothing but the list holds any more is handed out again.

A model build otherwise allocates, page-faults and later frees a new buffer; a sweep
worker builds one model per point. The caller rewrites a reused array whole, so reuse
never changes a result.
"""

from __future__ import annotations

import sys
import threading

import numpy as np

#: Arrays a list keeps for reuse (a sweep worker needs one at a time; threads more).
KEPT = 4
_LOCK = threading.Lock()


def reusable_buffer(kept: list[np.ndarray], size: int) -> np.ndarray:
    """An array of ``size`` float64 (contents undefined): one of ``kept`` that nothing
    else references, or a new one (added to ``kept`` while it holds fewer than
    :data:`KEPT`). Thread-safe: a returned array is referenced by its caller, so no other
    call hands it out until the caller drops it."""
    with _LOCK:
        buf = _unreferenced(kept)
        if buf is None or buf.size != size:
            buf = np.empty(size)
            if len(kept) < KEPT:
                kept.append(buf)
    return buf


def _refcount_in_loop(items: list[np.ndarray]) -> int:
    for item in items:
        return sys.getrefcount(item)
    return 0


def _unreferenced(buffers: list[np.ndarray]) -> np.ndarray | None:
    """The first of ``buffers`` that only the list references, or None."""
    for buf in buffers:
        if sys.getrefcount(buf) <= _FREE_REFCOUNT:
            return buf
    return None


#: The reference count of an array held only by a list, seen inside the loop of
#: :func:`_unreferenced` (measured, not assumed: interpreters count borrowed references
#: differently).
_FREE_REFCOUNT = _refcount_in_loop([np.empty(1)])
