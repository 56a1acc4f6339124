"""The wheel carries everything a user needs: built from the checkout, installed in a fresh
virtual environment (its dependencies from the test environment), it runs the default
case by name from a directory outside the checkout."""

from __future__ import annotations

import subprocess
import sys
import venv
from pathlib import Path

import pandas as pd
import pytest

from helpers import ROOT


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
