"""Volumetric decomposition of a compressor's capacities: its effective dead volume and
the losses that do not grow with the pressure ratio.

The classic reading of a catalogue: at each point the volumetric efficiency
``eta_v = mdot / (rho_s V n)`` (``mdot`` the capacity over the rating's enthalpy
difference, ``rho_s`` the suction gas at the rating's suction temperature, ``V`` the swept
volume, ``n`` the nominal speed) is fitted, by linear least squares over the points, to

    eta_v = 1 - x - (V_d / V) R,    R = rho(p_d, s_s) / rho_s - 1,

``R`` the volume a unit of dead volume re-expands to: the gas it holds at discharge
pressure, expanded isentropically from the suction state's entropy (Stoecker and Jones,
*Refrigeration and Air Conditioning*, 2nd ed., sec. 12.3, for the clearance volumetric
efficiency). ``V_d`` is the **effective dead volume** [m3]: the metal's dead volume and
every loss that grows with the pressure ratio like it (leakage through the piston gap, a
reed that opens late at low suction density, suction heating that grows as the
evaporating temperature falls). ``x`` holds the **other losses** [-], those that do not
(the suction gas's mean heating and pressure drops, the motor's slip from the nominal
speed). Done on the catalogue and on the model's predictions of the same points, the two
decompositions say which kind of loss the model has too much or too little of; over the
members of a family they say how each kind scales with the bore (a shared valve plate
gives every member the same dead volume).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from recipsim.case.case import Case
from recipsim.physics.thermo.fluid import Fluid
from recipsim.results.electrical import rating_enthalpies

#: Fewest points a decomposition is fitted to (two unknowns and a residual).
MIN_POINTS = 3
#: Two-sided 95 % quantile of Student's t by degrees of freedom (1..10; 1.96 beyond).
_T95 = (12.71, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228)


@dataclass(frozen=True)
class VolumetricFit:
    """A decomposition (see the module docstring).

    Attributes
    ----------
    dead_volume : float
        Effective dead volume ``V_d`` [m3].
    dead_volume_ci95 : tuple of float
        Its 95 % interval [m3].
    other_losses : float
        ``x`` [-].
    other_losses_ci95 : tuple of float
        Its 95 % interval [-].
    rms : float
        Root mean square of the fit's residuals in ``eta_v`` [-].
    points : int
        Points fitted.
    """

    dead_volume: float
    dead_volume_ci95: tuple[float, float]
    other_losses: float
    other_losses_ci95: tuple[float, float]
    rms: float
    points: int


def volumetric_point(case: Case, capacity: float) -> tuple[float, float]:
    """The volumetric efficiency ``eta_v`` [-] of ``capacity`` [W] at ``case``'s operating
    point and its re-expansion ratio ``R`` [-] (module docstring), with CoolProp's HEOS."""
    fluid = Fluid(case.refrigerant.coolprop_name)
    op = case.operating_point
    h_gas, h_liquid = rating_enthalpies(fluid, op)
    gas = fluid.state_pt(op.suction_pressure, op.suction_temperature)
    swept_per_second = case.geometry.swept_volume * op.shaft_speed / (2.0 * math.pi)
    eta = capacity / (h_gas - h_liquid) / (gas["rho"] * swept_per_second)
    discharged = fluid.state_ps(op.discharge_pressure, gas["s"])
    return eta, discharged["rho"] / gas["rho"] - 1.0


def fit_volumetric(
    efficiencies: Sequence[float], ratios: Sequence[float], swept_volume: float
) -> VolumetricFit:
    """Least-squares ``eta_v = 1 - x - (V_d / V) R`` over points (``efficiencies``
    ``eta_v`` [-], ``ratios`` ``R`` [-]) of a compressor of ``swept_volume`` ``V`` [m3].

    Raises
    ------
    ValueError
        With fewer than :data:`MIN_POINTS` finite points, or all at one ``R``.
    """
    eta = np.asarray(efficiencies, dtype=float)
    r = np.asarray(ratios, dtype=float)
    finite = np.isfinite(eta) & np.isfinite(r)
    eta, r = eta[finite], r[finite]
    if eta.size < MIN_POINTS or np.ptp(r) <= 1e-9 * np.max(np.abs(r)):
        raise ValueError(
            f"a volumetric decomposition needs {MIN_POINTS} points at different pressure "
            f"ratios ({eta.size} given)"
        )
    design = np.column_stack([np.ones_like(r), -r / swept_volume])
    (intercept, dead), *_ = np.linalg.lstsq(design, eta, rcond=None)
    residual = eta - design @ np.array([intercept, dead])
    dof = eta.size - 2
    variance = float(residual @ residual) / dof if dof > 0 else math.nan
    std = np.sqrt(np.diag(variance * np.linalg.inv(design.T @ design)))
    t = _T95[dof - 1] if dof <= len(_T95) else 1.96
    loss = 1.0 - float(intercept)
    return VolumetricFit(
        dead_volume=float(dead),
        dead_volume_ci95=(float(dead - t * std[1]), float(dead + t * std[1])),
        other_losses=loss,
        other_losses_ci95=(loss - t * float(std[0]), loss + t * float(std[0])),
        rms=float(np.sqrt(np.mean(residual * residual))),
        points=int(eta.size),
    )


def decompose(cases: Sequence[Case], capacities: Sequence[float]) -> VolumetricFit:
    """:func:`fit_volumetric` of ``capacities`` [W], each at its case's operating point
    (one compressor: the swept volume of the first case)."""
    points = [
        volumetric_point(c, q) if math.isfinite(q) else (math.nan, math.nan)
        for c, q in zip(cases, capacities, strict=True)
    ]
    efficiencies = [eta for eta, _ in points]
    ratios = [r for _, r in points]
    return fit_volumetric(efficiencies, ratios, cases[0].geometry.swept_volume)


#: The capacity column a decomposition reads.
CAPACITY = "cooling_capacity [W]"


def volumetric_rows(
    member: str, cases: Sequence[Case], sources: Mapping[str, Sequence[float]]
) -> list[dict[str, object]]:
    """Rows of a decomposition table for one compressor ``member``: one per source of
    capacities [W] (``{"catalogue": [...], "model": [...]}``, each at ``cases``' operating
    points); a source with too few finite points is left out."""
    rows: list[dict[str, object]] = []
    for source, capacities in sources.items():
        try:
            fit = decompose(cases, capacities)
        except ValueError:
            continue
        rows.append(
            {
                "member": member,
                "source": source,
                "effective_dead_volume [m3]": fit.dead_volume,
                "effective_dead_volume_ci95_low [m3]": fit.dead_volume_ci95[0],
                "effective_dead_volume_ci95_high [m3]": fit.dead_volume_ci95[1],
                "other_losses [-]": fit.other_losses,
                "other_losses_ci95_low [-]": fit.other_losses_ci95[0],
                "other_losses_ci95_high [-]": fit.other_losses_ci95[1],
                "rms [-]": fit.rms,
                "points [-]": fit.points,
            }
        )
    return rows
