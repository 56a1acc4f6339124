"""The piston's lubricated skirt: the ``piston_top`` and ``piston_skirt`` stations as one
film over the skirt between them, with its hydrodynamic and contact forces and the
axial friction (:mod:`recipsim.physics.mechanics.skirt`), evaluated by the flexible model
itself (:func:`recipsim.physics.mechanics.bearing_forces.piston_skirt_forces`)."""

from __future__ import annotations

from recipsim.physics.mechanics.bearing_laws.law import BearingLaw
from recipsim.physics.mechanics.layout import PISTON_STATION_NAMES

CODE = 3

LAW = BearingLaw(
    name="skirt_film",
    code=CODE,
    summary="the piston's two stations as one lubricated skirt: axial Reynolds problems per "
    "circumferential station (wedge, squeeze, tilt), Guembel cavitation, asperity contact, "
    "axial friction",
    source="Reynolds' equation with Guembel cavitation, separated by the long film's "
    "circumferential shape; checked against a 2-D finite-difference Reynolds solution",
    bearings=PISTON_STATION_NAMES,
    station_pair=True,
)
