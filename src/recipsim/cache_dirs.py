"""One rule for recipsim's cache directories.

Every cache (property tables, numba's compiled code, pint's parsed unit definitions,
journal-bearing tables) lives under :func:`cache_dir`: ``$RECIPSIM_CACHE`` if set, else
the platform's user cache directory for ``recipsim`` from platformdirs (on Linux
``$XDG_CACHE_HOME/recipsim``, by default ``~/.cache/recipsim``). Directories are
created with mode 0o700: numba's and pint's caches are loaded with pickle, so a cache
directory that others can write is a way to run their code in your process; recipsim
warns once if it finds one and then does not use those caches (:func:`trusted_cache`,
see ``docs/caches.md``).

numba's cache of recipsim's own compiled functions is kept per version of the compiled
sources (:func:`numba_cache_path`), by a cache locator that serves recipsim's files only
(:func:`use_recipsim_numba_cache`): numba invalidates a cached function when its own
file changes, not when a constant it reads from another module does (a parameter-layout
index), so one directory per digest of all the compiled sources keeps a stale cache from
reading the wrong slots. The integrator (``solve/``) has a directory of its own, per
digest of :data:`SOLVER_SOURCES` only: it calls a scene's physics through pointers
(:mod:`recipsim.model.scene_functions`) and compiles none of it in, so a change to a
physics module compiles the scenes' functions again, not the integrator. Nothing else
is redirected: the process environment and numba's configuration stay as the user set
them. The locator uses numba's extension point for cache locations (a class in
``CacheImpl._locator_classes``); a numba without it leaves recipsim's functions to
numba's own cache rules.
"""

from __future__ import annotations

import hashlib
import logging
import os
import pickle
import stat
import warnings
from functools import cache, lru_cache
from pathlib import Path
from typing import Any

_warned: set[str] = set()

#: The package's folder, and those holding compiled code or the constants it reads.
_PACKAGE = Path(__file__).resolve().parent
_COMPILED_SOURCES = ("physics", "model", "solve", "studies/bench")
#: What the integrator's compiled code (the folder ``solve``) is made of: its own sources,
#: the scene-function calls and the layouts whose sizes it allocates (``model``: the
#: scenes' layout, :mod:`~recipsim.model.scene_functions`), the tables that fix those
#: sizes (the cylinder's and the mechanism's layouts, the layout table), the property
#: callback's signature and status codes. No physics kernel: a scene's physics reaches
#: the integrator through pointers. ``tests/unit/base/test_cache_dirs.py`` checks that
#: every recipsim module the compiled ``solve`` modules import is here.
SOLVER_SOURCES = (
    "solve",
    "model",
    "physics/layout_table.py",
    "physics/thermo/cylinder.py",
    "physics/mechanics/layout.py",
    "physics/thermo/property_slots.py",
    "physics/thermo/properties.py",
)
#: The folder whose functions are cached per digest of :data:`SOLVER_SOURCES`.
SOLVER_FOLDER = "solve"


@lru_cache(maxsize=2)
def compiled_sources_digest(sources: tuple[str, ...] = _COMPILED_SOURCES) -> str:
    """A digest of every source file of ``sources`` (folders and files of the package;
    by default every package holding compiled code) (16 hex)."""
    digest = hashlib.blake2b(digest_size=8)
    for entry in sources:
        path = _PACKAGE / entry
        for file in sorted(path.rglob("*.py")) if path.is_dir() else [path]:
            digest.update(file.relative_to(_PACKAGE).as_posix().encode())
            digest.update(file.read_bytes())
    return digest.hexdigest()


def numba_cache_path(solver: bool = False) -> Path:
    """Where numba's cache of recipsim's compiled functions is kept:
    ``<NUMBA_CACHE_DIR or <cache>/numba>/recipsim-<digest of the compiled sources>``;
    with ``solver``, the integrator's: ``.../recipsim-solver-<digest of SOLVER_SOURCES>``."""
    base = Path(os.environ.get("NUMBA_CACHE_DIR") or str(cache_dir() / "numba"))
    if solver:
        return base / f"recipsim-solver-{compiled_sources_digest(SOLVER_SOURCES)}"
    return base / f"recipsim-{compiled_sources_digest()}"


