"""``recipsim calibrate``: the data file, the fit and its refusals (issue 16, item 8).

The fit logic is checked on fake models with closed-form answers (``simulate`` is
injectable: a case in, a summary row out), the whole chain once on the real model: data
made by the model itself with a known suction-valve flow coefficient, which the
calibration must recover from two of three points and then predict the third.
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
from recipsim.studies.calibrate.data import printed_resolution, read_points
from recipsim.studies.calibrate.parameters import CalibrationError, parse_parameter
from recipsim.studies.calibrate.run import _at_bound, calibrate_case

CATALOGUE = Path(__file__).parents[4] / "src/recipsim/data/catalogue/danfoss_tles5.7kk.3_r600a.csv"
FS, FD = "valves.suction.flow_coefficient", "valves.discharge.flow_coefficient"


def _write(path: Path, rows: list[tuple[float, float, float]]) -> Path:
    lines = ["evaporating_temperature [degC],cooling_capacity [W],COP [-]"]
    lines += [f"{te:g},{q:.2f},{cop:.3f}" for te, q, cop in rows]
    path.write_text("\n".join(lines) + "\n")
    return path


def _linear(case: Case) -> dict[str, float]:
    """Capacity proportional to the suction flow coefficient, COP to the discharge one,
    both rising 2 %/K with the evaporating temperature."""
    v, te = case.valves, case.operating_point.evaporating_temperature
    trend = 1.0 + 0.02 * (te - 248.15)
    return {
        "cooling_capacity [W]": 150.0 * v.suction.flow_coefficient * trend,
        "COP [-]": 2.5 * v.discharge.flow_coefficient * trend,
    }


def _linear_data(tmp_path: Path) -> tuple[Case, Path]:
    """The R600a case and the data file of :func:`_linear` at its truth (0.62, 0.71), at
    three evaporating temperatures."""
    case = load_case("r600a_lbp")
    truth = case.with_({FS: 0.62, FD: 0.71})
    rows = []
    for te in (-30, -25, -20):
        row = _linear(truth.with_({"operating_point.evaporating_temperature": f"{te} degC"}))
        rows.append((te, row["cooling_capacity [W]"], row["COP [-]"]))
    return case, _write(tmp_path / "d.csv", rows)


def _product(case: Case) -> dict[str, float]:
    """Only the product of the two coefficients matters: not separately identifiable."""
    v = case.valves
    p = v.suction.flow_coefficient * v.discharge.flow_coefficient
    return {"cooling_capacity [W]": 150.0 * p, "COP [-]": 2.5 * p}


def test_printed_resolution_is_half_the_last_digit() -> None:
    assert printed_resolution("36") == 0.5
    assert printed_resolution("1.02") == pytest.approx(0.005)
    assert printed_resolution("-23.3") == pytest.approx(0.05)
    assert printed_resolution("1.5e3") == pytest.approx(50.0)


@pytest.mark.skipif(
    not CATALOGUE.is_file(), reason="the shared catalogue is not beside the checkout"
)
def test_the_catalogue_reads_as_points() -> None:
    points, targets = read_points(CATALOGUE)
    assert targets == ("cooling_capacity [W]", "COP [-]")
    assert len(points) == 7
    en = points[2]  # EN 12900 rating point: capacity and COP
    assert en.overrides["operating_point.standard"] == "EN12900"
    assert en.overrides["operating_point.evaporating_temperature"] == "-25 degC"
    assert en.targets == {"cooling_capacity [W]": 68.0, "COP [-]": 1.02}
    assert en.resolution == {"cooling_capacity [W]": 0.5, "COP [-]": pytest.approx(0.005)}
    assert "COP [-]" not in points[0].targets  # empty cell: not measured
    assert points[6].targets["COP [-]"] == 1.32


def test_bad_data_files_name_the_column_and_row(tmp_path: Path) -> None:
    bad = tmp_path / "bad.csv"
    bad.write_text("evaporating_temperature,cooling_capacity [W]\n-25,68\n")
    with pytest.raises(CaseError, match=r"evaporating_temperature: an input column is named"):
        read_points(bad)
    bad.write_text("evaporating_temperature [degC],cooling_capacity [W]\n-25,zero\n")
    with pytest.raises(CaseError, match=r"row 1, cooling_capacity \[W\]: 'zero' is not a number"):
        read_points(bad)
    with pytest.raises(CaseError, match=r"COP \[-\]: no such column"):
        read_points(bad, targets=["COP [-]"])


def test_two_parameters_recovered_with_their_confidence(tmp_path: Path) -> None:
    """Fake linear model, truth (0.62, 0.71), data printed to 0.01 W and 0.001 (COP
    1.7-2.0): the fit returns the truth within the rounding's effect (3e-4 relative: 1e-3
    asserted); the standard deviation from the data's resolution is the closed form of
    this model, ``1 / sqrt(sum((1 + r_i) / sigma_i)^2)`` per parameter (each parameter
    scales one target, ``sigma_i`` = half the last digit / sqrt 3 / measured), to the
    forward difference's 0.5 %; the 95 % interval is ``exp(+-1.96 std)`` around it; the
    point left out is predicted within the rounding."""
    case, data = _linear_data(tmp_path)
    cal = calibrate_case(
        case, data, [f"{FS}=0.3:1", f"{FD}=0.3:1"], points=[1, 3], simulate=_linear
    )
    table = cal.parameters.set_index("parameter")
    assert table.loc[FS, "fitted"] == pytest.approx(0.62, rel=1e-3)
    assert table.loc[FD, "fitted"] == pytest.approx(0.71, rel=1e-3)
    used = [r for r in cal.points.itertuples() if r.used_in_fit]
    for key, target, resolution in ((FS, "cooling_capacity [W]", 0.005), (FD, "COP [-]", 5e-4)):
        measured = [
            getattr(r, "_" + str(list(cal.points.columns).index(f"measured {target}") + 1))
            for r in used
        ]
        predicted = [
            getattr(r, "_" + str(list(cal.points.columns).index(f"predicted {target}") + 1))
            for r in used
        ]
        weights = [
            (p / m / (resolution / math.sqrt(3.0) / m)) ** 2
            for p, m in zip(predicted, measured, strict=True)
        ]
        std = 1.0 / math.sqrt(sum(weights))
        assert table.loc[key, "std_from_resolution [-]"] == pytest.approx(std, rel=1e-2)
        fitted, spread = (
            table.loc[key, "fitted"],
            max(
                table.loc[key, "std_from_resolution [-]"], table.loc[key, "std_from_residuals [-]"]
            ),
        )
        assert table.loc[key, "ci95_low"] == pytest.approx(fitted * math.exp(-1.96 * spread))
        assert table.loc[key, "ci95_high"] == pytest.approx(fitted * math.exp(1.96 * spread))
    left_out = cal.points.set_index("row").loc[2]
    assert not left_out["used_in_fit"]
    assert abs(left_out["error cooling_capacity [-]"]) < 1e-3
    assert cal.calibrated.valves.suction.flow_coefficient == pytest.approx(0.62, rel=1e-3)


def test_warnings_of_trials_are_dropped_and_the_calibrated_points_keep_theirs(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    """A model that warns as the valve metrics do (one warning per solve, naming the
    trial's coefficient): nothing is logged during the fit, and each row of the points
    table carries the warning of the calibrated case's own solve at that point."""
    import logging

    def warning_linear(case: Case) -> dict[str, float]:
        logging.getLogger("recipsim.results.valve_metrics").warning(
            "suction coefficient %.4f flows back", case.valves.suction.flow_coefficient
        )
        return _linear(case)

    case, data = _linear_data(tmp_path)
    with caplog.at_level(logging.WARNING, logger="recipsim"):
        cal = calibrate_case(case, data, [f"{FS}=0.3:1", f"{FD}=0.3:1"], simulate=warning_linear)
    assert not [r for r in caplog.records if "flows back" in r.getMessage()]
    fitted = cal.calibrated.valves.suction.flow_coefficient
    assert fitted == pytest.approx(0.62, rel=1e-3)
    assert list(cal.points["warnings"]) == [f"suction coefficient {fitted:.4f} flows back"] * 3


def test_a_parameter_pushed_past_its_bound_is_flagged(tmp_path: Path) -> None:
    """Fake linear model, truth (0.62, 0.71) with the first parameter allowed only up to
    0.5: the fit ends on that bound (to its own xtol, not to machine precision) and says so;
    the other parameter, free, is not flagged."""
    case = load_case("r600a_lbp")
    truth = case.with_({FS: 0.62, FD: 0.71})
    rows = []
    for te in (-30, -20):
        row = _linear(truth.with_({"operating_point.evaporating_temperature": f"{te} degC"}))
        rows.append((te, row["cooling_capacity [W]"], row["COP [-]"]))
    data = _write(tmp_path / "d.csv", rows)
    cal = calibrate_case(case, data, [f"{FS}=0.3:0.5", f"{FD}=0.3:1"], simulate=_linear)
    table = cal.parameters.set_index("parameter")
    assert table.loc[FS, "fitted"] == pytest.approx(0.5, rel=1e-4)
    assert table.loc[FS, "at_bound"]
    assert not table.loc[FD, "at_bound"]


def test_at_bound_uses_the_fits_resolution() -> None:
    """The trust-region fit stops within its xtol (1e-4) of a bound, not on it: the TLES
    case's conductance ended at 9.99999 of its 0.05-10 W/K range and must be flagged; a
    value 0.1 % inside is not; a bound at zero is judged on the range."""
    assert _at_bound(9.999991674184745, 0.05, 10.0)
    assert _at_bound(0.0500001, 0.05, 10.0)
    assert not _at_bound(9.99, 0.05, 10.0)
    assert _at_bound(1e-6, 0.0, 1.0) and not _at_bound(1e-3, 0.0, 1.0)


def test_ill_posed_fits_are_refused(tmp_path: Path) -> None:
    case = load_case("r600a_lbp")
    data = _write(tmp_path / "d.csv", [(-25, 100.0, 1.5), (-20, 120.0, 1.7)])
    with pytest.raises(CalibrationError, match="3 parameters cannot be fitted to 2 measured"):
        calibrate_case(
            case,
            data,
            [f"{FS}=0.3:1", f"{FD}=0.3:1", "geometry.bore=0.01:0.03"],
            points=[1],
            simulate=_linear,
        )
    with pytest.raises(CalibrationError, match=r"heat_transfer.wall_temperature: no influence"):
        calibrate_case(
            case, data, [f"{FS}=0.3:1", "heat_transfer.wall_temperature=300:360"], simulate=_linear
        )
    with pytest.raises(CalibrationError, match=r"not separately identifiable.*flow_coefficient \+"):
        calibrate_case(case, data, [f"{FS}=0.3:1", f"{FD}=0.3:1"], simulate=_product)
    with pytest.raises(CalibrationError, match=r"--points \[5\]"):
        calibrate_case(case, data, [f"{FS}=0.3:1"], points=[5], simulate=_linear)


def test_parameter_bounds_and_start() -> None:
    case = load_case("r600a_lbp")
    p = parse_parameter(FS, case)  # no bounds: a tenth to ten times the case's value
    assert (p.lower, p.initial, p.upper) == pytest.approx((0.08, 0.8, 8.0))
    assert p.logarithmic
    q = parse_parameter("operating_point.shaft_speed=2000 rpm:4000 rpm", case)
    assert q.lower == pytest.approx(2000 * math.pi / 30) and q.upper == pytest.approx(
        4000 * math.pi / 30
    )
    with pytest.raises(CalibrationError, match="lower bound"):
        parse_parameter(f"{FS}=1:0.5", case)
    with pytest.raises(CalibrationError, match="give bounds"):
        parse_parameter("valves.suction.preload", case)


def test_calibration_on_the_model_recovers_a_flow_coefficient(tmp_path: Path) -> None:
    """The real model makes the data (suction flow coefficient 0.6, cycle tolerance 1e-6,
    printed to 0.01 W and 1e-4); ``recipsim calibrate`` fits it on rows 1 and 3 from the
    case's 0.8 within 1e-3, predicts row 2 within 1e-3, and its calibrated case.toml
    loads with the fitted value."""
    base = load_case("r600a_lbp")
    rows = []
    for te in (-25, -20, -15):
        from recipsim.api import simulate

        s = simulate(
            base.with_(
                {
                    "operating_point.evaporating_temperature": f"{te} degC",
                    FS: 0.6,
                    "solver.cycle_tolerance": 1e-6,
                }
            )
        ).summary
        rows.append((te, s["cooling_capacity [W]"], s["COP [-]"]))
    lines = ["evaporating_temperature [degC],cooling_capacity [W],COP [-]"]
    lines += [f"{te},{q:.2f},{cop:.4f}" for te, q, cop in rows]
    data = tmp_path / "d.csv"
    data.write_text("\n".join(lines) + "\n")
    out = tmp_path / "out"
    code = main(
        [
            "calibrate",
            "r600a_lbp",
            str(data),
            "--parameters",
            f"{FS}=0.3:1",
            "--points",
            "1,3",
            "--out",
            str(out),
        ]
    )
    assert code == 0
    result = out / "r600a_lbp"
    params = pd.read_csv(result / "parameters.csv")
    assert params.loc[0, "fitted"] == pytest.approx(0.6, rel=1e-3)
    points = pd.read_csv(result / "points.csv")
    assert points["error cooling_capacity [-]"].abs().max() < 1e-3
    assert points["error COP [-]"].abs().max() < 1e-3
    assert load_case(result / "case.toml").valves.suction.flow_coefficient == pytest.approx(
        0.6, rel=1e-3
    )
    # an ill-posed request is an input error (exit 2), nothing written
    assert (
        main(
            [
                "calibrate",
                "r600a_lbp",
                str(data),
                "--parameters",
                "heat_transfer.wall_temperature=300:360",
                "--out",
                str(tmp_path / "x"),
            ]
        )
        == 2
    )
    assert not (tmp_path / "x").exists()
