"""One rule for recipsim's cache directories.

Every cache (property tables, fluid constants, numba's compiled code, pint's parsed
unit definitions) lives under :func:`cache_dir`: ``$RECIPSIM_CACHE`` if set, else the
platform's user cache directory for ``recipsim`` from platformdirs (on Linux
``$XDG_CACHE_HOME/recipsim``, by default ``~/.cache/recipsim``). Directories are created
with mode 0o700: numba's cache is loaded with pickle, so a cache directory that others
can write is a way to run their code in your process; recipsim warns once if it finds
one (see ``docs/caches.md``).
"""

from __future__ import annotations

import os
import stat
import warnings
from pathlib import Path

_warned: set[str] = set()


def numba_cache_lacks(module: str, function: str | None = None) -> bool:
    """Whether numba's cache for this version of the compiled sources holds nothing yet of
    ``module`` (e.g. ``"integrator"``: the first run then compiles the solver), or of its
    ``function`` if given (``"integrate_coupled"``: each scene compiles on its own)."""
    directory = os.environ.get("NUMBA_CACHE_DIR")
    if not directory or os.environ.get("NUMBA_DISABLE_JIT") == "1":
        return False
    path = Path(directory)
    pattern = f"{module}.{function}-*.nbi" if function else f"{module}.*.nbi"
    return not path.is_dir() or next(path.rglob(pattern), None) is None


def cache_dir() -> Path:
    """recipsim's cache directory (not created here)."""
    env = os.environ.get("RECIPSIM_CACHE")
    if env:
        return Path(env)
    import platformdirs

    return Path(platformdirs.user_cache_dir("recipsim", appauthor=False))


def private_dir(path: Path) -> Path:
    """Create ``path`` (and its missing parents) with mode 0o700; returns it.

    Warns once per directory if it exists and is writable by the group or others.
    """
    path = Path(path)
    missing = []
    probe = path
    while not probe.exists() and probe != probe.parent:
        missing.append(probe)
        probe = probe.parent
    for directory in reversed(missing):
        try:
            directory.mkdir(mode=0o700)
        except FileExistsError:
            pass
    check_private(path)
    return path


def check_private(path: Path) -> None:
    """Warn (once) if ``path`` is a directory that the group or others may write."""
    try:
        mode = path.stat().st_mode
    except OSError:
        return
    if mode & (stat.S_IWGRP | stat.S_IWOTH) and str(path) not in _warned:
        _warned.add(str(path))
        warnings.warn(
            f"recipsim's cache directory {path} is writable by other users; numba's "
            "cache there is loaded with pickle: chmod go-w it (see docs/caches.md)",
            stacklevel=2,
        )
