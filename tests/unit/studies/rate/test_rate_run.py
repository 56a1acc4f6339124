"""``recipsim rate`` end to end on a cheap case (the ideal machine with R600a: the rigid
crank, no motor model):
one rating of 20 points shared by the tests (a module-scoped fixture), whose evaporating
5 C column lies outside R600a's envelope (0 C at most): those four points fail, are
reported and are left out of the fit. The catalogue of the TLES5.7KK.3 runs beside it (a
different compressor: only the agreement of the polynomial with the model is checked).
Later runs share the points on disk and compute nothing new.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import recipsim
from recipsim.cli.main import main
from recipsim.errors import CaseError
from recipsim.studies.rate.grid import rating_grid
from recipsim.studies.rate.polynomial import RatingError
from recipsim.studies.rate.run import rate_case
from recipsim.studies.rate.tables import GRID_TOLERANCE

CATALOGUE = Path(__file__).parents[4] / "src/recipsim/data/catalogue/danfoss_tles5.7kk.3_r600a.csv"
EVAPORATING = [-30.0, -25.0, -20.0, -15.0, 5.0]  # degC; 5 C is outside the envelope
CONDENSING = "35:65:10"


@pytest.fixture(scope="module")
def out(tmp_path_factory):
    folder = tmp_path_factory.mktemp("rate")
    # an R600a compressor without a motor model: the ideal machine, rated at EN 12900
    (folder / "r600a_ideal.toml").write_text(
        'extends = "reference_r134a_lbp_ideal"\nrefrigerant = "R600a"\n'
    )
    return folder


@pytest.fixture(scope="module")
def rating(out):
    case = recipsim.load_case(str(out / "r600a_ideal.toml"))
    return recipsim.rate(
        case,
        standard="EN12900",
        evaporating=EVAPORATING,
        condensing=CONDENSING,
        catalogue=CATALOGUE,
        directory=out,
        progress=False,
    )


def test_failed_points_are_reported_and_left_out_of_the_fit(rating):
    table = rating.ratings
    failed = table[table["evaporating_temperature [degC]"] == 5.0]
    assert len(table) == 20 and len(failed) == 4
    assert set(failed["status"]) == {"outside_envelope"}
    assert failed["message"].str.contains("envelope").all()
    assert failed["cooling_capacity_polynomial [W]"].isna().all()  # not fitted, not filled
    assert any("4 of 20 points failed" in note for note in rating.notes)
    row = rating.coefficients.set_index("quantity").loc["cooling_capacity"]
    assert row["points"] == 16
    # the range of validity is the good points', not the grid's
    bounds = (row["S_min"], row["S_max"], row["D_min"], row["D_max"])
    assert bounds == pytest.approx((-30.0, -15.0, 35.0, 65.0), abs=1e-6)


def test_the_polynomial_reproduces_its_own_grid(rating):
    # a smooth map of a pure refrigerant: the cubic fits it within the 1 % the rating
    # promises (and says where, otherwise)
    residuals = rating.residuals.set_index("quantity")
    for quantity in ("cooling_capacity", "power_input", "mass_flow"):
        assert residuals.loc[quantity, "max_rel [-]"] <= GRID_TOLERANCE, quantity
    ok = rating.ratings[rating.ratings["status"] == "ok"]
    for quantity in ("cooling_capacity", "power_input"):
        relative = ok[f"{quantity}_residual [-]"].abs().max()
        assert relative == pytest.approx(residuals.loc[quantity, "max_rel [-]"], rel=1e-9)


def test_dew_points_of_a_pure_refrigerant_are_the_grid(rating):
    ok = rating.ratings[rating.ratings["status"] == "ok"]
    for nominal, dew in (("evaporating", "suction_dew"), ("condensing", "discharge_dew")):
        difference = ok[f"{nominal}_temperature [degC]"] - ok[f"{dew}_temperature [degC]"]
        assert difference.abs().max() < 1e-6  # CoolProp's saturation solve, both ways


def test_the_written_coefficients_read_back_to_the_fit(rating, out):
    directory = out / "r600a_ideal_EN12900"
    polynomials = recipsim.read_coefficients(directory / "coefficients.csv")
    ok = rating.ratings[rating.ratings["status"] == "ok"]
    t_evap = ok["suction_dew_temperature [degC]"].to_numpy() + 273.15
    t_cond = ok["discharge_dew_temperature [degC]"].to_numpy() + 273.15
    columns = {"cooling_capacity": "cooling_capacity_polynomial [W]"}
    columns["mass_flow"] = "mass_flow_polynomial [kg/h]"
    for quantity, unit_si in (("cooling_capacity", 1.0), ("mass_flow", 3600.0)):
        column = columns[quantity]
        evaluated = polynomials[quantity].si(t_evap, t_cond) * unit_si
        assert evaluated == pytest.approx(ok[column].to_numpy(), rel=1e-12)
        assert rating.evaluate(quantity, t_evap, t_cond) * unit_si == pytest.approx(evaluated)
    for name in ("ratings.csv", "rating_table.csv", "residuals.csv", "catalogue.csv"):
        assert len(pd.read_csv(directory / name)) > 0, name


def test_without_a_motor_model_current_is_left_out_and_power_is_shaft_power(rating):
    rows = rating.coefficients.set_index("quantity")
    assert rows.loc["current", ["C1", "C10"]].isna().all()
    assert "no motor model" in rows.loc["current", "note"]
    assert rows.loc["power_input", "source"] == "shaft_power [W]"
    assert "current [A]" not in rating.ratings
    assert "current" not in rating.polynomials


def test_catalogue_points_inside_the_range_get_the_polynomial(rating):
    table = rating.catalogue
    inside = table[table["polynomial"].notna()]
    # the catalogue's points at 55 C from -30 to -15 C lie inside the fitted range
    assert set(inside["row"]) == {2, 3, 4, 5}
    capacity = inside[inside["quantity"] == "cooling_capacity"]
    grid = rating.ratings.set_index(
        ["evaporating_temperature [degC]", "condensing_temperature [degC]"]
    )
    for _, row in capacity.iterrows():
        point = grid.loc[(round(row["evaporating_temperature [K]"] - 273.15, 6), 55.0)]
        # the same conditions, given as the standard alone or with the catalogue's explicit
        # suction-gas, liquid and ambient temperatures: the same point, to round-off
        assert row["model"] == pytest.approx(point["cooling_capacity [W]"], rel=1e-9)
        # so the polynomial there misses the model by the fit's residual at that point
        assert (row["polynomial"] - row["model"]) / row["model"] == pytest.approx(
            point["cooling_capacity_residual [-]"], abs=1e-9
        )
    outside = table[table["polynomial"].isna()]
    assert set(outside["row"]) == {1, 6, 7}  # -35 C, -10 C: outside; 7: ASHRAE LBP
    assert outside["note"].str.len().min() > 0
    ashrae = table[table["row"] == 7]
    assert ashrae["model"].notna().all()  # run at its own standard
    assert ashrae["note"].str.contains("ASHRAE_LBP").all()


def test_fewer_than_ten_good_points_are_refused(rating, out):
    case = recipsim.load_case(str(out / "r600a_ideal.toml"))
    directory = out / "r600a_ideal_EN12900"
    with pytest.raises(RatingError, match="8 good points.*8 ok, 4 outside_envelope"):
        # 12 points, four outside the envelope: the same points, taken from disk
        rate_case(case, directory, standard="EN12900", evaporating=[-30.0, -20.0, 5.0],
                  condensing=CONDENSING, sweep_options={"progress": False, "jobs": 1})  # fmt: skip


def test_the_command_resumes_from_the_points_on_disk(rating, out, capsys):
    argv = ["rate", str(out / "r600a_ideal.toml"), "--standard", "EN12900",
            "--evaporating=-30,-25,-20,-15,5", f"--condensing={CONDENSING}", "--out", str(out),
            "-j", "1", "--no-plots"]  # fmt: skip
    assert main(argv) == 0
    printed = capsys.readouterr().out
    assert "fit residuals" in printed and "4 of 20 points failed" in printed
    directory = out / "r600a_ideal_EN12900"
    provenance = json.loads((directory / "points" / "provenance.json").read_text())
    assert provenance["computed"] == 0 and provenance["reused"] == 20
    meta = json.loads((directory / "rating.json").read_text())
    assert meta["standard"] == "EN12900" and meta["status_counts"]["outside_envelope"] == 4


def test_a_case_the_standard_contradicts_is_refused_before_any_point_runs(tmp_path):
    case = recipsim.load_case("r600a_lbp", {"operating_point.suction_temperature": "20 degC"})
    with pytest.raises(CaseError, match="suction_temperature"):
        rate_case(case, tmp_path / "r", standard="EN12900", sweep_options={"progress": False})
    assert not (tmp_path / "r" / "points").exists()


def test_the_default_grid_is_the_applications_inside_the_envelope():
    tles = recipsim.load_case("tles5.7kk3_r600a")
    grid = rating_grid(tles)
    assert (grid.standard, grid.temperature_unit, grid.application) == ("EN12900", "degC", "LBP")
    assert grid.evaporating == (-35.0, -30.0, -25.0, -20.0, -15.0, -10.0)
    assert grid.condensing == (35.0, 45.0, 55.0, 65.0)
    ahri = rating_grid(tles, "AHRI_540")
    assert ahri.temperature_unit == "degF" and len(ahri.condensing) >= 4
    kelvin = (np.array(ahri.condensing) - 32.0) / 1.8 + 273.15
    envelope = tles.refrigerant.envelope
    assert kelvin.min() >= envelope["condensing_temperature_min"]
    assert kelvin.max() <= envelope["condensing_temperature_max"]


def test_a_makers_coefficients_are_compared_with_the_model(rating, out, tmp_path):
    # the rating's own coefficients as the maker's: they differ from the model by the
    # fit's residuals, point by point
    maker = tmp_path / "maker.csv"
    maker.write_bytes((out / "r600a_ideal_EN12900" / "coefficients.csv").read_bytes())
    case = recipsim.load_case(str(out / "r600a_ideal.toml"))
    again = rate_case(case, out / "r600a_ideal_EN12900", standard="EN12900",
                      evaporating=EVAPORATING, condensing=CONDENSING, coefficients=maker,
                      sweep_options={"progress": False, "jobs": 1})  # fmt: skip
    capacity = again.maker[again.maker["quantity"] == "cooling_capacity"]
    residual = again.ratings["cooling_capacity_residual [-]"].dropna().to_numpy()
    # difference = (model - maker) / maker = -r / (1 + r) for a residual r = fit / model - 1
    assert capacity["difference [-]"].to_numpy() == pytest.approx(
        -residual / (1.0 + residual), abs=1e-9
    )
    assert set(again.maker["quantity"]) == {"cooling_capacity", "power_input", "mass_flow"}


def test_a_case_without_a_standard_is_rated_at_its_rating_points_standard():
    lbp = rating_grid(recipsim.load_case("r600a_lbp"))  # rating_point = "ashrae_lbp"
    assert (lbp.standard, lbp.temperature_unit, lbp.application) == ("ASHRAE_LBP", "degF", "LBP")
    ac = rating_grid(recipsim.load_case("r32_ac"))  # rating_point = "ahri_ac"
    assert (ac.standard, ac.temperature_unit, ac.application) == ("AHRI_540", "degF", "HBP")
