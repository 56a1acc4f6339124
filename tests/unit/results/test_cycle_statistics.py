"""The summary's statistics of a cycle in one compiled pass
(:mod:`recipsim.results.cycle_statistics`) are the numpy expressions they replaced, to
the last bit: on the cycle tables of every kind of scene, on random columns with NaN,
zero flows and valves that never close, and numpy's pairwise sum itself on arrays of
every length class (under 8 values, up to 128, split in halves). Equal to the last bit
because the summary's numbers must not move with the way they are computed (a report's
``summary.csv`` is the same bytes as before), and because numpy's summation order is
deterministic: a numpy release that changed it would show here first."""

from __future__ import annotations

import math

import numpy as np
import pytest

from helpers import CASES, REFERENCE
from recipsim.case.load import load_case
from recipsim.model import scenes
from recipsim.physics.mechanics.layout import BEARING_NAMES
from recipsim.results.columns import Columns
from recipsim.results.cycle_statistics import (
    ALWAYS_OPEN,
    NEVER_OPEN,
    STATS,
    _pairwise_sum,
    cycle_statistics,
)
from recipsim.results.run import simulate_case


def _open_run_by_walking(flowing: np.ndarray) -> tuple[float, float]:
    """First and last sample of the longest circular run of True (the first of the
    longest, counted from the first False), walked sample by sample."""
    n = len(flowing)
    if flowing.all():
        return ALWAYS_OPEN, ALWAYS_OPEN
    if not flowing.any():
        return NEVER_OPEN, NEVER_OPEN
    start = int(np.flatnonzero(~flowing)[0])
    best, best_len, i = (0, 0), 0, 0
    while i < n:
        if flowing[(start + i) % n]:
            j = i
            while j < n and flowing[(start + j) % n]:
                j += 1
            if j - i > best_len:
                best_len, best = j - i, ((start + i) % n, (start + j - 1) % n)
            i = j
        else:
            i += 1
    return float(best[0]), float(best[1])


def numpy_statistics(
    columns: dict[str, np.ndarray], pinned: bool, gas: bool, reed: bool, plenum: tuple
) -> dict[str, float]:
    """The statistics as the summary computed them before, in numpy."""
    p = columns["cylinder_pressure [Pa]"]
    v = columns["cylinder_volume [m3]"]
    torque = columns["shaft_torque [N m]"]
    speed = columns["crank_speed [rad/s]"]
    f = np.stack([columns[f"bearing_force_{b} [N]"] for b in BEARING_NAMES])
    out: dict[str, float] = {}
    rms = np.sqrt(np.mean(f * f, axis=1))
    for k, b in enumerate(BEARING_NAMES):
        out[f"force_rms_{b}"] = float(rms[k])
        out[f"force_max_{b}"] = float(f[k].max())
        if pinned:
            out[f"orbit_max_{b}"] = 0.0
        else:
            x = columns[f"bearing_displacement_{b}_x [m]"]
            y = columns[f"bearing_displacement_{b}_y [m]"]
            out[f"orbit_max_{b}"] = float(np.sqrt(np.max(x * x + y * y)))
    out["inverse_speed_mean"] = float(np.mean(1.0 / speed))
    out["speed_min"], out["speed_max"] = float(speed.min()), float(speed.max())
    out["pressure_max"], out["pressure_min"] = float(p.max()), float(p.min())
    out["torque_max"], out["torque_min"] = float(torque.max()), float(torque.min())
    out["torque_over_speed_mean"] = float(np.mean(torque / speed))
    for k, side in enumerate(("suction", "discharge")):
        if not gas:
            out[f"{side}_valve_area"] = math.nan
            out[f"{side}_open_sample"] = out[f"{side}_close_sample"] = NEVER_OPEN
            continue
        flow = columns[f"{side}_mass_flow [kg/s]"]
        passing = flow != 0.0
        flowing = passing | np.roll(passing, -1)
        p_mid = 0.5 * (p + np.roll(p, -1))
        area = np.sum(np.where(flowing, (plenum[k] - p_mid) * (np.roll(v, -1) - v), 0.0))
        out[f"{side}_valve_area"] = float(area)
        if reed:
            is_open = columns[f"{side}_valve_lift [m]"] > 0.0
        else:
            magnitude = np.abs(flow)
            is_open = magnitude > 1e-12 * max(magnitude.max(), 1e-300)
        first, last = _open_run_by_walking(is_open)
        out[f"{side}_open_sample"], out[f"{side}_close_sample"] = first, last
    return out


def _same(a: float, b: float) -> bool:
    return (math.isnan(a) and math.isnan(b)) or a == b


def _check(columns: dict[str, np.ndarray], pinned: bool, gas: bool, reed: bool, plenum) -> None:
    got = cycle_statistics(Columns(columns), pinned, gas, reed, plenum)
    want = numpy_statistics(columns, pinned, gas, reed, plenum)
    assert sorted(e.name for e in STATS.entries) == sorted(want)
    differ = {
        e.name: (got[e.index], want[e.name])
        for e in STATS.entries
        if not _same(got[e.index], want[e.name])
    }
    assert not differ


