"""The reference compressor's mechanism (design notes section 4): its case tables with
units, its slider-crank geometry and its speed."""

from __future__ import annotations

import math
from typing import Any

from recipsim.case.mechanism import mechanism_from_dict
from recipsim.case.mechanism_spec import CrankGeometry, MechanismSpec
from recipsim.physics.mechanics.bearing_laws.registry import DEFAULT_LAW


def reference_mechanism_tables() -> dict[str, Any]:
    """Case tables of the reference compressor (design notes section 4), with units.

    Masses, inertias and damping are engineering estimates; stiffnesses k1, k2, k3, k5,
    k6 are the paper's (Kurka et al., ISMA 2010). Choices made here:

    - piston inertia: solid cylinder 35 g, 22 mm x 20 mm (2.23e-6 kg m^2), centre of
      mass at mid-length, i.e. on the pin axis;
    - piston pin stiffness: 5e7 N/m (stiff; the paper treats the pin as rigid);
    - piston_top / piston_skirt markers at the two Gauss points of the piston length
      (4.23 mm and 15.77 mm below the crown): two springs k/2 there have the same force
      and moment stiffness as a uniform elastic foundation of total stiffness k;
    - damping: about 50 % of critical on the carried mass
      (c = 2 * 0.5 * sqrt(k m), m = 0.45 kg per rotor bearing, 65 g for the eccentric,
      35 g for the pin, 17.5 g for each piston bearing), rounded. With it the viscous
      bearing forces are about a tenth of the elastic ones, as the paper reports for
      its "parametric dissipation" (whose values it does not give). Real oil films
      damp far more (short-bearing squeeze damping is of order 1e5 N s/m);
    - journal film data (diameter, length, 10 um radial clearance) and the ISO VG 10
      oil at 60 C for the hydrodynamic laws; the journals take the default law
      (``options.bearing_law``, linear unless set).
    """
    gauss = 10.0 / math.sqrt(3.0)
    return {
        "mechanism": {
            "piston": {
                "mass": "35 g",
                "length": "20 mm",
                "pin_offset_from_crown": "10 mm",
                "centre_of_mass_from_crown": "10 mm",
                "transverse_inertia": "2.2254e-6 kg*m**2",
            },
            "connecting_rod": {
                "mass": "30 g",
                "centre_of_mass_fraction": 0.35,
                "inertia": "4e-6 kg*m**2",
            },
            "rotor": {
                "mass": "0.90 kg",
                "polar_inertia": "3.5e-4 kg*m**2",
                "transverse_inertia": "7.0e-4 kg*m**2",
                "centre_of_mass_z": "-40 mm",
                "primary_z": "-20 mm",
                "secondary_z": "-52 mm",
            },
        },
        "bearings": {
            "primary": {
                "stiffness": "5.0e7 N/m",
                "damping": "4700 N*s/m",
                **_journal("16 mm", "20 mm"),
            },
            "secondary": {
                "stiffness": "4.0e7 N/m",
                "damping": "4200 N*s/m",
                **_journal("14 mm", "12 mm"),
            },
            "eccentric": {
                "stiffness": "2.5e7 N/m",
                "damping": "1300 N*s/m",
                **_journal("14 mm", "12 mm"),
            },
            "pin": {"stiffness": "5.0e7 N/m", "damping": "1300 N*s/m"},
            "piston_top": {
                "law": DEFAULT_LAW,
                "stiffness": "3.0e7 N/m",
                "damping": "730 N*s/m",
                "position_from_crown": f"{10.0 - gauss:.4f} mm",
            },
            "piston_skirt": {
                "law": DEFAULT_LAW,
                "stiffness": "3.0e7 N/m",
                "damping": "730 N*s/m",
                "position_from_crown": f"{10.0 + gauss:.4f} mm",
            },
        },
        "oil": {"name": "iso_vg10", "film_temperature": "60 degC"},
    }


def _journal(diameter: str, length: str) -> dict[str, str]:
    """Film data of a reference journal (design notes section 4): 10 um radial clearance."""
    return {"diameter": diameter, "length": length, "radial_clearance": "10 um"}


def reference_geometry() -> CrankGeometry:
    """Reference compressor slider-crank: bore 22 mm, stroke 18.4 mm, rod 36 mm."""
    return CrankGeometry.from_stroke(bore=0.022, stroke=0.0184, rod_length=0.036)


def reference_mechanism() -> MechanismSpec:
    """:func:`reference_mechanism_tables` parsed."""
    return mechanism_from_dict(reference_mechanism_tables(), "<reference>")


#: Reference compressor speed, 3500 rpm [rad/s].
REFERENCE_SPEED = 3500.0 * 2.0 * math.pi / 60.0
