"""The wheel carries everything a user needs: built from the checkout, installed in a fresh
virtual environment (its dependencies from the test environment), it runs the default
case by name from a directory outside the checkout and lists the shipped cases, which
it carries as ``recipsim.shipped_cases`` (the top-level ``cases/``)."""

from __future__ import annotations

import io
import subprocess
import sys
import tomllib
import venv
from pathlib import Path

import pandas as pd
import pytest

from helpers import CASES, ROOT


def test_every_package_of_the_source_tree_is_listed_for_the_wheel():
    """pyproject.toml lists the packages (the shipped data folders are mapped onto
    subpackages): a package added under src/ must be added there too."""
    from setuptools import find_namespace_packages

    with open(ROOT / "pyproject.toml", "rb") as fh:
        tool = tomllib.load(fh)["tool"]["setuptools"]
    listed = set(tool["packages"])
    assert set(find_namespace_packages(str(ROOT / "src"))) <= listed
    mapped = {"recipsim.shipped_cases": "cases", "recipsim.shipped_refrigerants": "refrigerants"}
    for package, folder in mapped.items():
        assert package in listed and tool["package-dir"][package] == folder
        assert (ROOT / folder / "__init__.py").is_file()


@pytest.mark.slow
def test_wheel_runs_the_default_case_by_name_outside_the_checkout(tmp_path):
    wheels = tmp_path / "wheels"
    build = subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(wheels), str(ROOT)],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert build.returncode == 0, build.stderr[-2000:]
    (wheel,) = wheels.glob("recipsim-*.whl")
    env_dir = tmp_path / "venv"
    venv.EnvBuilder(system_site_packages=True, with_pip=True).create(env_dir)
    python = env_dir / "bin" / "python"
    install = subprocess.run(
        [str(python), "-m", "pip", "install", "-q", "--no-deps", str(wheel)],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert install.returncode == 0, install.stderr[-2000:]
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()

    def run(*args: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [str(python), *args], cwd=elsewhere, capture_output=True, text=True, timeout=600
        )

    where = run("-c", "import recipsim; print(recipsim.__file__)")
    assert Path(where.stdout.strip()).is_relative_to(env_dir), where.stdout  # not the checkout
    version = run("-m", "recipsim", "--version")
    assert version.returncode == 0 and version.stdout.startswith("recipsim ")
    out = run("-m", "recipsim", "run", "reference_r134a_lbp", "--no-plots", "--quiet")
    assert out.returncode == 0, out.stderr[-2000:]
    summary = pd.read_csv(elsewhere / "reports" / "reference_r134a_lbp" / "summary.csv")
    assert bool(summary["converged [-]"].iloc[0])
    assert summary["refrigerant"].iloc[0] == "R134a"
    listed = run("-c", "import recipsim; print(recipsim.cases().to_json(orient='records'))")
    assert listed.returncode == 0, listed.stderr[-2000:]
    table = pd.read_json(io.StringIO(listed.stdout))
    shipped = {p.stem for p in CASES.rglob("*.toml")} - {"expectations"}
    assert set(table["name"]) == shipped
    assert all(Path(path).is_relative_to(env_dir) for path in table["path"])
