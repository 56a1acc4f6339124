"""Circuits fitted to nameplates, kept on disk (recipsim.physics.motor_nameplate_cache):
the cached circuit is the fitted one exactly, a damaged or foreign file is fitted again
and replaced, and a process that loads a nameplate case with a warm cache never imports
scipy.optimize (0.25-0.4 s)."""

from __future__ import annotations

import dataclasses
import json
import subprocess
import sys

import pytest

from helpers import REFERENCE
from recipsim.physics import motor_nameplate_cache
from recipsim.physics.motor_nameplate import (
    HOUSEHOLD_COMPRESSOR_NAMEPLATE,
    motor_circuit_from_nameplate,
)
from recipsim.physics.motor_nameplate_cache import nameplate_circuit


@pytest.fixture
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("RECIPSIM_CACHE", str(tmp_path))
    return tmp_path / "motor_circuits"


def _fits(monkeypatch) -> list[object]:
    """Count the fits that nameplate_circuit runs."""
    fits: list[object] = []

    def counted(plate):
        fits.append(plate)
        return motor_circuit_from_nameplate(plate)

    monkeypatch.setattr(motor_nameplate_cache, "motor_circuit_from_nameplate", counted)
    return fits


def test_cached_circuit_is_the_fitted_one(cache, monkeypatch):
    fits = _fits(monkeypatch)
    first = nameplate_circuit(HOUSEHOLD_COMPRESSOR_NAMEPLATE)
    (path,) = cache.iterdir()
    second = nameplate_circuit(HOUSEHOLD_COMPRESSOR_NAMEPLATE)
    assert len(fits) == 1
    assert second == first == motor_circuit_from_nameplate(HOUSEHOLD_COMPRESSOR_NAMEPLATE)
    # another nameplate has its own entry
    other = dataclasses.replace(HOUSEHOLD_COMPRESSOR_NAMEPLATE, rated_output=90.0)
    assert nameplate_circuit(other) != first
    assert len(fits) == 2 and len(list(cache.iterdir())) == 2
    assert path.exists()


@pytest.mark.parametrize(
    "damage",
    [
        lambda d: "not json",
        lambda d: json.dumps({**d, "main_resistance": d["main_resistance"] * 1.01}),
        lambda d: json.dumps({k: v for k, v in d.items() if k != "rotor_resistance"}),
        lambda d: json.dumps({**d, "extra": 1.0}),
        lambda d: json.dumps({**d, "rotor_resistance": "1.0"}),
        lambda d: json.dumps({**d, "variant": "PSC"}),
        lambda d: json.dumps({**d, "magnetising_reactance": float("nan")}),
    ],
    ids=["malformed", "altered", "missing", "extra", "text", "variant", "nan"],
)
def test_a_damaged_file_is_fitted_again_and_replaced(cache, monkeypatch, damage):
    fitted = nameplate_circuit(HOUSEHOLD_COMPRESSOR_NAMEPLATE)
    (path,) = cache.iterdir()
    path.write_text(damage(json.loads(path.read_text())))
    fits = _fits(monkeypatch)
    assert nameplate_circuit(HOUSEHOLD_COMPRESSOR_NAMEPLATE) == fitted
    assert len(fits) == 1
    assert json.loads(path.read_text()) == dataclasses.asdict(fitted)


def test_an_unwritable_cache_only_costs_the_fit(tmp_path, monkeypatch):
    blocked = tmp_path / "file"
    blocked.write_text("")  # the cache directory cannot be made under a file
    monkeypatch.setenv("RECIPSIM_CACHE", str(blocked))
    assert nameplate_circuit(HOUSEHOLD_COMPRESSOR_NAMEPLATE) == motor_circuit_from_nameplate(
        HOUSEHOLD_COMPRESSOR_NAMEPLATE
    )


def test_nameplate_case_loads_without_scipy_optimize():
    """The catalogue case (its motor given by nameplate) with a warm cache: neither the
    case load (the fit) nor the run (the slip at the load's torque) imports
    scipy.optimize."""
    case = REFERENCE.parent / "tles5.7kk3_r600a.toml"
    script = f"""
import json, sys
from recipsim.case.load import load_case
from recipsim.pipeline import simulate_case
simulate_case(load_case({str(case)!r}))
print(json.dumps("scipy.optimize" in sys.modules))
"""
    for _ in range(2):  # the first fills the caches
        out = subprocess.run(
            [sys.executable, "-c", script], capture_output=True, text=True, check=True
        )
    assert json.loads(out.stdout.strip().splitlines()[-1]) is False


def test_an_installation_without_sources_still_caches(cache, monkeypatch):
    """Where a module's source file cannot be read, the key falls back to recipsim's
    version: the circuit is still fitted, cached and read back."""
    from recipsim.physics import motor_circuit

    monkeypatch.setattr(motor_circuit, "__file__", str(cache / "missing.py"))
    motor_nameplate_cache._fit_source_digest.cache_clear()
    try:
        first = nameplate_circuit(HOUSEHOLD_COMPRESSOR_NAMEPLATE)
        assert nameplate_circuit(HOUSEHOLD_COMPRESSOR_NAMEPLATE) == first
        assert len(list(cache.iterdir())) == 1
    finally:
        motor_nameplate_cache._fit_source_digest.cache_clear()
