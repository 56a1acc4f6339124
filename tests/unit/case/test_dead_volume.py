"""Dead volume as the metal has it: the piston-top gap times the bore area, the ports
through the valve plate and any other recess. A bore change then changes the clearance
ratio (the ports stay), where a clearance ratio would scale with the swept volume.

The suction port lies upstream of its reed (the reed closes it from the cylinder's side),
so only the discharge port is dead volume.

A case (or an override) that gives one of ``clearance_ratio``, ``clearance_volume`` and
``top_clearance`` replaces whichever the case it extends gave; one file giving two is
refused, naming the key.
"""

from __future__ import annotations

import math

import pytest

from recipsim.api import load_case
from recipsim.errors import CaseError

GAP, PLATE, OTHER = 0.1e-3, 2.5e-3, 5e-9


def _dead(bore: float | None = None):
    values = {
        "geometry.top_clearance": f"{GAP * 1e3} mm",
        "geometry.valve_plate_thickness": f"{PLATE * 1e3} mm",
        "geometry.other_dead_volume": OTHER,
    }
    if bore is not None:
        values["geometry.bore"] = f"{bore * 1e3} mm"
    return load_case("tles5.7kk3_r600a", values)


def test_dead_volume_is_gap_ports_and_recesses():
    case = _dead()
    g, v = case.geometry, case.valves
    port = math.pi / 4.0 * v.discharge.port_diameter**2
    expected = GAP * g.piston_area + PLATE * port + OTHER
    assert g.clearance_volume == pytest.approx(expected, rel=1e-14)


def test_a_larger_bore_has_a_smaller_clearance_ratio():
    small, large = _dead(0.020), _dead(0.0265)
    ratio = [c.geometry.clearance_volume / c.geometry.swept_volume for c in (small, large)]
    ports = small.geometry.clearance_volume - GAP * small.geometry.piston_area
    # gap/stroke stays; the ports' (and recesses') share falls with the swept volume
    gap_share = GAP / small.geometry.stroke
    assert ratio[0] - gap_share == pytest.approx(ports / small.geometry.swept_volume, rel=1e-12)
    assert ratio[1] - gap_share == pytest.approx(ports / large.geometry.swept_volume, rel=1e-12)
    assert ratio[1] < ratio[0]


def test_a_clearance_ratio_override_replaces_the_inherited_top_clearance():
    case = load_case(
        "tles5.7kk3_r600a", {"geometry.top_clearance": "0.1 mm", "geometry.clearance_ratio": 0.03}
    )
    g = case.geometry
    assert g.clearance_volume / g.swept_volume == pytest.approx(0.03, rel=1e-12)


def test_two_clearances_in_one_file_are_refused(tmp_path):
    path = tmp_path / "two.toml"
    path.write_text(
        'extends = "tles5.7kk3_r600a"\n[geometry]\nclearance_ratio = 0.02\n'
        'top_clearance = "0.1 mm"\n'
    )
    with pytest.raises(CaseError, match="geometry.clearance_ratio.*exactly one"):
        load_case(str(path))


def test_a_motor_matched_to_a_displacement_scales_with_the_bore():
    """``motor.rated_displacement``: a member with another bore gets the torques (and the
    circuit's rated output) in proportion to its displacement, at the same rated speed."""
    small = load_case("tles5.7kk3_r600a")
    large = load_case("tles5.7kk3_r600a", {"geometry.bore": "26.49 mm"})
    ratio = large.geometry.swept_volume / small.geometry.swept_volume
    assert ratio == pytest.approx(1.754, abs=1e-3)
    assert large.motor.rated_torque == pytest.approx(small.motor.rated_torque * ratio, rel=1e-12)
    assert large.motor.breakdown_torque == pytest.approx(
        small.motor.breakdown_torque * ratio, rel=1e-12
    )
    assert large.motor.rated_speed == small.motor.rated_speed
    # matched to the bore's own displacement: the torques as written
    own = load_case(
        "tles5.7kk3_r600a",
        {"geometry.bore": "26.49 mm", "motor.rated_displacement": large.geometry.swept_volume},
    )
    assert own.motor.rated_torque == pytest.approx(small.motor.rated_torque, rel=1e-6)


def test_a_displacement_gives_the_bore_at_the_cases_stroke():
    """``geometry.displacement`` instead of ``bore``: pi bore^2 stroke / 4 is the
    displacement to round-off, and the case is the one the bore itself gives (a member of
    the family named by its displacement)."""
    by_volume = load_case("tles5.7kk3_r600a", {"geometry.displacement": "10 cm^3"})
    g = by_volume.geometry
    assert g.swept_volume == pytest.approx(10e-6, rel=1e-14)
    assert g.stroke == pytest.approx(18.14e-3, rel=1e-14)  # the stroke is kept
    by_bore = load_case("tles5.7kk3_r600a", {"geometry.bore": g.bore})
    assert by_bore.geometry == g
    assert by_bore.motor.rated_torque == by_volume.motor.rated_torque
    # a bore given afterwards replaces the displacement, as in the case it extends
    again = load_case(
        "tles5.7kk3_r600a", {"geometry.displacement": "10 cm^3", "geometry.bore": 0.02}
    )
    assert again.geometry.bore == 0.02


def test_bore_and_displacement_in_one_file_are_refused(tmp_path):
    path = tmp_path / "both.toml"
    path.write_text(
        'extends = "tles5.7kk3_r600a"\n[geometry]\nbore = "20 mm"\ndisplacement = "5 cm^3"\n'
    )
    with pytest.raises(CaseError, match="geometry.bore.*exactly one of bore and displacement"):
        load_case(str(path))


def test_a_displacement_whose_bore_is_out_of_range_names_the_key():
    with pytest.raises(CaseError, match=r"geometry.displacement.*bore of 1\.6.*outside"):
        load_case("tles5.7kk3_r600a", {"geometry.displacement": "0.04 m^3"})
