"""What a bearing law declares (:class:`BearingLaw`) and the signature of its compiled
functions.

A journal law's compiled film function has the signature ::

    film(par, row, tables, ex, ey, vx, vy, spin_journal, spin_bushing) -> (fx, fy, torque)

``par`` the mechanism's parameter array with the bearing's row starting at ``row``
(offsets ``BP_*`` of :mod:`recipsim.physics.mechanics.layout`), ``tables`` the bearing
tables, ``ex, ey`` [m] and ``vx, vy`` [m/s] the journal marker relative to the bushing
marker in the plane normal to the bearing axis, the spins about the axis [rad/s]; it
returns the film force on the journal [N] and the film torque on the journal [N m]. Its
peak-pressure function takes the same arguments and returns [Pa]. The registry adds the
asperity contact, the bushing's torque and the dissipation, the same for every film law.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from recipsim.slots import ModelChoice


@dataclass(frozen=True)
class BearingLaw(ModelChoice):
    """A bearing law: a :class:`~recipsim.slots.ModelChoice` with what the case reader,
    the model builder and the start-up need.

    Attributes
    ----------
    bearings : tuple of str
        The bearings (``layout.BEARING_NAMES``) that may run on it.
    film : bool
        It reads the oil-film keys of ``[bearings.<name>]`` (geometry, clearance, oil,
        contact) and the model writes them into the bearing's row.
    spring : bool
        It reads ``stiffness`` and ``damping`` (required).
    station_pair : bool
        It acts on the piston's two stations together (both name it or neither).
    table : callable or None
        ``table(length_over_diameter) -> numpy.ndarray``: the law's per-bearing table
        (read-only), built once per L/D; None: no table.
    start_stiffness : callable or None
        ``start_stiffness(par, row, speed) -> float`` [N/m]: a stiffness for start poses
        and tolerances; None: 0 (the body starts centred).
    """

    bearings: tuple[str, ...] = ()
    film: bool = True
    spring: bool = False
    station_pair: bool = False
    table: Callable[[float], np.ndarray] | None = None
    start_stiffness: Callable[[np.ndarray, int, float], float] | None = None
