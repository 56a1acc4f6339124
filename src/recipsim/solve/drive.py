"""Models whose set-up needs a solve first.

The coupled scene's ``torque_profile`` drive applies the pinned mechanism's driving
torque under the cylinder pressure of the rigid crank (the paper's input to its
flexible run). That pressure is the periodic solution of the case's cylinder scene:
solved here, in the solver layer, and handed to
:func:`recipsim.model.build.build_model`, which never runs the solver itself.
"""

from __future__ import annotations

import math

import numpy as np

from recipsim.case.case import Case
from recipsim.model import scenes
from recipsim.model.build import Model, build_model, cylinder_model
from recipsim.physics.mechanics.drives import DRIVES
from recipsim.physics.thermo.pressure_sources import PRESSURE_SOURCES
from recipsim.solve.periodic import sample_outputs, solve_periodic


def rigid_crank_pressure(case: Case) -> tuple[np.ndarray, np.ndarray]:
    """Cylinder pressure of ``case`` on the rigid crank over its converged revolution.

    Returns
    -------
    angles, pressures : numpy.ndarray
        Crank angle [rad] in [0, 2 pi), increasing; cylinder pressure [Pa].
    """
    model = cylinder_model(case)
    rigid = solve_periodic(model)
    out = sample_outputs(rigid.model, rigid.final)
    named = scenes.OUTPUTS.bundle(out)
    theta = np.mod(named.crank_angle, 2.0 * math.pi)
    order = np.argsort(theta)
    return theta[order], named.cylinder_pressure[order]


def build_model_for(case: Case) -> Model:
    """:func:`~recipsim.model.build.build_model` of ``case``, with the rigid crank's
    pressure solved first where the coupled ``torque_profile`` drive needs it."""
    solves_gas = PRESSURE_SOURCES[case.options.pressure].solves_gas
    needs = solves_gas and DRIVES[case.options.drive].torque_table
    return build_model(case, rigid_crank_pressure(case) if needs else None)
