"""The integrator's numba cache is kept per digest of what it is compiled from: a change
to a physics kernel leaves it valid (the scenes' functions reach it through pointers),
a change to a layout whose sizes it allocates does not."""

from __future__ import annotations

import ast
import re
import shutil
from pathlib import Path

import pytest

from recipsim import cache_dirs

PACKAGE = Path(cache_dirs.__file__).resolve().parent


def _covered(module: str) -> bool:
    """Whether ``recipsim.<module path>`` is a file or inside a folder of SOLVER_SOURCES."""
    relative = Path(*module.split(".")[1:])
    for entry in cache_dirs.SOLVER_SOURCES:
        if relative.with_suffix(".py").as_posix() == entry or relative.is_relative_to(entry):
            return True
    return False


def test_every_module_the_compiled_solver_imports_is_in_its_digest() -> None:
    """Each recipsim module that a compiled module of ``solve/`` (one with numba
    functions) imports from, or whose constants it could compile in, is a source of the
    integrator's cache digest; a missing one would leave a stale integrator reading
    wrong layout sizes."""
    decorated = re.compile(r"^\s*@(njit|overload|intrinsic)\b", re.MULTILINE)
    folder = PACKAGE / cache_dirs.SOLVER_FOLDER
    compiled = [f for f in folder.glob("*.py") if decorated.search(f.read_text())]
    assert compiled
    imported = set()
    for file in compiled:
        for node in ast.walk(ast.parse(file.read_text())):
            if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("recipsim."):
                imported.add(node.module)
    outside = {m for m in imported if not _covered(m)}
    assert not outside, f"compiled solve/ modules import {sorted(outside)}: add to SOLVER_SOURCES"


@pytest.fixture
def package_copy(tmp_path, monkeypatch):
    """A copy of the package's compiled sources that the digests read."""
    copy = tmp_path / "recipsim"
    for entry in ("physics", "model", "solve", "studies/bench"):
        shutil.copytree(PACKAGE / entry, copy / entry, ignore=shutil.ignore_patterns("__pycache__"))
    monkeypatch.setattr(cache_dirs, "_PACKAGE", copy)
    cache_dirs.compiled_sources_digest.cache_clear()
    yield copy
    cache_dirs.compiled_sources_digest.cache_clear()


def _digests() -> tuple[str, str]:
    cache_dirs.compiled_sources_digest.cache_clear()
    return (
        cache_dirs.compiled_sources_digest(),
        cache_dirs.compiled_sources_digest(cache_dirs.SOLVER_SOURCES),
    )


def test_a_physics_kernel_change_leaves_the_integrators_cache(package_copy) -> None:
    full, solver = _digests()
    kernel = package_copy / "physics" / "thermo" / "cylinder_rhs.py"
    kernel.write_text(kernel.read_text() + "\n# changed\n")
    changed_full, changed_solver = _digests()
    assert changed_full != full  # the scenes' functions compile again
    assert changed_solver == solver  # the integrator does not


@pytest.mark.parametrize(
    "source",
    [
        "physics/thermo/cylinder.py",
        "physics/mechanics/layout.py",
        "model/scenes.py",
        "solve/dopri5.py",
    ],
)
def test_a_layout_or_solver_change_renews_the_integrators_cache(package_copy, source) -> None:
    _, solver = _digests()
    path = package_copy / source
    path.write_text(path.read_text() + "\n# changed\n")
    assert _digests()[1] != solver


def test_the_solver_has_a_cache_directory_of_its_own(monkeypatch, tmp_path) -> None:
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    solver, other = cache_dirs.numba_cache_path(solver=True), cache_dirs.numba_cache_path()
    assert solver.parent == other.parent == tmp_path
    assert solver.name.startswith("recipsim-solver-") and solver != other
