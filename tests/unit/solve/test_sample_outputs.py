"""The outputs at a converged revolution's samples. On the rigid crank the cycle table
reads them through one compiled call that also sorts them by crank angle and computes
the pinned reactions there (:func:`recipsim.solve.revolution.rigid_cycle`): it must give
what the general route gives, value for value (every output evaluated, sorted by numpy,
the reactions by :func:`recipsim.results.bearings.pinned_columns`)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from helpers import CASES, REFERENCE, solve_case
from recipsim.model import scenes
from recipsim.model.build import case_mechanism_parameters
from recipsim.physics.mechanics.pinned import N_PIN_OUT
from recipsim.physics.thermo import cylinder as cyl
from recipsim.results.bearings import pinned_columns, pinned_reaction_columns
from recipsim.results.cycle import CYLINDER_WIDTH
from recipsim.solve.periodic import sample_outputs
from recipsim.solve.revolution import rigid_cycle

_CRANK_ANGLE = scenes.OUTPUTS.entry("crank_angle").index


@pytest.mark.parametrize("case", [REFERENCE, CASES / "hard" / "soft_suction_reed_flutter.toml"])
def test_the_rigid_cycle_in_one_call_is_the_general_route(case):
    sol = solve_case(case)
    model, rev = sol.model, sol.final
    assert model.scene == scenes.SCENE_CYLINDER
    par = case_mechanism_parameters(model.case)
    angles, rows, modes, reactions = rigid_cycle(model, rev, CYLINDER_WIDTH, par)

    out = sample_outputs(model, rev)  # every output, in time order
    theta = np.mod(out[:, _CRANK_ANGLE], 2.0 * math.pi)
    theta = np.where(theta > 2.0 * math.pi - 1e-9, 0.0, theta)
    order = np.argsort(theta, kind="stable")
    np.testing.assert_array_equal(angles, theta[order])
    assert np.all(np.diff(angles) >= 0.0) and 0.0 <= angles[0] and angles[-1] < 2.0 * math.pi
    np.testing.assert_array_equal(rows, out[order, :CYLINDER_WIDTH].T)
    np.testing.assert_array_equal(modes, rev.sample_modes[order].T)
    assert reactions.shape == (out.shape[0], N_PIN_OUT)

    omega = model.case.operating_point.shaft_speed
    pressure = rows[cyl.A_PRESSURE]
    expected, torque = pinned_columns(angles, pressure, omega, par)
    got, got_torque = pinned_reaction_columns(reactions, omega)
    assert list(got) == list(expected)
    for name, column in expected.items():
        np.testing.assert_array_equal(got[name], column, err_msg=name)
    np.testing.assert_array_equal(got_torque, torque)


def test_only_the_rigid_crank_is_read_in_one_call():
    sol = solve_case(CASES / "paper_tabulated.toml")
    assert sol.model.scene != scenes.SCENE_CYLINDER
    par = case_mechanism_parameters(sol.model.case)
    with pytest.raises(ValueError, match="cylinder's scene"):
        rigid_cycle(sol.model, sol.final, CYLINDER_WIDTH, par)
