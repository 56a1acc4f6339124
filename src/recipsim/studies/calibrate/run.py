"""A calibration from end to end: read the data, fit on the chosen points, predict every
point with the calibrated case, tabulate (:class:`Calibration`)."""

from __future__ import annotations

import difflib
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pandas as pd

from recipsim.case.case import Case
from recipsim.errors import CaseError, RecipsimError
from recipsim.pipeline import simulate_case
from recipsim.results.column_docs import documented
from recipsim.results.summary_docs import STARTUP_SUMMARY_DOCS, SUMMARY_DOCS
from recipsim.studies.calibrate.data import MeasuredPoint, find_data_file, read_points
from recipsim.studies.calibrate.family import Member, as_members, member_case
from recipsim.studies.calibrate.fit import FitResult, fit_parameters
from recipsim.studies.calibrate.parameters import CalibrationError, Parameter, parse_parameter
from recipsim.studies.calibrate.priors import prior_of, verdict
from recipsim.studies.calibrate.volumetric import CAPACITY, volumetric_rows
from recipsim.studies.point_warnings import kept_warnings

#: A fitted value this close (relative) to a bound ended on it: the fit's ``xtol``.
AT_BOUND_TOLERANCE = 1e-4


@dataclass(frozen=True)
class Calibration:
    """Result of :func:`calibrate_case`.

    Attributes
    ----------
    case : Case
        The case as given.
    calibrated : Case
        The case with the fitted values set (as overrides).
    fit : FitResult
        Fitted values, standard deviations, residuals.
    parameters : pandas.DataFrame
        One row per parameter: ``parameter``, ``initial``, ``lower``, ``upper``,
        ``fitted``, ``at_bound``, ``std_from_resolution [-]``, ``std_from_residuals [-]``
        (relative for logarithmic parameters), ``ci95_low``, ``ci95_high`` (SI), and its
        prior: ``plausible_low``, ``plausible_high`` (SI; empty where none is declared),
        ``plausible_source`` and ``verdict`` (:func:`.priors.verdict`).
    points : pandas.DataFrame
        One row per data row of every member: ``member`` (its data file's stem),
        ``row``, ``point``, ``used_in_fit``, ``status``, ``warnings`` (those the
        calibrated case's solve at the point logged, joined by ``"; "``), and per target
        ``measured <t>``, ``predicted <t>``, ``error <name> [-]``.
    data : str
        The family case's data file.
    members : tuple of (str, Case, str)
        Every member as (name, calibrated case, data file), the family case's first.
    volumetric : pandas.DataFrame
        Where the capacity is a target: per member, the volumetric decomposition
        (:mod:`.volumetric`) of the catalogue's capacities and of the calibrated model's,
        one row each (``member``, ``source``, the effective dead volume and the other
        losses with their 95 % intervals, ``rms [-]``, ``points [-]``).
    """

    case: Case
    calibrated: Case
    fit: FitResult
    parameters: pd.DataFrame
    points: pd.DataFrame
    data: str
    members: tuple[tuple[str, Case, str], ...] = ()
    volumetric: pd.DataFrame = field(default_factory=pd.DataFrame)


def _summary_row(case: Case) -> dict[str, Any]:

    run = simulate_case(case)
    row = run.row
    if not row.get("converged [-]", True):
        residual = row.get("cycle_residual [-]", math.nan)
        raise RecipsimError(
            f"{case.name}: not converged: cycle residual {residual:.2g} after "
            f"{row.get('revolutions [-]', '?')} revolutions ({row.get('periodic_method', '?')}; "
            f"tolerance {case.solver.cycle_tolerance:.2g})"
        )
    return dict(row)


