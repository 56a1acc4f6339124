"""Shared data for the mechanism tests: the reference compressor and a test curve."""

from __future__ import annotations

import math

import numpy as np
import pytest

from recipsim.case.mechanism_spec import CrankGeometry, MechanismSpec
from recipsim.case.reference_mechanism import (
    REFERENCE_SPEED,
    reference_geometry,
    reference_mechanism,
)
from recipsim.physics.mechanics.tabulated import PressureCurve, ideal_cycle_pressure_curve

#: Shell (suction) pressure of the test cases [Pa]: R134a at -23.3 C evaporating.
SHELL_PRESSURE = 1.15e5
#: Test pressure curve smoothing: Gaussian, 5 deg standard deviation. It stands in for
#: the finite valve opening and closing and removes the high harmonics of the ideal
#: cycle's corners (which would otherwise dominate the undamped response).
CURVE_SMOOTHING = math.radians(5.0)


@pytest.fixture(scope="session")
def spec() -> MechanismSpec:
    return reference_mechanism()


@pytest.fixture(scope="session")
def geometry() -> CrankGeometry:
    return reference_geometry()


@pytest.fixture(scope="session")
def omega() -> float:
    return REFERENCE_SPEED


@pytest.fixture(scope="session")
def curve(geometry: CrankGeometry) -> PressureCurve:
    """Ideal R134a LBP cycle 1.15 -> 15 bar, n = 1.1, 2 % clearance, smoothed 5 deg."""
    return ideal_cycle_pressure_curve(
        geometry.crank_radius, geometry.rod_length, smoothing=CURVE_SMOOTHING
    )


@pytest.fixture(scope="session")
def revolution_angles() -> np.ndarray:
    return np.linspace(0.0, 2.0 * math.pi, 360, endpoint=False)


@pytest.fixture(scope="session")
def shell_pressure() -> float:
    return SHELL_PRESSURE
