"""``recipsim calibrate``: physical priors (the plausible range a key declares, a verdict
per fitted parameter), several compressors of a family in one fit, and the regressions
of a bound at zero and of a catalogue named by its file name.

Fake models with closed-form answers (``simulate`` is injectable); one cheap run of the
real model through the command line (one parameter, one point fitted).
"""

from __future__ import annotations

import math
from pathlib import Path

import pandas as pd
import pytest

from recipsim.case.case import Case
from recipsim.case.load import load_case
from recipsim.cli.main import main
from recipsim.errors import CaseError
from recipsim.studies.calibrate.data import find_data_file, read_points
from recipsim.studies.calibrate.family import Member, parse_member
from recipsim.studies.calibrate.parameters import CalibrationError, parse_parameter
from recipsim.studies.calibrate.priors import Prior, judged, prior_of, verdict
from recipsim.studies.calibrate.run import calibrate_case

FS, FD = "valves.suction.flow_coefficient", "valves.discharge.flow_coefficient"
FRACTION = "thermal.direct_suction_fraction"


def _write(path: Path, rows: list[tuple[float, float, float]]) -> Path:
    lines = ["evaporating_temperature [degC],cooling_capacity [W],COP [-]"]
    lines += [f"{te:g},{q:.3f},{cop:.4f}" for te, q, cop in rows]
    path.write_text("\n".join(lines) + "\n")
    return path


def _sized(case: Case) -> dict[str, float]:
    """Capacity proportional to the suction flow coefficient and to the bore's area, COP
    to the discharge coefficient, both rising 2 %/K with the evaporating temperature."""
    v, te = case.valves, case.operating_point.evaporating_temperature
    trend = (1.0 + 0.02 * (te - 248.15)) * (case.geometry.bore / 0.02) ** 2
    return {
        "cooling_capacity [W]": 150.0 * v.suction.flow_coefficient * trend,
        "COP [-]": 2.5 * v.discharge.flow_coefficient * (1.0 + 0.02 * (te - 248.15)),
    }


def _data(tmp_path: Path, name: str, truth: Case, model=_sized) -> Path:
    rows = []
    for te in (-30, -20):
        row = model(truth.with_({"operating_point.evaporating_temperature": f"{te} degC"}))
        rows.append((te, row["cooling_capacity [W]"], row["COP [-]"]))
    return _write(tmp_path / name, rows)


def test_declared_ranges_and_their_conditions() -> None:
    """A key with a range gives it with its source; a correlation's constant only under
    its own correlation; a geometry key declares none."""
    tles = load_case("tles5.7kk3_r600a")
    efficiency = prior_of(tles, "motor.rated_efficiency")
    assert efficiency is not None and efficiency.lower < 0.72 < efficiency.upper
    assert "EPA" in efficiency.source
    conductance = prior_of(tles, "thermal.ua_motor_oil")
    assert conductance is not None
    assert (conductance.lower, conductance.upper) == pytest.approx((0.15, 1.5))
    assert prior_of(tles, "heat_transfer.coefficient") is not None  # annand
    adair = tles.with_({"options.heat_transfer": "adair"})
    assert prior_of(adair, "heat_transfer.coefficient") is None
    assert prior_of(tles, "geometry.bore") is None


def test_verdicts_name_each_fault() -> None:
    prior = Prior(0.5, 10.0, "a source")
    assert verdict(2.0, (1.5, 3.0), prior).startswith("plausible")
    outside = verdict(60.6, (53.0, 69.0), prior)
    assert judged(outside) and "outside the plausible range 0.5 to 10" in outside
    loose = verdict(34.0, (0.5, 2258.0), prior)  # 3.7 decades
    assert judged(loose) and "spans 3.7 decades" in loose
    assert "reaches zero" in verdict(0.4, (-0.27, 1.07), None)
    assert verdict(0.4, (0.3, 0.5), None) == "no range: no plausible range declared"
    assert judged(verdict(0.5, (0.0, math.inf), prior, at_bound=True))


