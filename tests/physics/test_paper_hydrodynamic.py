"""The paper study's hydrodynamic column (issue 15) and the orbits in the clearance circle.

The shipped ``paper_tabulated`` case: the reference compressor's crank train under its
frozen cylinder-pressure curve, the journals on ``finite_journal`` films (16/20 mm and
14/12 mm, 10 um radial clearance, ISO VG 10 at 60 C) through the ordinary case solve.
Measured (360 samples): RMS loads against pinned +0.1 / +0.2 / +0.0 % (inertia) and
+0.1 / +0.3 / +0.1 % (gas) on primary / secondary / eccentric, the undamped linear
bearings +113 / +526 / +45 % (gas); smallest films 6.55 / 5.13 / 3.78 um under gas.
About 2 s for the column (two case solves), 4 s for the whole study with 2-revolution
undamped transients.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from matplotlib.patches import Circle

from recipsim.case.case import Case
from recipsim.case.load import load_case
from recipsim.physics.mechanics.layout import BEARING_NAMES
from recipsim.report.mechanics_plots import film_bearings, film_clearance, plot_orbits
from recipsim.studies.paper import run_paper_study
from recipsim.studies.paper_hydrodynamic import JOURNALS, hydrodynamic_case
from recipsim.studies.paper_report import CLOSE_TO_PINNED, conclusion_three
from recipsim.studies.paper_runs import HYDRODYNAMIC_RUNS, RUNS, PaperStudy
from recipsim.studies.paper_tables import table1_columns

SAMPLES = 180


@pytest.fixture(scope="module")
def case() -> Case:
    return load_case("paper_tabulated")


@pytest.fixture(scope="module")
def study(case: Case, tmp_path_factory: pytest.TempPathFactory) -> PaperStudy:
    assert case.pressure_curve is not None
    return run_paper_study(
        case,
        case.pressure_curve,
        tmp_path_factory.mktemp("paper") / "study",
        undamped_start="quasi_static",
        undamped_revolutions=2,
        samples_per_revolution=SAMPLES,
        hydrodynamic=True,
    )


def rows(study: PaperStudy, column: str) -> np.ndarray:
    t = study.table1.set_index("bearing")
    return t.loc[list(JOURNALS), column].to_numpy(dtype=float)


def test_column_layout_and_runs(study: PaperStudy) -> None:
    """Table 1 gains the hydrodynamic entries; both runs converged at constant speed,
    the case's periodic solver, on equal crank-angle steps from TDC."""
    assert list(study.table1.columns) == table1_columns(hydrodynamic=True)
    assert table1_columns() == [c for c in table1_columns(True) if "hydrodynamic" not in c]
    assert list(study.runs) == [*RUNS, *HYDRODYNAMIC_RUNS]
    for name in HYDRODYNAMIC_RUNS:
        record = study.runs[name]
        assert record.model == "hydrodynamic" and record.mode == "case"
        assert record.converged is True, record
        cycle = study.cycles[name]
        np.testing.assert_allclose(cycle["crank_angle [deg]"], np.arange(SAMPLES) * 2.0)
        speed = cycle["crank_speed [rad/s]"].to_numpy()
        np.testing.assert_allclose(speed, study.settings["crank_speed [rad/s]"], rtol=1e-12)


def test_rms_and_relative_columns_follow_from_the_cycles(study: PaperStudy) -> None:
    """RMS and peak from the cycle tables' force magnitudes (independent of the
    summary); relative differences against the pinned run of the same load."""
    t = study.table1
    for config in ("inertia", "gas"):
        cycle = study.cycles[f"{config}_hydrodynamic"]
        force = cycle[[f"bearing_force_{b} [N]" for b in BEARING_NAMES]].to_numpy()
        np.testing.assert_allclose(
            np.sqrt(np.mean(force**2, axis=0)), t[f"{config}_hydrodynamic_rms [N]"], rtol=1e-9
        )
        np.testing.assert_allclose(force.max(axis=0), t[f"{config}_hydrodynamic_peak [N]"])
        ratio = t[f"{config}_hydrodynamic_rms [N]"] / t[f"{config}_pinned_rms [N]"] - 1.0
        np.testing.assert_allclose(t[f"{config}_hydrodynamic_vs_pinned [-]"], ratio, rtol=1e-12)


def test_films_stay_inside_the_clearance(study: PaperStudy, case: Case) -> None:
    """Smallest film = clearance - largest orbit radius (the columns' definition), positive
    with margin (measured 3.8 um on the eccentric under gas); no film for the pin and
    piston bearings (nan)."""
    t = study.table1.set_index("bearing")
    for config in ("inertia", "gas"):
        for name in JOURNALS:
            film = case.mechanism.bearing(name).film
            assert film is not None
            h = t.loc[name, f"{config}_hydrodynamic_min_film [m]"]
            orbit = t.loc[name, f"{config}_hydrodynamic_orbit_max [m]"]
            assert h == pytest.approx(film.radial_clearance - orbit, rel=1e-9)
            assert h > 0.2 * film.radial_clearance, (config, name, h)
        others = [b for b in BEARING_NAMES if b not in JOURNALS]
        assert np.all(np.isnan(t.loc[others, f"{config}_hydrodynamic_min_film [m]"]))