def calibrate_case(
    case: Case,
    data: str | Path,
    parameters: Sequence[str],
    points: Sequence[int] | None = None,
    targets: Sequence[str] | None = None,
    ignore: Sequence[str] = (),
    simulate: Callable[[Case], dict[str, Any]] = _summary_row,
    members: Sequence[Member | str] = (),
) -> Calibration:
    """Fit ``parameters`` of ``case`` to the measured points of ``data`` (and of the
    family's other ``members``: one fit, the parameters shared, the residuals stacked).

    Parameters
    ----------
    case : Case
        The case to calibrate.
    data : str or Path
        CSV of measured points (:mod:`recipsim.studies.calibrate.data`), or a shipped
        catalogue's file name.
    parameters : sequence of str
        ``KEY`` or ``KEY=LOWER:UPPER`` (:func:`.parameters.parse_parameter`).
    points : sequence of int, optional
        Data rows (1-based) to fit on, in every member that does not name its own; the
        others are predicted only. Default: all.
    targets : sequence of str, optional
        Target columns; default ``cooling_capacity [W]`` and ``COP [-]``.
    ignore : sequence of str
        Data columns to leave out.
    simulate : callable
        ``Case -> summary row``; raises :class:`~recipsim.errors.RecipsimError` for a
        failed or non-converged run.
    members : sequence of Member or str
        The family's other compressors (:class:`.family.Member`, or its command-line
        form ``"DATA:bore=26.49mm"``), each with its own data file and case or bore.

    Returns
    -------
    Calibration

    Raises
    ------
    CaseError
        An invalid data file, member or case key.
    CalibrationError
        An ill-posed problem (see :mod:`.fit`).
    """
    groups, chosen = _member_groups(case, data, members, points, targets, ignore)
    specs = [parse_parameter(text, case) for text in parameters]
    if len({p.key for p in specs}) < len(specs):
        raise CalibrationError("a parameter is named twice")
    for member, member_base, measured, used in groups:
        _check_points(
            member_base, [p for p in measured if p.row in used], chosen, specs, str(member.data)
        )
    fitting = [(c, p) for _, c, measured, used in groups for p in measured if p.row in used]
    fit = fit_parameters(
        case, [p for _, p in fitting], chosen, specs, simulate, cases=[c for c, _ in fitting]
    )
    fitted = {p.key: v for p, v in zip(specs, fit.values, strict=True)}
    tables, calibrated, volumetric = [], [], []
    for member, member_base, measured, used in groups:
        own = member_base.with_(fitted)
        calibrated.append((member.name, own, str(find_data_file(member.data))))
        table = _point_table(own, measured, used, chosen, simulate)
        table.insert(0, "member", member.name)
        tables.append(table)
        volumetric += _volumetric(member.name, own, measured, table)
    return Calibration(
        case,
        calibrated[0][1],
        fit,
        _parameter_table(fit, case),
        pd.concat(tables, ignore_index=True),
        calibrated[0][2],
        tuple(calibrated),
        pd.DataFrame(volumetric),
    )


def _volumetric(
    name: str, case: Case, measured: Sequence[MeasuredPoint], table: pd.DataFrame
) -> list[dict[str, Any]]:
    """The volumetric decomposition rows of one member (:mod:`.volumetric`): its
    catalogue's capacities and the calibrated model's, at every data row (none where the
    capacity is not a target)."""
    predicted = f"predicted {CAPACITY}"
    if predicted not in table:
        return []
    cases = [case.with_(p.overrides) for p in measured]
    sources = {
        "catalogue": [p.targets.get(CAPACITY, math.nan) for p in measured],
        "model": [float(v) for v in table[predicted]],
    }
    return volumetric_rows(name, cases, sources)


_Group = tuple[Member, Case, list[MeasuredPoint], set[int]]


def _member_groups(
    case: Case,
    data: str | Path,
    members: Sequence[Member | str],
    points: Sequence[int] | None,
    targets: Sequence[str] | None,
    ignore: Sequence[str],
) -> tuple[list[_Group], list[str]]:
    """Every member (the family case's data first) with its case, its measured points
    and the rows it fits on; and the targets of all of them."""
    family = [Member(find_data_file(data), points=tuple(points) if points else None)]
    family += as_members([*members, family[0]])[:-1]  # refuses a member repeating the data
    groups: list[_Group] = []
    chosen: list[str] = []
    for member in family:
        measured, own = read_points(find_data_file(member.data), targets, ignore)
        chosen += [t for t in own if t not in chosen]
        rows = {p.row for p in measured}
        used = set(member.points or points or rows)
        unknown = sorted(used - rows)
        if unknown:
            raise CalibrationError(f"--points {unknown}: {member.name} has rows {sorted(rows)}")
        member_base = member_case(case, member) if member is not family[0] else case
        groups.append((member, member_base, measured, used))
    return groups, chosen