def use_recipsim_numba_cache() -> None:
    """Have numba keep the cache of recipsim's compiled functions in
    :func:`numba_cache_path` (created private); other functions keep numba's own rules.

    Called once, as ``recipsim`` is imported, before any of its functions is compiled.
    Where the directory cannot be created, numba's own locators take over.
    """
    from numba.core import caching

    impl = getattr(caching, "CacheImpl", None) or getattr(caching, "_CacheImpl", None)
    locators: list[Any] | None = getattr(impl, "_locator_classes", None)
    if locators is None:  # another numba: its own cache rules apply to recipsim too
        logging.getLogger("recipsim").debug("numba has no cache locator list")
        return
    if not any(cls is _RecipsimCacheLocator() for cls in locators):
        locators.insert(0, _RecipsimCacheLocator())


@cache
def discard_unreadable_indexes(folder: str) -> None:
    """Remove the numba cache indexes (``*.nbi``) of ``folder`` that do not unpickle (a
    file truncated or overwritten), once per folder and process: numba would raise on
    them at every run; without them it compiles those functions again and rewrites the
    index. Only recipsim's own, trusted cache folders are scanned."""
    for index in Path(folder).glob("*.nbi"):
        try:
            with open(index, "rb") as handle:
                pickle.load(handle)  # numba's format: its version, then the index data
                pickle.loads(handle.read())
        except Exception:  # anything unreadable: pickle raises many types
            # logged (one line), not warned: this runs while recipsim is being imported
            logging.getLogger("recipsim").warning(
                "numba cache index %s was unreadable; it is compiled again", index
            )
            index.unlink(missing_ok=True)


@lru_cache(maxsize=1)
def _RecipsimCacheLocator() -> type:  # noqa: N802 (a class, made once)
    """numba's cache locator for the files of this package (see the module docstring)."""
    from numba.core import caching

    class RecipsimCacheLocator(caching._SourceFileBackedLocatorMixin, caching._CacheLocator):
        def __init__(self, py_func: Any, py_file: str) -> None:
            self._py_file = py_file
            self._lineno = py_func.__code__.co_firstlineno
            folder = Path(py_file).resolve().parent.relative_to(_PACKAGE)
            solver = folder.parts[:1] == (SOLVER_FOLDER,)
            self._cache_path = str(numba_cache_path(solver) / folder)

        def get_cache_path(self) -> str:
            return self._cache_path

        def ensure_cache_path(self) -> None:
            if trusted_cache(Path(self._cache_path)) is None:
                raise OSError(f"untrusted cache directory {self._cache_path}")
            super().ensure_cache_path()
            discard_unreadable_indexes(self._cache_path)

        @classmethod
        def from_function(cls, py_func: Any, py_file: str) -> Any:
            if not Path(py_file).resolve().is_relative_to(_PACKAGE):
                return None
            return super().from_function(py_func, py_file)

    return RecipsimCacheLocator


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
    if not is_private(path) and path.is_dir() and str(path) not in _warned:
        _warned.add(str(path))
        warnings.warn(
            f"recipsim's cache directory {path} is writable by other users (or not yours); "
            "its pickled caches (numba's compiled code, pint's unit definitions) are not "
            "used: chmod go-w it (see docs/caches.md)",
            stacklevel=2,
        )


def is_private(path: Path) -> bool:
    """Whether ``path`` is owned by this user and writable by no one else."""
    try:
        info = path.stat()
    except OSError:
        return False
    return info.st_uid == os.getuid() and not info.st_mode & (stat.S_IWGRP | stat.S_IWOTH)


def trusted_cache(path: Path) -> Path | None:
    """``path`` created private (:func:`private_dir`), if it and the cache root are owned
    by this user and writable by no one else; else None (with a warning): a cache that is
    loaded with pickle is used only from there, since whoever can write a folder can plant
    code in it or swap it for another."""
    try:
        private_dir(path)
    except OSError:
        return None
    root = cache_dir()
    folders = [root, path] if Path(path).is_relative_to(root) else [path]
    for folder in folders:
        check_private(folder)
    return path if all(is_private(folder) for folder in folders) else None
