"""The volumetric decomposition of a compressor's capacities
(:mod:`recipsim.studies.calibrate.volumetric`): ``eta_v = 1 - x - (V_d / V) R``.

- ``R`` is the isentropic re-expansion of the dead volume's gas: at the ASHRAE LBP point
  for R600a the density ratio rho_2s / rho_s is 10.8 (the thermo notes' closed-form
  oracle, printed to three digits), so ``R`` = 9.8 within 0.05.
- ``eta_v`` inverts the capacity: a capacity made from an efficiency gives it back.
- The fit recovers a dead volume and losses exactly from exact points, and its 95 %
  interval covers them under noise.
- ``calibrate`` decomposes the catalogue and the calibrated model alike, and writes
  ``volumetric.csv``.
"""

from __future__ import annotations

import math
from pathlib import Path

import CoolProp.CoolProp as CP
import numpy as np
import pandas as pd
import pytest

from recipsim.case.case import Case
from recipsim.case.load import load_case
from recipsim.studies.calibrate.report import write_calibration
from recipsim.studies.calibrate.run import calibrate_case
from recipsim.studies.calibrate.volumetric import (
    decompose,
    fit_volumetric,
    volumetric_point,
)

ASHRAE = {"operating_point.standard": "ASHRAE_LBP"}


def test_the_re_expansion_ratio_is_the_isentropic_density_ratio() -> None:
    case = load_case("tles5.7kk3_r600a", ASHRAE)
    _, ratio = volumetric_point(case, 100.0)
    assert ratio == pytest.approx(10.8 - 1.0, abs=0.05)


def test_a_capacity_made_from_an_efficiency_gives_it_back() -> None:
    case = load_case("tles5.7kk3_r600a")  # EN 12900: -25/55 C, suction gas 32 C
    op, fluid = case.operating_point, "Isobutane"
    rho = CP.PropsSI("D", "P", op.suction_pressure, "T", op.suction_temperature, fluid)
    h_gas = CP.PropsSI("H", "P", op.suction_pressure, "T", op.suction_temperature, fluid)
    h_liquid = CP.PropsSI("H", "T", op.condensing_temperature, "Q", 0, fluid)
    swept_per_second = case.geometry.swept_volume * op.shaft_speed / (2 * math.pi)
    capacity = 0.6 * rho * swept_per_second * (h_gas - h_liquid)
    eta, _ = volumetric_point(case, capacity)
    assert eta == pytest.approx(0.6, rel=1e-6)  # CoolProp's saturation solve: 1e-6


def test_the_fit_recovers_a_dead_volume_and_losses_exactly() -> None:
    swept, dead, losses = 5.7e-6, 0.1e-6, 0.15
    ratios = np.array([15.0, 12.0, 9.5, 7.5, 6.0, 5.0])
    fit = fit_volumetric(1.0 - losses - dead / swept * ratios, ratios, swept)
    assert fit.dead_volume == pytest.approx(dead, rel=1e-10)
    assert fit.other_losses == pytest.approx(losses, rel=1e-10)
    assert fit.rms < 1e-12 and fit.points == 6


def test_the_interval_covers_the_truth_under_noise() -> None:
    swept, dead, losses = 5.7e-6, 0.1e-6, 0.15
    ratios = np.linspace(5.0, 15.0, 7)
    noise = 0.003 * np.array([1.0, -0.6, 0.2, -1.0, 0.8, -0.3, 0.5])  # a catalogue's rounding
    fit = fit_volumetric(1.0 - losses - dead / swept * ratios + noise, ratios, swept)
    assert fit.dead_volume_ci95[0] < dead < fit.dead_volume_ci95[1]
    assert fit.other_losses_ci95[0] < losses < fit.other_losses_ci95[1]
    assert fit.rms == pytest.approx(float(np.sqrt(np.mean(noise**2))), rel=0.5)


