"""The outputs at a converged revolution's samples: the rigid crank's cylinder block
alone is the same as the first columns of every output, and only that scene may ask
for it (the others' right-hand sides fill the mechanism's block too)."""

from __future__ import annotations

import numpy as np
import pytest

from helpers import CASES, REFERENCE, solve_case
from recipsim.model import scenes
from recipsim.solve.periodic import sample_outputs


def test_the_cylinder_block_alone_is_the_full_outputs_first_columns():
    sol = solve_case(REFERENCE)
    assert sol.model.scene == scenes.SCENE_CYLINDER
    full = sample_outputs(sol.model, sol.final)
    block = sample_outputs(sol.model, sol.final, cylinder_only=True)
    assert full.shape[1] == scenes.N_AUX and block.shape == (full.shape[0], scenes.A_MECH)
    np.testing.assert_array_equal(block, full[:, : scenes.A_MECH])


def test_only_the_rigid_crank_may_ask_for_the_cylinder_block():
    sol = solve_case(CASES / "paper_tabulated.toml")
    assert sol.model.scene != scenes.SCENE_CYLINDER
    with pytest.raises(ValueError, match="rigid crank"):
        sample_outputs(sol.model, sol.final, cylinder_only=True)