def test_energy_closes_at_constant_speed(study: PaperStudy) -> None:
    """Shaft power = indicated power + film and damper dissipation over the periodic
    revolution (to 1e-3: the cycle tolerance); the inertia load does no gas work, so
    its shaft power is the friction alone (measured 7.6 W, positive)."""
    for config, run in study.hydrodynamic.items():
        s = run.summary
        balance = s["indicated_power [W]"] + s["bearing_dissipation_power [W]"]
        assert s["shaft_power [W]"] == pytest.approx(balance, rel=1e-3), config
    inertia = study.hydrodynamic["inertia"].summary
    assert abs(inertia["indicated_power [W]"]) < 1e-9 * inertia["shaft_power [W]"]
    friction = sum(inertia[f"friction_power_{j} [W]"] for j in JOURNALS)
    assert 0.0 < friction <= inertia["shaft_power [W]"] * (1.0 + 1e-3)


def test_conclusion_three(study: PaperStudy, tmp_path: Path) -> None:
    """The paper's conclusion 3 holds on films: every journal's RMS load within 5 % of
    pinned for both loads (measured 0.25 % at most), while the undamped linear bearings
    are far off; the verdict and its figures are written in README and study.json."""
    for config in ("inertia", "gas"):
        rel = rows(study, f"{config}_hydrodynamic_vs_pinned [-]")
        assert np.all(np.abs(rel) < CLOSE_TO_PINNED), (config, rel)
    assert np.any(np.abs(rows(study, "gas_flexible_vs_pinned [-]")) > 0.1)
    text = conclusion_three(study.table1)
    assert " holds here" in text
    # a table whose films were far off says so
    far = study.table1.copy()
    far["gas_hydrodynamic_vs_pinned [-]"] = 0.3
    assert "does not hold" in conclusion_three(far)
    assert study.out_dir is not None
    readme = (study.out_dir / "README.md").read_text()
    assert text in readme and "gas_hydrodynamic" in readme
    info = json.loads((study.out_dir / "study.json").read_text())
    assert info["conclusion_3"] == text
    assert info["settings"]["hydrodynamic"]["law"] == "finite_journal"
    assert set(info["films"]) == {"inertia", "gas"}
    names = {p.name for p in study.files}
    assert {"orbits_hydrodynamic.png", "cycle_gas_hydrodynamic.csv"} <= names


def test_hydrodynamic_case_is_validated(case: Case) -> None:
    """The column's case: film journals, constant speed, the given curve; what it
    changes is validated like the file (an unknown law is refused, naming the key)."""
    from recipsim.errors import CaseError
    from recipsim.studies.paper_hydrodynamic import constant_curve

    curve = constant_curve(2.0e5)
    c = hydrodynamic_case(case, curve, label="x")
    assert c.name == "paper_tabulated_hydrodynamic_x"
    assert [c.mechanism.bearing(j).law for j in JOURNALS] == ["finite_journal"] * 3
    assert c.options.drive == "constant_speed" and c.options.pressure == "tabulated"
    assert c.pressure_curve is curve
    with pytest.raises(CaseError, match="bearings.primary.law"):
        hydrodynamic_case(case, curve, law="ball_bearing")


# ------------------------------------------------------------------------------ orbits


def test_orbit_plot_draws_the_clearance_circle(study: PaperStudy, case: Case) -> None:
    """Lubricated orbits: one dashed circle per journal of radius = its radial clearance
    [um] (artist data), every orbit point inside it, equal aspect framed on the circle;
    the smallest-film cross lies on the orbit where the film column is smallest."""
    cycle = study.cycles["gas_hydrodynamic"]
    assert film_bearings(cycle) == JOURNALS
    fig = plot_orbits({"gas": cycle}, bearings=JOURNALS)
    ax = fig.axes[0]
    circles = {p.get_gid(): p for p in ax.patches if isinstance(p, Circle)}
    for name in JOURNALS:
        clearance = case.mechanism.bearing(name).film.radial_clearance  # type: ignore[union-attr]
        assert film_clearance(cycle, name) == pytest.approx(clearance, rel=1e-9)
        circle = circles[f"clearance_{name}"]
        assert circle.get_radius() == pytest.approx(1e6 * clearance, rel=1e-12)
        assert circle.center == (0.0, 0.0)
        (line,) = [ln for ln in ax.get_lines() if ln.get_label() == name]
        r = np.hypot(np.asarray(line.get_xdata()), np.asarray(line.get_ydata()))
        assert np.all(r < circle.get_radius()), name
        (cross,) = [ln for ln in ax.get_lines() if str(ln.get_label()).startswith(f"{name}:")]
        h = cycle[f"film_thickness_{name} [m]"].to_numpy()
        k = int(np.argmin(h))
        xy = 1e6 * cycle[[f"bearing_displacement_{name}_{a} [m]" for a in "xy"]].to_numpy()[k]
        np.testing.assert_allclose([cross.get_xdata()[0], cross.get_ydata()[0]], xy)
    assert ax.get_aspect() == 1.0
    assert ax.get_xlim()[1] == pytest.approx(1.08e6 * 10e-6, rel=1e-9)


def test_linear_orbit_plot_has_no_circle(study: PaperStudy) -> None:
    """Linear bearings keep today's plot: no clearance circle, no film marker."""
    cycle = study.cycles["gas_damped_flexible"]
    assert film_bearings(cycle) == () and film_clearance(cycle, "primary") is None
    ax = plot_orbits({"damped": cycle}).axes[0]
    assert not [p for p in ax.patches if isinstance(p, Circle)]
    assert all(":" not in str(ln.get_label()) for ln in ax.get_lines())


def test_case_report_orbits_show_every_film_bearing(study: PaperStudy, tmp_path: Path) -> None:
    """The case report draws the lubricated journals (all three) in their circles."""
    from recipsim.report.plotting import save_cycle_figures

    cycle = study.cycles["gas_hydrodynamic"]
    names = save_cycle_figures(cycle, tmp_path)
    assert "orbits.png" in names
    assert (tmp_path / "orbits.png").stat().st_size > 10_000