def test_a_fit_outside_its_plausible_range_is_reported(tmp_path: Path) -> None:
    """Truth 0.4 for the suction flow coefficient (plausible 0.5-1.0): the fit returns
    it and its verdict says so in the table and in parameters.csv; the other parameter,
    at 0.71, is plausible."""
    case = load_case("r600a_lbp")
    data = _data(tmp_path, "d.csv", case.with_({FS: 0.4, FD: 0.71}))
    cal = calibrate_case(case, data, [f"{FS}=0.2:1", f"{FD}=0.3:1"], simulate=_sized)
    table = cal.parameters.set_index("parameter")
    assert table.loc[FS, "fitted"] == pytest.approx(0.4, rel=1e-3)
    assert table.loc[FS, "verdict"].startswith("outside the plausible range 0.5 to 1")
    assert "Ussyk" in table.loc[FS, "plausible_source"]
    assert table.loc[FD, "verdict"].startswith("plausible")
    from recipsim.studies.calibrate.report import write_calibration

    written = pd.read_csv(write_calibration(cal, tmp_path / "out") / "parameters.csv")
    assert written.set_index("parameter").loc[FS, "verdict"].startswith("outside")


def test_a_family_shares_its_parameters_across_members(tmp_path: Path) -> None:
    """Two members, 20 mm and 26.49 mm bores, data from the same truth (0.62, 0.71): the
    fit stacks both members' points and recovers the truth; the member given by bore and
    the member given by its own case (the same bore set in it) agree; the points table
    names each point's member."""
    case = load_case("r600a_lbp")
    truth = {FS: 0.62, FD: 0.71}
    small = _data(tmp_path, "small.csv", case.with_(truth))
    large = _data(tmp_path, "large.csv", case.with_({**truth, "geometry.bore": "26.49 mm"}))
    parameters = [f"{FS}=0.3:1", f"{FD}=0.3:1"]
    cal = calibrate_case(
        case, small, parameters, members=[f"{large}:bore=26.49mm"], simulate=_sized
    )
    fitted = cal.parameters.set_index("parameter")["fitted"]
    assert fitted[FS] == pytest.approx(0.62, rel=1e-3)
    assert fitted[FD] == pytest.approx(0.71, rel=1e-3)
    assert list(cal.points["member"]) == ["small", "small", "large", "large"]
    assert cal.points["error cooling_capacity [-]"].abs().max() < 1e-3
    assert cal.fit.residuals and len(cal.fit.residuals) == 8  # 2 targets x 2 points x 2
    large_case = tmp_path / "large_case.toml"
    large_case.write_text('extends = "r600a_lbp"\n[geometry]\nbore = "26.49 mm"\n')
    by_case = calibrate_case(
        case, small, parameters, members=[Member(large, case=large_case)], simulate=_sized
    )
    assert by_case.parameters["fitted"].tolist() == pytest.approx(fitted.tolist(), rel=1e-6)
    # the member named by its displacement at the family's stroke: the same bore
    stroke = case.geometry.stroke
    volume = math.pi / 4.0 * 0.02649**2 * stroke
    by_volume = calibrate_case(
        case,
        small,
        parameters,
        members=[f"{large}:displacement={volume * 1e6!r}cm^3"],
        simulate=_sized,
    )
    assert by_volume.parameters["fitted"].tolist() == pytest.approx(fitted.tolist(), rel=1e-9)


def test_member_options_are_checked() -> None:
    assert parse_member("a.csv:bore=26.49mm:points=3,7") == Member("a.csv", None, "26.49mm", (3, 7))
    assert parse_member("a.csv:displacement=10cm^3") == Member("a.csv", displacement="10cm^3")
    with pytest.raises(CaseError, match="expected one of case, bore, displacement, points"):
        parse_member("a.csv:bore26")
    with pytest.raises(CaseError, match="bore or displacement, not both"):
        parse_member("a.csv:bore=26mm:displacement=10cm^3")
    with pytest.raises(CaseError, match="bore or displacement, not both"):
        Member("a.csv", bore="26mm", displacement="10cm^3")  # from Python too
    with pytest.raises(CaseError, match="row numbers"):
        parse_member("a.csv:points=three")


