"""The piston's lubricated skirt: the ``piston_top`` and ``piston_skirt`` stations as one
film over the skirt between them, with its hydrodynamic and contact forces and the
axial friction (:mod:`recipsim.physics.mechanics.skirt`), evaluated by the flexible model
itself (:func:`recipsim.physics.mechanics.bearing_forces.piston_skirt_forces`)."""

from __future__ import annotations

from recipsim.physics.mechanics.bearing_laws.law import FILM_OUTPUTS, BearingLaw, mechanism_output
from recipsim.physics.mechanics.layout import PISTON_STATION_NAMES
from recipsim.slots import Output

CODE = 3

#: The piston film's own report columns, besides each station's film columns: its axial
#: friction force and power over the cycle, the power's time mean in the summary.
PISTON_FILM_OUTPUTS = (
    mechanism_output("piston_friction_force"),
    mechanism_output("piston_friction_power"),
    Output(
        "piston_friction_power",
        "W",
        "time mean of the power of the piston film's axial friction",
        "summary",
    ),
)

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
    outputs=(*FILM_OUTPUTS, *PISTON_FILM_OUTPUTS),
)