@pytest.fixture(scope="module", params=["rigid", "coupled", "lubricated", "tabulated", "ideal"])
def scene(request):
    short = ["solver.min_revolutions=2", "solver.max_revolutions=2"]
    path, overrides = {
        "rigid": (REFERENCE, []),
        "coupled": (
            CASES / "reference_r134a_lbp_coupled.toml",
            [*short, "options.drive=induction_motor"],  # a speed that varies
        ),
        "lubricated": (CASES / "reference_r134a_lbp_lubricated.toml", short),
        "tabulated": (CASES / "paper_tabulated.toml", []),
        "ideal": (REFERENCE, ["options.valves=ideal"]),
    }[request.param]
    run = simulate_case(load_case(path, overrides), [])
    table = run.table
    columns = table if isinstance(table, dict) else {c: table[c].to_numpy() for c in table}
    model = None if run.solution is None else run.solution.model
    gas = model is not None and model.has_gas
    pinned = model is None or model.scene == scenes.SCENE_CYLINDER
    return columns, pinned, gas, run.case.options.valves == "reed"


def test_a_cycles_statistics_are_numpys_to_the_last_bit(scene) -> None:
    columns, pinned, gas, reed = scene
    _check(columns, pinned, gas, reed, (1.1e5, 11e5))


def _random_columns(rng: np.random.Generator, n: int) -> dict[str, np.ndarray]:
    names = [
        "cylinder_pressure [Pa]",
        "cylinder_volume [m3]",
        "shaft_torque [N m]",
        *(f"bearing_force_{b} [N]" for b in BEARING_NAMES),
        *(f"bearing_displacement_{b}_{ax} [m]" for b in BEARING_NAMES for ax in "xy"),
    ]
    columns = {name: rng.standard_normal(n) * 10.0 ** rng.uniform(-6, 6) for name in names}
    columns["crank_speed [rad/s]"] = 300.0 + rng.standard_normal(n)
    for side in ("suction", "discharge"):
        flow = rng.standard_normal(n) * 1e-3
        flow[rng.random(n) < rng.uniform(0.0, 1.0)] = 0.0  # closed stretches, or none
        columns[f"{side}_mass_flow [kg/s]"] = flow
        columns[f"{side}_valve_lift [m]"] = np.where(rng.random(n) < 0.5, 0.0, np.abs(flow))
    return columns


@pytest.mark.parametrize("seed", range(30))
def test_random_columns_give_numpys_statistics(seed: int) -> None:
    rng = np.random.default_rng(seed)
    n = int(rng.choice([3, 7, 8, 9, 64, 127, 128, 129, 300, 720, 1441]))
    columns = _random_columns(rng, n)
    if seed % 5 == 1:  # a NaN in a force, a pressure, a flow: numpy's max propagates it
        for name in ("bearing_force_eccentric [N]", "cylinder_pressure [Pa]"):
            columns[name][int(rng.integers(n))] = np.nan
        columns["suction_mass_flow [kg/s]"][int(rng.integers(n))] = np.nan
    if seed % 5 == 2:  # a valve that never closes, one that never opens
        columns["suction_mass_flow [kg/s]"][:] = 1e-3
        columns["suction_valve_lift [m]"][:] = 1e-4
        columns["discharge_mass_flow [kg/s]"][:] = 0.0
        columns["discharge_valve_lift [m]"][:] = 0.0
    for pinned in (True, False):
        for reed in (True, False):
            _check(columns, pinned, True, reed, (float(rng.uniform(1e5, 2e5)), 9e5))
    _check(columns, False, False, False, (math.nan, math.nan))


@pytest.mark.parametrize("n", [1, 2, 7, 8, 9, 15, 16, 17, 127, 128, 129, 255, 256, 720, 4099])
def test_the_pairwise_sum_is_numpys(n: int) -> None:
    rng = np.random.default_rng(n)
    for _ in range(20):
        a = rng.standard_normal(n) * 10.0 ** rng.uniform(-8, 8, n)
        assert _pairwise_sum(a, 0, n) == np.sum(a)
        assert _pairwise_sum(a, 0, n) / n == np.mean(a)


def test_the_first_runs_head_start_compiles_the_signature_a_summary_uses(scene) -> None:
    """:func:`compile_statistics` (the first run's head start) and a summary's call
    compile one signature: the head start is not wasted on other types."""
    from recipsim.results.cycle_statistics import _statistics, compile_statistics

    compile_statistics()
    columns, pinned, gas, reed = scene
    cycle_statistics(Columns(columns), pinned, gas, reed, (1e5, 1e6))
    assert len(_statistics.signatures) == 1
