"""Bounded least-squares fit of case parameters to measured points.

Residuals are relative, ``predicted / measured - 1``, one per measured target value of
each calibration point. Parameters with positive bounds are fitted in their logarithm
(conductances, coefficients and loss factors act multiplicatively), others linearly over
their range. The Jacobian is a forward difference with a fixed step (1 % of the
parameter, or of its range): well above the periodic solver's noise at the tightened
cycle tolerance (:data:`SOLVER_OVERRIDES`), so the fit sees the model's trend, not its
numerical noise.

Before fitting, a problem is refused with a :class:`CalibrationError` when it is
ill-posed: more parameters than measured values; a parameter whose 1 % change moves no
residual by more than :data:`MIN_INFLUENCE`; parameters whose effects are linearly
dependent (the scaled Jacobian's condition number above :data:`MAX_CONDITION`, the
message names the combination). Confidence: the parameters' covariance from the
linearisation at the optimum, ``(J^T W J)^-1``, with ``W`` from the data's printed
resolution (a rounded catalogue figure is uniformly uncertain within half its last
digit, standard deviation ``resolution / sqrt(3)``) and, when there are more residuals
than parameters, also scaled by the residual variance (model error); the larger of the
two is reported, as a 95 % interval.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from recipsim.case.case import Case
from recipsim.errors import RecipsimError
from recipsim.studies.calibrate.data import MeasuredPoint
from recipsim.studies.calibrate.parameters import CalibrationError, Parameter
from recipsim.studies.point_warnings import kept_warnings

#: Relative step of the finite-difference Jacobian (of the parameter or of its range).
STEP = 0.01
#: A parameter moving no residual by more than this per 1 % step has no influence.
MIN_INFLUENCE = 1e-5
#: Largest condition number of the scaled Jacobian of an identifiable problem.
MAX_CONDITION = 1e6
#: Widest spread of a fitted logarithmic parameter (one standard deviation) [decades].
MAX_DECADES = 1.0
#: Solver settings of the fit's runs: a cycle tolerance well below the step's effect.
SOLVER_OVERRIDES = {"solver.cycle_tolerance": 1e-6, "solver.max_revolutions": 400}
#: Residual of a point whose run failed: far from any fit, so the fit steers away.
FAILED_RESIDUAL = 10.0


@dataclass(frozen=True)
class FitResult:
    """Outcome of :func:`fit_parameters` (values in SI)."""

    parameters: tuple[Parameter, ...]
    values: tuple[float, ...]
    std_resolution: tuple[float, ...]
    std_residual: tuple[float, ...]  # NaN when residuals = parameters
    residuals: tuple[float, ...]
    evaluations: int
    message: str

    @property
    def ci95(self) -> tuple[tuple[float, float], ...]:
        """95 % interval of each parameter from the larger standard deviation."""
        out = []
        for p, v, a, b in zip(
            self.parameters, self.values, self.std_resolution, self.std_residual, strict=True
        ):
            s = max(a, b) if math.isfinite(b) else a
            if p.logarithmic:  # std of log(value)
                out.append((v * math.exp(-1.96 * s), v * math.exp(1.96 * s)))
            else:
                out.append((v - 1.96 * s * p.span, v + 1.96 * s * p.span))
        return tuple(out)


class Residuals:
    """Relative residuals of the calibration points as a function of the fitted
    variables ``x`` (cached by ``x``: the Jacobian's base point is not run twice).

    ``sigma`` is each residual's standard deviation from the data's printed resolution
    (relative); ``evaluations`` counts the parameter sets run. ``cases``, one per point,
    runs each point on its own case (the members of a family); default ``case`` for all.
    """

    def __init__(
        self,
        case: Case,
        points: Sequence[MeasuredPoint],
        targets: Sequence[str],
        parameters: Sequence[Parameter],
        simulate: Callable[[Case], dict[str, float]],
        cases: Sequence[Case] | None = None,
    ) -> None:
        self.case, self.points, self.targets = case, points, targets
        self.cases = list(cases) if cases is not None else [case] * len(points)
        self.parameters, self.simulate = parameters, simulate
        self.sigma = np.array(
            [
                p.resolution[t] / math.sqrt(3.0) / abs(p.targets[t])
                for p in points
                for t in targets
                if t in p.targets
            ]
        )
        self._cache: dict[tuple[float, ...], np.ndarray] = {}
        self._failures: dict[tuple[float, ...], list[str]] = {}

    @property
    def evaluations(self) -> int:
        return len(self._cache)

    def __call__(self, x: np.ndarray) -> np.ndarray:
        key = tuple(float(v) for v in x)
        if key not in self._cache:
            fitted = {p.key: p.from_x(v) for p, v in zip(self.parameters, key, strict=True)}
            out = []
            failures = []
            for case, point in zip(self.cases, self.points, strict=True):
                row, why = _run_point(case, point, fitted, self.simulate)
                if row is None:
                    failures.append(f"{point.label}: {why}")
                for t in self.targets:
                    if t in point.targets:
                        predicted = row.get(t, math.nan) if row is not None else math.nan
                        r = predicted / point.targets[t] - 1.0
                        out.append(r if math.isfinite(r) else FAILED_RESIDUAL)
            self._cache[key] = np.array(out)
            self._failures[key] = failures
        return self._cache[key]

    def failures(self, x: np.ndarray) -> list[str]:
        """The points that failed at ``x`` (already run), each with its error's message."""
        return self._failures.get(tuple(float(v) for v in x), [])

    def describe(self, x: np.ndarray) -> str:
        """``x`` as the parameters' values, and the points that failed there."""
        values = ", ".join(
            f"{p.key} = {p.from_x(v):.4g}" for p, v in zip(self.parameters, x, strict=True)
        )
        failed = self.failures(x)
        if not failed:
            return f"at {values}: no point failed"
        more = f"; and {len(failed) - 1} more point(s)" if len(failed) > 1 else ""
        return f"at {values}: {failed[0]}{more}"


def _run_point(
    case: Case,
    point: MeasuredPoint,
    fitted: dict[str, float],
    simulate: Callable[[Case], dict[str, float]],
) -> tuple[dict[str, float] | None, str]:
    """The point's summary row, or None and why it failed."""
    try:  # a trial's warnings are not the calibrated case's: kept, then dropped
        with kept_warnings():
            return simulate(case.with_({**point.overrides, **SOLVER_OVERRIDES, **fitted})), ""
    except (RecipsimError, ValueError) as exc:  # ValueError: a property flash in CoolProp
        return None, str(exc)


def forward_jacobian(
    f: Callable[[np.ndarray], np.ndarray],
    x: np.ndarray,
    upper: np.ndarray | None = None,
    names: Sequence[str] | None = None,
    lower: np.ndarray | None = None,
) -> np.ndarray:
    """Forward differences with the fixed step :data:`STEP` in the fitted variables
    (the log for logarithmic parameters: a 1 % change; else 1 % of the range); a
    backward step where the forward one would pass ``upper`` (a value the case may
    refuse, such as a fraction above 1) or where a point fails the forward step, unless
    it would pass ``lower``. ``names``: the parameters' keys, for the error (a
    :class:`Residuals` ``f`` adds where a point failed and why)."""
    f0 = f(x)
    jac = np.empty((f0.size, x.size))
    for j in range(x.size):
        h = -STEP if upper is not None and x[j] + STEP > upper[j] else STEP
        step = np.array(x, dtype=float)
        step[j] += h
        moved = f(step)
        failed = (moved == FAILED_RESIDUAL) & (f0 != FAILED_RESIDUAL)
        if np.any(failed):  # a point that fails a step away: the other side, or stop
            tried = [step.copy()]
            step[j] = x[j] - h
            if lower is None or step[j] >= lower[j]:
                moved, h = f(step), -h
                failed = (moved == FAILED_RESIDUAL) & (f0 != FAILED_RESIDUAL)
                tried.append(step.copy())
            if np.any(failed):
                name = names[j] if names is not None else f"parameter {j + 1}"
                where = (
                    " (" + "; ".join(f.describe(t) for t in tried) + ")"
                    if isinstance(f, Residuals)
                    else ""
                )
                side = "on either side" if len(tried) == 2 else "and the other side is its bound"
                raise CalibrationError(
                    f"{name}: a calibration point fails a {STEP:.0%} step away from the "
                    f"current values {side}{where}; narrow the bounds"
                )
        jac[:, j] = (moved - f0) / h
    return jac


def check_identifiable(jac: np.ndarray, parameters: Sequence[Parameter]) -> None:
    """Refuse parameters without influence or with linearly dependent effects."""
    names = [p.key for p in parameters]
    influence = np.abs(jac).max(axis=0) * STEP
    dead = [n for n, i in zip(names, influence, strict=True) if not i > MIN_INFLUENCE]
    if dead:
        raise CalibrationError(
            f"{', '.join(dead)}: no influence on the fitted data (a {STEP:.0%} change moves "
            f"no fitted quantity by more than {MIN_INFLUENCE:g} relative); remove it"
        )
    if len(names) > 1:
        scaled = jac / np.linalg.norm(jac, axis=0)
        _, s, vt = np.linalg.svd(scaled, full_matrices=False)
        if s[-1] <= 0.0 or s[0] / s[-1] > MAX_CONDITION:
            weights = vt[-1]
            combo = " + ".join(
                f"{w:+.2f} {n}" for w, n in zip(weights, names, strict=True) if abs(w) > 0.1
            )
            raise CalibrationError(
                "the parameters are not separately identifiable from these data (condition "
                f"number {s[0] / max(s[-1], 1e-300):.2g}); no data constrain the combination "
                f"{combo}: fit fewer parameters or add points"
            )


def check_determined(parameters: Sequence[Parameter], std: Sequence[float]) -> None:
    """Refuse a fit whose data leave a parameter free over more than
    :data:`MAX_DECADES` decades (a logarithmic one) or over more than its whole range (a
    linear one, fitted as a fraction of its range), at one standard deviation (the larger
    of the data's resolution and the residuals' estimates)."""
    loose = []
    for p, sigma in zip(parameters, std, strict=True):
        limit = MAX_DECADES * math.log(10.0) if p.logarithmic else 1.0
        if not sigma <= limit:
            spread = f"{sigma / math.log(10.0):.3g} decades" if p.logarithmic else "its range"
            loose.append(f"{p.key} (one standard deviation spans {spread})")
    if loose:
        raise CalibrationError(
            "the data do not determine " + ", ".join(loose) + ": its effect is the same as "
            "another parameter's or too small to measure; fit fewer parameters or add points"
        )


def fit_parameters(
    case: Case,
    points: Sequence[MeasuredPoint],
    targets: Sequence[str],
    parameters: Sequence[Parameter],
    simulate: Callable[[Case], dict[str, float]],
    max_evaluations: int = 60,
    cases: Sequence[Case] | None = None,
) -> FitResult:
    """Fit ``parameters`` so the simulated ``targets`` match the measured ones.

    Parameters
    ----------
    case : Case
        The case to calibrate (its overrides included).
    points : sequence of MeasuredPoint
        The calibration points (their inputs are applied as overrides).
    targets : sequence of str
        Summary columns compared with the measurements.
    parameters : sequence of Parameter
        What is fitted, with bounds.
    simulate : callable
        ``Case -> summary row`` (:func:`recipsim.simulate`'s summary as a dict).
    max_evaluations : int
        Largest number of least-squares iterations' function evaluations.
    cases : sequence of Case, optional
        One per point: the case each point runs on (a family's members); default
        ``case``. The residuals of every member are stacked in one fit.

    Returns
    -------
    FitResult

    Raises
    ------
    CalibrationError
        Ill-posed (more parameters than measured values, a parameter without influence,
        dependent parameters) or no successful run at the optimum.
    """
    n_data = sum(t in p.targets for p in points for t in targets)
    if len(parameters) > n_data:
        raise CalibrationError(
            f"{len(parameters)} parameters cannot be fitted to {n_data} measured values: "
            "fit fewer parameters or use more points"
        )
    f = Residuals(case, points, targets, parameters, simulate, cases)
    keys = [p.key for p in parameters]
    lower = np.array([p.to_x(p.lower) for p in parameters])
    upper = np.array([p.to_x(p.upper) for p in parameters])
    x0 = np.array([p.to_x(p.initial) for p in parameters])
    x0 = np.clip(x0, lower + 1e-6 * (upper - lower), upper - 1e-6 * (upper - lower))
    check_identifiable(forward_jacobian(f, x0, upper, keys, lower), parameters)
    from scipy.optimize import least_squares  # a heavy import, needed only to fit

    result = least_squares(
        f,
        x0,
        jac=lambda x: forward_jacobian(f, x, upper, keys, lower),
        bounds=(lower, upper),
        method="trf",
        xtol=1e-4,
        ftol=1e-8,
        max_nfev=max_evaluations,
    )
    r = f(result.x)
    if np.any(r == FAILED_RESIDUAL):
        raise CalibrationError(
            f"a calibration point does not run at the fitted values ({f.describe(result.x)})"
        )
    std_by = _confidence(f, result.x, r, (lower, upper), parameters)
    return FitResult(
        parameters=tuple(parameters),
        values=tuple(p.from_x(v) for p, v in zip(parameters, result.x, strict=True)),
        std_resolution=std_by[0],
        std_residual=std_by[1],
        residuals=tuple(float(v) for v in r),
        evaluations=f.evaluations,
        message=str(result.message),
    )


def _confidence(
    f: Residuals,
    x: np.ndarray,
    r: np.ndarray,
    bounds: tuple[np.ndarray, np.ndarray],
    parameters: Sequence[Parameter],
) -> list[tuple[float, ...]]:
    """The standard deviations (:func:`_std`) at the optimum ``x``, after the checks of
    identifiability and determination there.

    A parameter that stopped acting on the way to the optimum (a loss coefficient driven
    towards its floor, where a 1 % change moves nothing) is reported with an unbounded
    interval (infinite standard deviations), not refused after the whole fit: the start
    had its influence.
    """
    lower, upper = bounds
    jac = forward_jacobian(f, x, upper, [p.key for p in parameters], lower)
    dead = np.abs(jac).max(axis=0) * STEP <= MIN_INFLUENCE
    live = [p for p, d in zip(parameters, dead, strict=True) if not d]
    if live:  # at the optimum too: effects may align there
        check_identifiable(jac[:, ~dead], live)
    std_res = _std(jac, r, f.sigma, len(parameters))
    std_by = [tuple(math.inf if d else v for v, d in zip(s, dead, strict=True)) for s in std_res]
    check_determined(
        live, [max(a, b) if b == b else a for a, b, d in zip(*std_by, dead, strict=True) if not d]
    )
    return std_by


def _std(
    jac: np.ndarray, r: np.ndarray, sigma: np.ndarray, n: int
) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """Standard deviations of the fitted variables: from the data's resolution, and
    (more residuals than parameters) from the residual variance."""
    weighted = jac / sigma[:, None]
    cov_data = np.linalg.pinv(weighted.T @ weighted)
    by_data = tuple(float(math.sqrt(max(v, 0.0))) for v in np.diag(cov_data))
    dof = r.size - n
    if dof <= 0:
        return by_data, (math.nan,) * n
    variance = float(r @ r) / dof
    cov = variance * np.linalg.pinv(jac.T @ jac)
    return by_data, tuple(float(math.sqrt(max(v, 0.0))) for v in np.diag(cov))
