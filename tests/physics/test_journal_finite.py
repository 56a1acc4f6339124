"""Finite-length journal bearing (tabulated impedance ratio) against the independent
finite-volume Reynolds solver of ``reynolds_reference``, its short-bearing limit, its
balances, and the table cache."""

from __future__ import annotations

import logging
import math

import numpy as np
import pytest
from reynolds_reference import reference_film_force

from recipsim.physics.mechanics.journal import bushing_torque, short_journal_film
from recipsim.physics.mechanics.journal_finite import (
    finite_journal_film,
    finite_journal_peak_pressure,
)
from recipsim.physics.mechanics.journal_table import (
    EPS_MAX,
    H_FORMAT,
    H_LENGTH,
    H_LENGTH_OVER_DIAMETER,
    H_N_EPS,
    H_N_THETA0,
    N_EPS,
    N_HEADER,
    N_NODE_VALUES,
    N_THETA0,
    TABLE_FORMAT,
    cache_path,
    finite_journal_table,
)

R, C, MU = 7e-3, 10e-6, 0.006
OMEGA = 3500 * 2 * math.pi / 60
RATIOS = (0.3, 0.857, 1.25, 1.5)  # L/D: the range, and the reference bearings


@pytest.fixture(scope="module")
def tables(tmp_path_factory):
    directory = tmp_path_factory.mktemp("journal_cache")
    return directory, {ld: finite_journal_table(ld, directory) for ld in RATIOS + (0.05,)}


def finite(table, ld, e, v, wj, wb):
    args = (e[0], e[1], v[0], v[1], wj, wb, R, 2 * R * ld, C, MU)
    return np.array(finite_journal_film(*args, table, 0))


def reference(ld, e, v, wj, wb):
    """Richardson extrapolation of the reference on 360 x 12 and 720 x 24 cells (its
    error is second order: the two grids differ by about 1 %, the extrapolation by
    1e-4 or less from a third grid)."""
    coarse, _ = reference_film_force(e, v, wj, wb, R, 2 * R * ld, C, MU, 360, 12)
    fine, peak = reference_film_force(e, v, wj, wb, R, 2 * R * ld, C, MU, 720, 24)
    return (4 * fine - coarse) / 3, peak


def state(eps, direction):
    """e at eps (angle 0.7 rad) and (v, omega_j, omega_b) for a named motion."""
    u = np.array([math.cos(0.7), math.sin(0.7)])
    t = np.array([-u[1], u[0]])
    e = eps * C * u
    motions = {
        "rotation": (np.zeros(2), OMEGA, 0.0),
        "approach": (0.5 * C * OMEGA * u, 0.0, 0.0),
        "separation": (-0.5 * C * OMEGA * u, 0.0, 0.0),
        "crank pin": ((0.3 * u + 0.2 * t) * C * OMEGA, OMEGA, 0.25 * OMEGA),
    }
    v, wj, wb = motions[direction]
    return e, v, wj, wb


@pytest.mark.slow
@pytest.mark.parametrize("ld", RATIOS)
def test_finite_law_against_independent_reynolds_solver(tables, ld):
    """eps 0.1-0.95, rotation, squeeze both ways and a crank-pin mix: force within 1.5 %
    of |F| (measured at most 0.45 %, at L/D 1.5, eps 0.95); in pure rotation the
    tangential force (the attitude) within 2 % of itself (measured 0.31 %); peak pressure
    within 1 % (measured 0.12 %)."""
    table = tables[1][ld]
    for eps in (0.1, 0.5, 0.8, 0.95):
        for direction in ("rotation", "approach", "separation", "crank pin"):
            e, v, wj, wb = state(eps, direction)
            ref, peak = reference(ld, e, v, wj, wb)
            got = finite(table, ld, e, v, wj, wb)
            assert np.linalg.norm(got[:2] - ref) < 0.015 * np.linalg.norm(ref), (eps, direction)
            if direction == "rotation":
                t = np.array([-e[1], e[0]]) / np.linalg.norm(e)
                assert got[:2] @ t == pytest.approx(ref @ t, rel=0.02)
            got_peak = finite_journal_peak_pressure(
                e[0], e[1], v[0], v[1], wj, wb, R, 2 * R * ld, C, MU, table, 0
            )
            assert got_peak == pytest.approx(peak, rel=0.01), (eps, direction)


def test_short_bearing_limit_is_approached(tables):
    """At L/D 0.05 the finite law is within 1 % of the short one for eps <= 0.8 (measured
    0.1 % at eps 0.1, 0.8 % at 0.8, where the film's circumferential scale shrinks), and
    the gap shrinks as (L/D)^2: from L/D 0.3 to 0.05 by more than 20 (36 in theory;
    measured 25-33)."""
    for eps in (0.1, 0.5, 0.8):
        for direction in ("rotation", "approach", "crank pin"):
            e, v, wj, wb = state(eps, direction)
            gaps = {}
            for ld in (0.05, 0.3):
                short = np.array(
                    short_journal_film(e[0], e[1], v[0], v[1], wj, wb, R, 2 * R * ld, C, MU)
                )
                got = finite(tables[1][ld], ld, e, v, wj, wb)
                gaps[ld] = np.linalg.norm(got[:2] - short[:2]) / np.linalg.norm(short[:2])
            assert gaps[0.05] < 0.01
            assert gaps[0.3] > 20 * gaps[0.05]