def test_a_zero_lower_bound_fits_inside_and_never_runs_past_the_upper(tmp_path: Path) -> None:
    """A fraction bounded 0:1 (the direct-suction fraction: the case refuses 1.01): with
    the truth at 0.3 the fit recovers it; with data that want more than 1 it ends on 1,
    flagged, and no trial (the Jacobian's steps included) leaves 0..1."""
    case = load_case("r600a_lbp")
    tried: list[float] = []

    def by_fraction(c: Case) -> dict[str, float]:
        tried.append(c.thermal.direct_suction_fraction)
        return {"cooling_capacity [W]": 100.0 * (1.0 + 0.5 * c.thermal.direct_suction_fraction)}

    data = tmp_path / "d.csv"
    data.write_text("evaporating_temperature [degC],cooling_capacity [W]\n-25,115.00\n")
    cal = calibrate_case(case, data, [f"{FRACTION}=0:1"], simulate=by_fraction)
    assert cal.parameters.loc[0, "fitted"] == pytest.approx(0.3, abs=1e-4)
    data.write_text("evaporating_temperature [degC],cooling_capacity [W]\n-25,160.00\n")
    tried.clear()
    cal = calibrate_case(case, data, [f"{FRACTION}=0:1"], simulate=by_fraction)
    assert cal.parameters.loc[0, "at_bound"]
    assert cal.parameters.loc[0, "verdict"].startswith("at a bound")
    assert 0.0 <= min(tried) and max(tried) <= 1.0


def test_a_parameter_that_stops_acting_near_its_bound_is_reported(tmp_path) -> None:
    """A loss coefficient whose effect vanishes towards its floor (capacity 100 (1 - 0.01
    K)), the data asking for no loss at all: the fit runs down to the lower bound 0.05,
    where a 1 % step moves nothing by 1e-5 (the fit stops within 1 % of the bound: the
    gradient vanishes there); it is reported with an unbounded interval, not refused as
    'no influence' after the whole fit."""
    case = load_case("reference_r134a_lbp_ideal")  # no muffler loss: the fit starts mid-range
    key = "thermal.suction_muffler_loss_coefficient"

    def lossy(c: Case) -> dict[str, float]:
        return {
            "cooling_capacity [W]": 100.0
            * (1.0 - 0.01 * c.thermal.suction_muffler_loss_coefficient)
        }

    data = tmp_path / "d.csv"
    data.write_text("evaporating_temperature [degC],cooling_capacity [W]\n-25,100.00\n")
    cal = calibrate_case(case, data, [f"{key}=0.05:200"], simulate=lossy)
    row = cal.parameters.iloc[0]
    assert row["fitted"] == pytest.approx(0.05, rel=0.01)
    assert math.isinf(row["ci95_high"]) and judged(row["verdict"])
    assert "the 95 % interval reaches zero" in row["verdict"]


def test_bounds_beyond_the_allowed_range_are_refused_and_an_open_end_is_kept() -> None:
    case = load_case("r600a_lbp")
    with pytest.raises(CalibrationError, match=r"reach beyond the allowed \[0, 1\]"):
        parse_parameter(f"{FRACTION}=0:1.5", case)
    assert parse_parameter("leakage.radial_clearance=0:20e-6", case).lower == 0.0


def test_a_shipped_catalogue_is_found_by_its_file_name(tmp_path, monkeypatch) -> None:
    monkeypatch.chdir(tmp_path)
    points, _ = read_points("danfoss_tles10kk.3_r600a.csv")
    assert len(points) == 7 and points[2].targets["COP [-]"] == 0.98
    assert find_data_file("danfoss_tles5.7kk.3_r600a").name == "danfoss_tles5.7kk.3_r600a.csv"
    with pytest.raises(CaseError, match="did you mean 'danfoss_tles5.7kk.3_r600a.csv'"):
        find_data_file("danfoss_tles5.7kk3_r600a.csv")


