"""The flexible mechanism on the compiled integrator, run from case files (issue 3).

Cross-checks between independent paths, not shapes:
- the compiled DOPRI5 scene against scipy's LSODA (the benchmark's solve_ivp driver in
  the same revolution loop) on the same case: same bearing RMS loads;
- pinned bearing loads from a case against the library's pinned inverse dynamics, and
  the pinned driving torque against the cylinder model's rigid-crank torque;
- energy closure of the flexible run: drive work = gas work + bearing dissipation;
- the rigid limit through case overrides: stiffness x100, damping x10 (same damping
  ratio), flexible RMS loads within 2 % of pinned.
"""

from __future__ import annotations

import numpy as np
import pytest

from helpers import CASES, REFERENCE, solve_case
from recipsim.case.load import load_case
from recipsim.model.build import case_mechanism_parameters, crank_geometry
from recipsim.model.pinned import pinned_loads
from recipsim.physics.mechanics.layout import BEARING_NAMES
from recipsim.results.bearings import mechanism_summary
from recipsim.results.tables import cycle_table, pinned_tabulated_cycle, summary

PAPER = CASES / "paper_tabulated.toml"
CONSTANT = ['options.drive="constant_speed"']
PINNED = ['options.mechanics="pinned"', 'options.drive="constant_speed"']


def rms(row: dict) -> np.ndarray:
    return np.array([row[f"bearing_rms_{b} [N]"] for b in BEARING_NAMES])


@pytest.fixture(scope="module")
def flexible_run():
    sol = solve_case(PAPER, CONSTANT + ["solver.rtol=1e-8", "solver.cycle_tolerance=1e-7"])
    cycle = cycle_table(sol)
    return sol, cycle, summary(sol, cycle)


def test_compiled_scene_matches_the_solve_ivp_driver(flexible_run):
    """Two integrators (compiled DOPRI5, scipy LSODA), one right-hand side: RMS within 1e-4.

    The LSODA run is the benchmark's ``solve_ivp`` driver in the shared revolution loop,
    on the same case at rtol 1e-9 (absolute tolerances 1e-9 of the state scales)."""
    from recipsim.model.build import build_model
    from recipsim.studies.bench.ivp import solve_periodic_ivp

    sol, _, row = flexible_run
    assert sol.converged
    tight = {"solver.rtol": 1e-9, "solver.atol": 1e-9, "solver.samples_per_revolution": 720}
    case = sol.model.case.with_(tight)
    ref = solve_periodic_ivp(build_model(case), "LSODA")
    assert ref.converged
    np.testing.assert_allclose(rms(row), rms(summary(ref, cycle_table(ref), case)), rtol=1e-4)


def test_flexible_energy_closes(flexible_run):
    """Drive work = work of the gas on the piston + bearing dissipation (periodic state)."""
    _, _, row = flexible_run
    balance = row["indicated_power [W]"] + row["bearing_dissipation_power [W]"]
    assert row["bearing_dissipation_power [W]"] > 1e-3 * row["shaft_power [W]"]
    assert row["shaft_power [W]"] == pytest.approx(balance, rel=1e-5)


def test_pinned_tabulated_case_is_the_library_inverse_dynamics():
    case = load_case(PAPER, PINNED)
    cycle = pinned_tabulated_cycle(case)
    theta = np.radians(cycle["crank_angle [deg]"].to_numpy())
    ref = pinned_loads(
        case.mechanism,
        crank_geometry(case),
        theta,
        case.operating_point.shaft_speed,
        pressure_angles=case.pressure_curve.crank_angle,
        pressures=case.pressure_curve.pressure,
        shell_pressure=case.operating_point.shell_pressure,
    )
    np.testing.assert_allclose(rms(mechanism_summary(cycle)), ref.force_rms(), rtol=1e-12)
    row = summary(None, cycle, case)
    # mean torque x speed is the p dV work of the table (frictionless rigid crank)
    assert row["shaft_power [W]"] == pytest.approx(row["indicated_power [W]"], rel=1e-4)