def test_finite_balances_and_range(tables):
    """Dissipation >= 0 and the moment balance on random states; finite and continuous
    beyond the table (eps > EPS_MAX, eps >= 1); the squeeze damper at e = 0 is the short
    one times Q(0) (the same for every direction to 1e-6: the table's solver tolerance)."""
    ld = 1.25
    table = tables[1][ld]
    rng = np.random.default_rng(5)
    for _ in range(200):
        eps = rng.uniform(0, 0.98)
        phi = rng.uniform(-math.pi, math.pi)
        e = eps * C * np.array([math.cos(phi), math.sin(phi)])
        v = C * OMEGA * 10 ** rng.uniform(-3, 1) * rng.normal(size=2)
        wj, wb = OMEGA * rng.uniform(-1, 1, size=2)
        fx, fy, tj = finite(table, ld, e, v, wj, wb)
        tb = bushing_torque(e[0], e[1], fx, fy, tj)
        assert tj + tb + (e[0] * fy - e[1] * fx) == pytest.approx(0.0, abs=1e-12 * abs(tj))
        power = -(fx * v[0] + fy * v[1] + tj * wj + tb * wb)
        assert power >= 0.0
    u = np.array([0.6, 0.8])
    v = np.array([0.01, -0.02])
    below = finite(table, ld, u * C * (EPS_MAX - 1e-9), v, OMEGA, 0.0)
    above = finite(table, ld, u * C * (EPS_MAX + 1e-9), v, OMEGA, 0.0)
    assert np.allclose(below, above, rtol=1e-5)
    for eps in (1.0, 3.0):
        assert np.all(np.isfinite(finite(table, ld, u * C * eps, v, OMEGA, 0.0)))
    ratios = []
    for angle in np.linspace(0, 2 * math.pi, 7):
        v = 0.01 * np.array([math.cos(angle), math.sin(angle)])
        got = finite(table, ld, np.zeros(2), v, 0.0, 0.0)
        short = -math.pi * MU * R * (2 * R * ld) ** 3 * v / (2 * C**3)
        ratios.append(got[:2] @ short / (short @ short))
        assert np.linalg.norm(got[:2] - ratios[-1] * short) < 1e-6 * np.linalg.norm(short)
    assert np.ptp(ratios) < 1e-6


def test_table_is_self_describing(tables):
    table = tables[1][1.25]
    assert table[H_FORMAT] == TABLE_FORMAT
    assert table[H_LENGTH] == table.size == N_HEADER + N_EPS * N_THETA0 * N_NODE_VALUES
    assert table[H_LENGTH_OVER_DIAMETER] == 1.25
    assert (table[H_N_EPS], table[H_N_THETA0]) == (N_EPS, N_THETA0)
    # the law reads it at any offset inside a larger parameter array
    e, v, wj, wb = state(0.7, "crank pin")
    embedded = np.concatenate([np.full(17, np.nan), table, np.full(5, np.nan)])
    args = (e[0], e[1], v[0], v[1], wj, wb, R, 2 * R * 1.25, C, MU)
    assert finite_journal_film(*args, embedded, 17) == finite_journal_film(*args, table, 0)


def test_cache_round_trip_and_tampered_file_rebuilt(tables, caplog):
    """A second call loads the same table without building (no log line); a file whose
    data were changed is reported, rebuilt, and the rebuilt table is the original."""
    directory, built = tables
    ld = 0.3
    path = cache_path(ld, directory)
    assert path.is_file()
    with caplog.at_level(logging.INFO, logger="recipsim"):
        again = finite_journal_table(ld, directory)
    assert np.array_equal(again, built[ld])
    assert not caplog.records
    with np.load(path) as npz:
        content = {k: npz[k] for k in npz.files}
    content["data"] = content["data"].copy()
    content["data"][N_HEADER + 5] += 1e-3
    with open(path, "wb") as handle:
        np.savez(handle, **content)
    with caplog.at_level(logging.INFO, logger="recipsim"):
        with pytest.warns(UserWarning, match="checksum"):
            rebuilt = finite_journal_table(ld, directory)
    assert np.array_equal(rebuilt, built[ld])
    assert len(caplog.records) == 1 and "building" in caplog.records[0].getMessage()
    path.write_bytes(b"not a table")
    with pytest.warns(UserWarning, match="unreadable"):
        assert np.array_equal(finite_journal_table(ld, directory), built[ld])
    with pytest.raises(ValueError):
        finite_journal_table(10.0, directory)