def test_too_few_points_or_one_pressure_ratio_are_refused() -> None:
    with pytest.raises(ValueError, match="needs 3 points"):
        fit_volumetric([0.6, 0.7], [10.0, 6.0], 5.7e-6)
    with pytest.raises(ValueError, match="different pressure"):
        fit_volumetric([0.6, 0.6, 0.6], [8.0, 8.0, 8.0], 5.7e-6)


def _efficiency_model(case: Case) -> dict[str, float]:
    """A compressor whose volumetric efficiency is 1 - 0.15 - (0.1 cm3 / V) R at every
    point, with the suction valve's flow coefficient (the fitted parameter) scaling it."""
    swept = case.geometry.swept_volume
    _, ratio = volumetric_point(case, 1.0)
    eta = (1.0 - 0.15 - 0.1e-6 / swept * ratio) * case.valves.suction.flow_coefficient
    per_eta = 1.0 / volumetric_point(case, 1.0)[0]  # capacity of eta_v = 1
    return {"cooling_capacity [W]": eta * per_eta}


def test_calibrate_decomposes_the_catalogue_and_the_model_alike(tmp_path: Path) -> None:
    case = load_case("tles5.7kk3_r600a")
    truth = case.with_({"valves.suction.flow_coefficient": 0.9})
    lines = ["evaporating_temperature [degC],cooling_capacity [W]"]
    for te in (-35, -30, -25, -20, -15, -10):
        point = truth.with_({"operating_point.evaporating_temperature": f"{te} degC"})
        lines.append(f"{te},{_efficiency_model(point)['cooling_capacity [W]']:.3f}")
    data = tmp_path / "points.csv"
    data.write_text("\n".join(lines) + "\n")
    cal = calibrate_case(
        case, data, ["valves.suction.flow_coefficient=0.5:1"], simulate=_efficiency_model
    )
    table = cal.volumetric.set_index("source")
    assert list(table.index) == ["catalogue", "model"]
    for source in ("catalogue", "model"):  # x = 1 - 0.9 (1 - 0.15), V_d = 0.9 x 0.1 cm3
        assert table.loc[source, "effective_dead_volume [m3]"] == pytest.approx(0.09e-6, rel=1e-3)
        assert table.loc[source, "other_losses [-]"] == pytest.approx(0.235, abs=1e-4)
    written = write_calibration(cal, tmp_path / "out")
    assert (written / "volumetric.csv").is_file()


def test_decompose_skips_points_without_a_capacity() -> None:
    case = load_case("tles5.7kk3_r600a")
    cases = [
        case.with_({"operating_point.evaporating_temperature": f"{te} degC"})
        for te in (-35, -25, -15, -10)
    ]
    capacities = [_efficiency_model(c)["cooling_capacity [W]"] for c in cases]
    full = decompose(cases, capacities)
    partial = decompose(cases, [*capacities[:3], math.nan])
    assert partial.points == 3
    assert partial.dead_volume == pytest.approx(full.dead_volume, rel=1e-9)


def test_the_console_prints_each_decomposition_in_cm3(capsys) -> None:
    from recipsim.cli.calibrate import _print_volumetric
    from recipsim.studies.calibrate.volumetric import volumetric_rows

    case = load_case("tles5.7kk3_r600a")
    cases = [
        case.with_({"operating_point.evaporating_temperature": f"{te} degC"})
        for te in (-35, -25, -15, -10)
    ]
    capacities = [_efficiency_model(c)["cooling_capacity [W]"] for c in cases]
    rows = volumetric_rows("tles", cases, {"catalogue": capacities})
    _print_volumetric(pd.DataFrame(rows))
    out = capsys.readouterr().out
    # the case's suction flow coefficient 0.8 scales eta_v: V_d 0.8 x 0.1 cm3, x 1 - 0.8 x 0.85
    assert "tles catalogue: effective dead volume 0.0800 cm3" in out
    assert "other losses 0.320" in out