def test_the_command_with_a_catalogue_name_runs_from_any_directory(
    tmp_path, monkeypatch, capsys
) -> None:
    """The TLES case's calibration command names its catalogue by file name: it runs from
    a directory without that file (one parameter on one rating point, cheap), prints the
    verdict, and a mistyped name is one line with exit status 2."""
    monkeypatch.chdir(tmp_path)
    args = ["calibrate", "tles5.7kk3_r600a"]
    fit = ["--parameters", "motor.rated_efficiency=0.5:0.9", "--points", "3", "--out", "out"]
    assert main([*args, "danfoss_tles5.7kk.3_r600a.csv", *fit]) == 0
    assert "motor.rated_efficiency = 0.7" in capsys.readouterr().out
    points = pd.read_csv(tmp_path / "out/tles5.7kk3_r600a/points.csv")
    assert len(points) == 7 and set(points["member"]) == {"danfoss_tles5.7kk.3_r600a"}
    assert main([*args, "danfoss_tles5.7kk3_r600a.csv", *fit]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "no such calibration data file" in err


def test_a_point_failing_a_step_away_is_stepped_the_other_way() -> None:
    """A run that fails a 1 % step forward (a refused value, a stalled solve: the residual
    FAILED_RESIDUAL) must not enter the Jacobian as a slope of 1000: the column is taken
    backward instead, and where both sides fail the fit stops with a message."""
    import numpy as np

    from recipsim.studies.calibrate.fit import FAILED_RESIDUAL, STEP, forward_jacobian
    from recipsim.studies.calibrate.parameters import CalibrationError

    def f(x: np.ndarray) -> np.ndarray:  # slope 2 in x; fails beyond x = 0.5
        return np.array([FAILED_RESIDUAL if x[0] > 0.5 else 2.0 * x[0]])

    jac = forward_jacobian(f, np.array([0.5]))
    assert jac[0, 0] == pytest.approx(2.0, rel=1e-9)

    def g(x: np.ndarray) -> np.ndarray:  # fails on both sides of 0.5
        return np.array([FAILED_RESIDUAL if abs(x[0] - 0.5) > 0.1 * STEP else 0.0])

    with pytest.raises(CalibrationError, match="fails a 1% step"):
        forward_jacobian(g, np.array([0.5]))


def test_a_failing_step_names_the_parameter_the_point_and_the_reason() -> None:
    """A linear parameter at its lower bound (0) whose forward step fails: the backward
    step would leave the bounds (a negative volume the case refuses), so it is not tried,
    and the error names the parameter, the point that failed and the solver's reason."""
    import numpy as np

    from recipsim.errors import RecipsimError
    from recipsim.studies.calibrate.data import MeasuredPoint
    from recipsim.studies.calibrate.fit import Residuals, forward_jacobian
    from recipsim.studies.calibrate.parameters import CalibrationError, Parameter

    key = "geometry.other_dead_volume"
    parameter = Parameter(key, 0.0, 1e-7, 0.0)
    tried: list[float] = []

    def simulate(case: Case) -> dict[str, float]:  # fails above 0.5e-9 m3
        volume = case.raw["geometry"]["other_dead_volume"]
        tried.append(volume)
        if volume > 0.5e-9:
            raise RecipsimError("not converged after 400 revolutions")
        return {"cooling_capacity [W]": 100.0}

    point = MeasuredPoint(1, "EN12900 -25degC", targets={"cooling_capacity [W]": 100.0},
                          resolution={"cooling_capacity [W]": 0.5})  # fmt: skip
    case = load_case("reference_r134a_lbp")
    f = Residuals(case, [point], ["cooling_capacity [W]"], [parameter], simulate)
    with pytest.raises(CalibrationError) as caught:
        forward_jacobian(f, np.array([0.0]), np.array([1.0]), [key], np.array([0.0]))
    message = str(caught.value)
    assert key in message and "EN12900 -25degC" in message
    assert "not converged after 400 revolutions" in message and "its bound" in message
    assert min(tried) >= 0.0  # no run below the lower bound


def test_an_unconverged_point_says_how_far_it_got() -> None:
    """A calibration run that ends unconverged (here: one revolution allowed) is refused
    with its residual, its revolutions and the tolerance, not a bare "not converged"."""
    from recipsim.errors import RecipsimError
    from recipsim.studies.calibrate.run import _summary_row

    case = load_case(
        "reference_r134a_lbp", {"solver.max_revolutions": 1, "solver.min_revolutions": 1}
    )
    with pytest.raises(RecipsimError, match=r"cycle residual .* after 1 revolutions .*tolerance"):
        _summary_row(case)
