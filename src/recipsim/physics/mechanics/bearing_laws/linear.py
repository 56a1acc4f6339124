"""The linear bearing law: an isotropic spring and dashpot, ``F = -k e - c de/dt``
normal to the bearing axis (the paper's visco-elastic bearings)."""

from __future__ import annotations

import numpy as np
from numba import njit

from recipsim.physics.mechanics.bearing_laws.law import BearingLaw
from recipsim.physics.mechanics.layout import BEARING_NAMES, BP_DAMPING, BP_STIFFNESS
from recipsim.schema import Described

CODE = 0


def _stiffness(par: np.ndarray, row: int, speed: float) -> float:
    """The law's own stiffness [N/m]."""
    return float(par[row + BP_STIFFNESS])


LAW = BearingLaw(
    name="linear",
    code=CODE,
    summary="isotropic spring and dashpot normal to the bearing axis",
    source="the paper's visco-elastic bearings",
    keys={
        "bearings.<name>": {
            "stiffness": Described(
                "N/m",
                "> 0",
                required="with law = linear",
                doc="isotropic, normal to the bearing axis",
                lo=0.0,
                open_lo=True,
            ),
            "damping": Described(
                "N*s/m",
                ">= 0",
                required="with law = linear",
                doc="viscous, normal to the bearing axis",
                lo=0.0,
            ),
        }
    },  # fmt: skip
    bearings=BEARING_NAMES,
    film=False,
    spring=True,
    start_stiffness=_stiffness,
)


@njit(cache=True)
def linear_load(
    par: np.ndarray, row: int, ex: float, ey: float, vx: float, vy: float
) -> tuple[float, float, float, float, float, float]:
    """Force of the linear law on the journal, as the registry's ``bearing_load``.

    Returns fx, fy [N], the (zero) torques on journal and bushing [N m], the power
    absorbed [W] (including the spring's rate of storage, zero over a period) and the
    (zero) contact force [N].
    """
    k = par[row + BP_STIFFNESS]
    c = par[row + BP_DAMPING]
    fx = -k * ex - c * vx
    fy = -k * ey - c * vy
    return fx, fy, 0.0, 0.0, -(fx * vx + fy * vy), 0.0


@njit(cache=True)
def linear_spring_energy(par: np.ndarray, row: int, ex: float, ey: float) -> float:
    """Elastic energy stored in the spring [J]."""
    return 0.5 * par[row + BP_STIFFNESS] * (ex * ex + ey * ey)
