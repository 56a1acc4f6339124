"""The summary's statistics of a cycle table, in one compiled pass over its columns.

:func:`recipsim.results.tables.summary` reduces the columns of the cycle table (one row
per crank-angle sample) to the summary's numbers: the RMS and peak load of each bearing
and its largest orbit, the time-mean crank speed and its ripple, the extremes of the
cylinder pressure and of the shaft torque, the p-V areas of the valves' throttling, when
each valve opens and closes, the time-mean torque of the motor. It did so in some forty
numpy calls of a few microseconds each on 720 samples, 0.15 ms of a sweep point's 1.9 ms
of overhead; :func:`cycle_statistics` reads the columns and makes one compiled call
(:func:`_statistics`) that fills :data:`STATS`.

Sums are numpy's pairwise sums (:func:`_pairwise_sum`, numpy's ``pairwise_sum`` for
float64, zero start): a sum here is the sum numpy gives for the same column, so every
summary value is what the numpy expressions in each function's docstring give
(``tests/unit/results/test_cycle_statistics.py`` checks them against those expressions).
Extremes propagate NaN, as numpy's ``max`` and ``min`` do. The run's report
(a DataFrame) and a sweep point (:class:`~recipsim.results.columns.Columns`) pass the
same arrays, so they get the same values.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from recipsim.physics.layout_table import Layout
from recipsim.physics.mechanics import layout as lay
from recipsim.results.columns import CycleLike

STATS = Layout("cycle statistics")
S_FORCE_RMS = STATS.add_series(
    "force_rms_{}", lay.BEARING_NAMES, "N", "sqrt(mean(F^2)) of the bearing force magnitude"
)
S_FORCE_MAX = STATS.add_series(
    "force_max_{}", lay.BEARING_NAMES, "N", "largest bearing force magnitude"
)
S_ORBIT_MAX = STATS.add_series(
    "orbit_max_{}", lay.BEARING_NAMES, "m", "largest sqrt(x^2 + y^2) (0 if pinned)"
)
S_INVERSE_SPEED_MEAN = STATS.add("inverse_speed_mean", "s/rad", "mean(1 / omega)")
S_SPEED_MIN = STATS.add("speed_min", "rad/s", "smallest crank speed")
S_SPEED_MAX = STATS.add("speed_max", "rad/s", "largest crank speed")
S_PRESSURE_MAX = STATS.add("pressure_max", "Pa", "peak cylinder pressure")
S_PRESSURE_MIN = STATS.add("pressure_min", "Pa", "lowest cylinder pressure")
S_TORQUE_MAX = STATS.add("torque_max", "N m", "peak shaft torque")
S_TORQUE_MIN = STATS.add("torque_min", "N m", "lowest shaft torque")
S_TORQUE_OVER_SPEED_MEAN = STATS.add(
    "torque_over_speed_mean", "N m s/rad", "mean(T / omega): the time mean's numerator"
)
S_VALVE_AREA = STATS.add_series(
    "{}_valve_area",
    ("suction", "discharge"),
    "J",
    "p-V area beyond the valve's plenum pressure while it passes gas (NaN without gas)",
)
S_OPEN_SAMPLE = STATS.add_series(
    "{}_open_sample",
    ("suction", "discharge"),
    "index",
    "first sample of the valve's longest open run (see NEVER_OPEN, ALWAYS_OPEN)",
)
S_CLOSE_SAMPLE = STATS.add_series(
    "{}_close_sample", ("suction", "discharge"), "index", "last sample of that run"
)
N_STATS = STATS.size

#: Open and close samples of a valve that never passes gas (or without a gas model) and
#: of one that never closes.
NEVER_OPEN = -1.0
ALWAYS_OPEN = -2.0

_N_BEARINGS = len(lay.BEARING_NAMES)


@njit(cache=True)
def _block_sum(a, lo, n):  # pragma: no cover - compiled
    """numpy's sum of at most 128 values ``a[lo:lo + n]``: a plain loop under 8 values,
    else 8 accumulators, added in pairs, then the rest."""
    if n < 8:
        total = 0.0
        for i in range(lo, lo + n):
            total += a[i]
        return total
    r0, r1, r2, r3 = a[lo], a[lo + 1], a[lo + 2], a[lo + 3]
    r4, r5, r6, r7 = a[lo + 4], a[lo + 5], a[lo + 6], a[lo + 7]
    i = 8
    whole = n - n % 8
    while i < whole:
        j = lo + i
        r0 += a[j]
        r1 += a[j + 1]
        r2 += a[j + 2]
        r3 += a[j + 3]
        r4 += a[j + 4]
        r5 += a[j + 5]
        r6 += a[j + 6]
        r7 += a[j + 7]
        i += 8
    total = ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7))
    while i < n:
        total += a[lo + i]
        i += 1
    return total


@njit(cache=True)
def _half(n):  # pragma: no cover - compiled
    """Where numpy cuts ``n`` values in two: half of them, down to a multiple of 8."""
    half = n // 2
    return half - half % 8


@njit(cache=True)
def _pairwise_sum(a, lo, n):  # pragma: no cover - compiled
    """Sum of ``a[lo:lo + n]`` in numpy's order (its ``pairwise_sum`` for float64: blocks
    of at most 128 values, :func:`_block_sum`, the halves of a longer run added).

    The halving walked with a stack, not by recursion: numba's cache does not reload a
    recursive function safely (the process crashed on the second run)."""
    if n <= 128:
        return _block_sum(a, lo, n)
    starts = np.empty(64, np.int64)
    counts = np.empty(64, np.int64)
    left_sums = np.empty(64)
    left_done = np.zeros(64, np.bool_)
    top = 0
    starts[0], counts[0] = lo, n
    while True:
        if counts[top] > 128:  # descend into the left half
            starts[top + 1], counts[top + 1] = starts[top], _half(counts[top])
            top += 1
            left_done[top] = False
            continue
        total = _block_sum(a, starts[top], counts[top])
        top -= 1
        while top >= 0 and left_done[top]:  # right halves done: add them to their left
            total = left_sums[top] + total
            top -= 1
        if top < 0:
            return total
        left_sums[top], left_done[top] = total, True  # a left half: now its right one
        half = _half(counts[top])
        starts[top + 1], counts[top + 1] = starts[top] + half, counts[top] - half
        top += 1
        left_done[top] = False


@njit(cache=True)
def _extremes(a):  # pragma: no cover - compiled
    """Largest and smallest value of ``a``, NaN if any is NaN (as numpy's max, min)."""
    hi = a[0]
    lo = a[0]
    for i in range(1, a.shape[0]):
        x = a[i]
        if x != x:
            return math.nan, math.nan
        if x > hi:
            hi = x
        if x < lo:
            lo = x
    if hi != hi:
        return math.nan, math.nan
    return hi, lo


@njit(cache=True)
def _longest_open_run(flowing):  # pragma: no cover - compiled
    """First and last sample of the longest circular run of ``flowing`` (the first of
    the longest, counted from the first closed sample), or the NEVER_OPEN, ALWAYS_OPEN
    codes."""
    n = flowing.shape[0]
    start = -1
    for i in range(n):
        if not flowing[i]:
            start = i
            break
    if start < 0:
        return ALWAYS_OPEN, ALWAYS_OPEN
    best_begin, best_end, best_length = -1, -1, 0
    begin = -1
    for k in range(1, n + 1):  # the circle unrolled from a closed sample, closed after it
        now = flowing[(start + k) % n] if k < n else False
        before = flowing[(start + k - 1) % n]
        if now and not before:
            begin = k
        elif before and not now:
            if k - begin > best_length:
                best_begin, best_end, best_length = begin, k - 1, k - begin
    if best_length == 0:
        return NEVER_OPEN, NEVER_OPEN
    return float((best_begin + start) % n), float((best_end + start) % n)


@njit(cache=True)
def _statistics(
    pressure, volume, torque, speed, forces, displacements, valves, plenum, reed, out
):  # pragma: no cover - compiled
    """Fill ``out`` (:data:`STATS`) from the columns (see :func:`cycle_statistics`)."""
    n = pressure.shape[0]
    scratch = np.empty(n)
    for b in range(forces.shape[0]):
        row = forces[b]
        for i in range(n):
            scratch[i] = row[i] * row[i]
        out[S_FORCE_RMS + b] = math.sqrt(_pairwise_sum(scratch, 0, n) / n)
        out[S_FORCE_MAX + b] = _extremes(row)[0]
    for b in range(_N_BEARINGS):
        largest = 0.0
        if displacements.shape[0] > 0:
            x, y = displacements[2 * b], displacements[2 * b + 1]
            for i in range(n):
                scratch[i] = x[i] * x[i] + y[i] * y[i]
            largest = math.sqrt(_extremes(scratch)[0])
        out[S_ORBIT_MAX + b] = largest
    for i in range(n):
        scratch[i] = 1.0 / speed[i]
    out[S_INVERSE_SPEED_MEAN] = _pairwise_sum(scratch, 0, n) / n
    out[S_SPEED_MAX], out[S_SPEED_MIN] = _extremes(speed)
    out[S_PRESSURE_MAX], out[S_PRESSURE_MIN] = _extremes(pressure)
    out[S_TORQUE_MAX], out[S_TORQUE_MIN] = _extremes(torque)
    for i in range(n):
        scratch[i] = torque[i] / speed[i]
    out[S_TORQUE_OVER_SPEED_MEAN] = _pairwise_sum(scratch, 0, n) / n
    flowing = np.empty(n, dtype=np.bool_)
    for side in range(2):
        out[S_VALVE_AREA + side] = math.nan
        out[S_OPEN_SAMPLE + side] = NEVER_OPEN
        out[S_CLOSE_SAMPLE + side] = NEVER_OPEN
        if valves.shape[0] == 0:
            continue
        flow, lift = valves[side], valves[2 + side]
        for i in range(n):  # trapezoids on the samples where the valve passes gas at an end
            j = (i + 1) % n
            passing = flow[i] != 0.0 or flow[j] != 0.0
            mid = 0.5 * (pressure[i] + pressure[j])
            scratch[i] = (plenum[side] - mid) * (volume[j] - volume[i]) if passing else 0.0
        out[S_VALVE_AREA + side] = _pairwise_sum(scratch, 0, n)
        if reed:
            for i in range(n):
                flowing[i] = lift[i] > 0.0
        else:
            for i in range(n):
                scratch[i] = abs(flow[i])
            floor = _extremes(scratch)[0]
            if 1e-300 > floor:  # Python's max(floor, 1e-300): NaN stays
                floor = 1e-300
            for i in range(n):
                flowing[i] = scratch[i] > 1e-12 * floor
        out[S_OPEN_SAMPLE + side], out[S_CLOSE_SAMPLE + side] = _longest_open_run(flowing)


#: The bearing columns the statistics read (report names).
_FORCE_COLUMNS = tuple(f"bearing_force_{name} [N]" for name in lay.BEARING_NAMES)
_DISPLACEMENT_COLUMNS = tuple(
    lay.OUTPUTS.entry(f"bearing_displacement_{name}_{axis}").column
    for name in lay.BEARING_NAMES
    for axis in "xy"
)
_VALVE_COLUMNS = (
    "suction_mass_flow [kg/s]",
    "discharge_mass_flow [kg/s]",
    "suction_valve_lift [m]",
    "discharge_valve_lift [m]",
)


def _rows(cycle: CycleLike, names: tuple[str, ...]) -> np.ndarray:
    return np.stack([cycle[name].to_numpy(dtype=np.float64) for name in names])


def _array(cycle: CycleLike, name: str) -> np.ndarray:
    """A column as a contiguous, writable float64 array (one compiled signature)."""
    values = np.ascontiguousarray(cycle[name].to_numpy(dtype=np.float64))
    return values if values.flags.writeable else values.copy()


def cycle_statistics(
    cycle: CycleLike,
    pinned: bool,
    gas: bool = False,
    reed: bool = False,
    plenum: tuple[float, float] = (math.nan, math.nan),
) -> list[float]:
    """The statistics :data:`STATS` of a cycle table, as a list indexed by its slots.

    Parameters
    ----------
    cycle : CycleLike
        The cycle table (a DataFrame or :class:`~recipsim.results.columns.Columns`):
        pressure, volume, shaft torque, crank speed, bearing force magnitudes, and as
        below.
    pinned : bool
        The table is the pinned mechanism's: no displacement columns are read, the
        orbits are 0.
    gas : bool
        The table has the gas model's columns (mass flows, reed lifts): the valve areas
        and timing are computed, else NaN and :data:`NEVER_OPEN`.
    reed : bool
        A valve is open while its reed lifts (``lift > 0``), else while its mass flow
        exceeds 1e-12 of its largest (valves without a reed).
    plenum : tuple of float
        Suction and discharge plenum pressures [Pa], the references of the valve areas.

    Returns
    -------
    list of float
        ``out[S_*]``. In numpy, per bearing ``sqrt(mean(F * F))``, ``F.max()`` and
        ``sqrt(max(x * x + y * y))``; ``mean(1 / omega)``, ``omega.max()``,
        ``omega.min()``, ``p.max()``, ``p.min()``, ``T.max()``, ``T.min()``,
        ``mean(T / omega)``; per valve ``sum(where(passing | roll(passing, -1),
        (plenum - 0.5 (p + roll(p, -1))) (roll(V, -1) - V), 0))`` with ``passing`` its
        mass flow ``!= 0``, and the first and last sample of its longest circular open
        run.
    """
    out = np.empty(N_STATS)
    empty = np.empty((0, 1))
    _statistics(
        _array(cycle, "cylinder_pressure [Pa]"),
        _array(cycle, "cylinder_volume [m3]"),
        _array(cycle, "shaft_torque [N m]"),
        _array(cycle, "crank_speed [rad/s]"),
        _rows(cycle, _FORCE_COLUMNS),
        empty if pinned else _rows(cycle, _DISPLACEMENT_COLUMNS),
        _rows(cycle, _VALVE_COLUMNS) if gas else empty,
        np.array(plenum, dtype=np.float64),
        reed,
        out,
    )
    return out.tolist()  # type: ignore[no-any-return]


def compile_statistics() -> None:
    """Compile :func:`_statistics` for the types :func:`cycle_statistics` passes, on one
    sample (the first run's head start, :mod:`recipsim.results.compile_ahead`: about 2 s
    of compiling that would otherwise follow the solve)."""
    one = np.ones(1)
    rows = np.ones((_N_BEARINGS, 1))
    _statistics(one, one, one, one, rows, rows, rows, np.ones(2), True, np.empty(N_STATS))