#: The columns a summary row can hold (the targets a fit can compare).
SUMMARY_COLUMNS = documented(SUMMARY_DOCS + STARTUP_SUMMARY_DOCS)


def _check_points(
    case: Case,
    points: Sequence[MeasuredPoint],
    targets: Sequence[str],
    specs: Sequence[Parameter],
    data: str,
) -> None:
    """Refuse, before any fit, targets that no summary has and points whose inputs the
    case refuses at the parameters' starting values (a unit in a header that does not
    fit its values, kelvin in a degC column), naming the data file, row and key: a fit
    would otherwise see every such point fail alike and blame the parameters.

    Raises
    ------
    CaseError
        Naming the data file and the column or row.
    """
    for target in targets:
        if target not in SUMMARY_COLUMNS:
            close = difflib.get_close_matches(target, sorted(SUMMARY_COLUMNS), n=1)
            hint = f"; did you mean {close[0]!r}?" if close else ""
            raise CaseError(data, target, f"a target must be a summary column{hint}")
    start = {p.key: p.initial for p in specs}
    for point in points:
        try:
            case.with_({**point.overrides, **start})
        except CaseError as exc:
            raise CaseError(data, f"row {point.row}", f"{exc.key}: {exc.message}") from None


def _at_bound(value: float, lower: float, upper: float) -> bool:
    """Whether ``value`` ended on a bound, to the fit's own resolution (``xtol`` 1e-4)."""
    tol = AT_BOUND_TOLERANCE * (upper - lower)  # for a bound at zero
    return any(
        math.isclose(value, b, rel_tol=AT_BOUND_TOLERANCE, abs_tol=tol if b == 0 else 0.0)
        for b in (lower, upper)
    )


def _parameter_table(fit: FitResult, case: Case) -> pd.DataFrame:
    rows = []
    for p, value, a, b, (low, high) in zip(
        fit.parameters, fit.values, fit.std_resolution, fit.std_residual, fit.ci95, strict=True
    ):
        bound = _at_bound(value, p.lower, p.upper)
        rows.append(
            {
                "parameter": p.key,
                "initial": p.initial,
                "lower": p.lower,
                "upper": p.upper,
                "fitted": value,
                "at_bound": bound,
                "std_from_resolution [-]": a,
                "std_from_residuals [-]": b,
                "ci95_low": low,
                "ci95_high": high,
                **_prior_columns(case, p.key, value, (low, high), bound),
            }
        )
    return pd.DataFrame(rows)


def _prior_columns(
    case: Case, key: str, value: float, interval: tuple[float, float], at_bound: bool
) -> dict[str, Any]:
    """The plausible range of ``key`` with its source, and the verdict on the fit."""
    prior = prior_of(case, key)
    return {
        "plausible_low": prior.lower if prior else math.nan,
        "plausible_high": prior.upper if prior else math.nan,
        "plausible_source": prior.source if prior else "",
        "verdict": verdict(value, interval, prior, at_bound),
    }


def _point_table(
    case: Case,
    measured: Sequence[MeasuredPoint],
    used: set[int],
    targets: Sequence[str],
    simulate: Callable[[Case], dict[str, Any]],
) -> pd.DataFrame:
    rows = []
    for point in measured:
        row: dict[str, Any] = {"row": point.row, "point": point.label}
        row["used_in_fit"] = point.row in used
        with kept_warnings() as warned:
            try:
                predicted = simulate(case.with_(point.overrides))
                row["status"] = "ok"
            except RecipsimError as exc:
                predicted, row["status"] = {}, f"failed: {exc}"
        row["warnings"] = "; ".join(warned)
        for t in targets:
            name = t.split(" [")[0]
            value = float(predicted.get(t, math.nan))
            row[f"predicted {t}"] = value
            row[f"measured {t}"] = point.targets.get(t, math.nan)
            row[f"error {name} [-]"] = (
                value / point.targets[t] - 1.0 if t in point.targets else math.nan
            )
        rows.append(row)
    return pd.DataFrame(rows)