def test_pinned_torque_equals_the_rigid_cylinder_torque():
    """Inverse dynamics of all bodies vs the cylinder model's slider-crank torque."""
    cycle = cycle_table(solve_case(REFERENCE))
    from recipsim.results.bearings import pinned_columns

    case = load_case(REFERENCE)
    op = case.operating_point
    par = case_mechanism_parameters(case)
    theta = np.radians(cycle["crank_angle [deg]"].to_numpy())
    _, torque = pinned_columns(
        theta, cycle["cylinder_pressure [Pa]"].to_numpy(), op.shaft_speed, par
    )
    shaft = cycle["shaft_torque [N m]"].to_numpy()
    assert np.max(np.abs(torque - shaft)) < 1e-9 * np.max(np.abs(shaft))


def test_rigid_limit_from_the_case_file():
    """Every stiffness x100 and damping x10 (same damping ratio): within 2 % of pinned."""
    case = load_case(PAPER)
    stiff = []
    for name, b in zip(BEARING_NAMES, case.mechanism.bearings, strict=True):
        stiff += [f"bearings.{name}.stiffness={b.stiffness * 100}"]
        stiff += [f"bearings.{name}.damping={b.damping * 10}"]
    sol = solve_case(PAPER, CONSTANT + stiff)
    flexible = rms(summary(sol))
    pinned = rms(mechanism_summary(pinned_tabulated_cycle(load_case(PAPER, PINNED))))
    assert sol.converged
    np.testing.assert_allclose(flexible, pinned, rtol=0.02)


def test_torque_profile_drive_turns_at_the_mean_speed():
    """Paper's drive: the pinned torque applied, the speed free; it ripples but holds."""
    sol = solve_case(PAPER)
    row = summary(sol)
    assert sol.converged
    assert row["mean_crank_speed [rpm]"] == pytest.approx(3500.0, rel=2e-3)
    assert 0.0 < row["crank_speed_ripple [-]"] < 0.01
    balance = row["indicated_power [W]"] + row["bearing_dissipation_power [W]"]
    assert row["shaft_power [W]"] == pytest.approx(balance, rel=2e-3)


def test_paper_command_writes_table1_with_the_paper_pattern(tmp_path):
    """`recipsim paper`: undamped flexible loads above pinned, damped ones close to pinned."""
    import pandas as pd

    from recipsim.cli.main import main

    out = tmp_path / "paper"
    status = main(
        ["paper", str(PAPER), "--out", str(out), "--no-plots", "--undamped-revolutions", "3"]
    )
    assert status == 0
    table = pd.read_csv(out / "paper_tabulated" / "table1.csv").set_index("bearing")
    assert list(table.index) == list(BEARING_NAMES)
    assert (table["gas_flexible_rms [N]"] > table["gas_pinned_rms [N]"]).all()
    assert (table["inertia_flexible_rms [N]"] > table["inertia_pinned_rms [N]"]).all()
    damped = table["gas_damped_flexible_rms [N]"] / table["gas_pinned_rms [N]"] - 1.0
    assert (damped.abs() < 0.07).all()
    assert (table["gas_pinned_rms [N]"] > table["inertia_pinned_rms [N]"]).all()


def test_the_pinned_summary_skips_the_orbits_it_knows_are_zero():
    """The pinned mechanism's journals do not move: its displacement columns are zero, so
    ``pinned=True`` (the summary's choice for a rigid crank) gives the same row, orbits
    0, in the same column order, without reading them."""
    table = pinned_tabulated_cycle(load_case(PAPER, PINNED))
    full, pinned = mechanism_summary(table), mechanism_summary(table, pinned=True)
    assert list(pinned.items()) == list(full.items())
    assert [v for k, v in pinned.items() if k.startswith("orbit_radius_max_")] == [0.0] * 6
