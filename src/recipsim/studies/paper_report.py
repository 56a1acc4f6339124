"""Files of the paper's study: figures, ``study.json`` and ``README.md`` (the reading of
:func:`recipsim.studies.paper.write_paper_study`), and the answer to the paper's
conclusion 3 from the hydrodynamic column.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from recipsim.report.mechanics_plots import (
    plot_bearing_loads,
    plot_drive_torque,
    plot_orbits,
    save_figure,
)
from recipsim.studies.paper_hydrodynamic import HYDRODYNAMIC_CONFIGURATIONS, JOURNALS
from recipsim.studies.paper_runs import (
    CONFIGURATIONS,
    HYDRODYNAMIC_RUNS,
    LABELS,
    PINNED_OF,
    RUNS,
    PaperStudy,
)

#: Largest relative RMS difference from pinned [-] that the summary calls "close" (the
#: damped linear bearings' margin in the paper's own reading of its Table 1).
CLOSE_TO_PINNED = 0.05


def write_figures(study: PaperStudy, directory: Path) -> list[Path]:
    """Write the study's figures into ``directory``; returns their paths.

    ``bearing_loads_<config>.png`` (pinned, flexible and, where run, hydrodynamic),
    ``orbits.png`` (flexible runs), ``orbits_hydrodynamic.png`` (film journals inside
    their clearance circles, when the column was run), ``drive_torque.png``.
    """
    c = study.cycles
    written = []
    for config in CONFIGURATIONS:
        tables = {"pinned": c[PINNED_OF[config]], "flexible": c[f"{config}_flexible"]}
        if f"{config}_hydrodynamic" in c:
            tables["hydrodynamic"] = c[f"{config}_hydrodynamic"]
        fig = plot_bearing_loads(tables, title=f"bearing loads: {LABELS[config]}")
        written.append(save_figure(fig, directory / f"bearing_loads_{config}.png"))
    orbit_tables = {LABELS[k]: c[f"{k}_flexible"] for k in CONFIGURATIONS}
    fig = plot_orbits(orbit_tables, title="orbits of the primary and secondary bearings")
    written.append(save_figure(fig, directory / "orbits.png"))
    if study.hydrodynamic:
        films = {LABELS[k]: c[f"{k}_hydrodynamic"] for k in study.hydrodynamic}
        fig = plot_orbits(
            films,
            bearings=JOURNALS,
            title="hydrodynamic journals: orbits in the clearance circle (x: smallest film)",
        )
        written.append(save_figure(fig, directory / "orbits_hydrodynamic.png"))
    torque_tables = {
        "pinned, inertia": c["inertia_pinned"],
        "pinned, gas": c["gas_pinned"],
        "flexible, inertia": c["inertia_flexible"],
        "flexible, gas": c["gas_flexible"],
        "flexible, gas + damping": c["gas_damped_flexible"],
    }
    if "gas_hydrodynamic" in c:
        torque_tables["hydrodynamic, gas"] = c["gas_hydrodynamic"]
    written.append(save_figure(plot_drive_torque(torque_tables), directory / "drive_torque.png"))
    return written


def _json_value(value: Any) -> Any:
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def study_summary(study: PaperStudy, files: list[str]) -> dict[str, Any]:
    """The content of ``study.json``: settings, runs, timings, Table 1, conclusion 3."""
    runs = [
        {k: _json_value(v) for k, v in record.__dict__.items()} for record in study.runs.values()
    ]
    table = {
        row["bearing"]: {k: _json_value(float(v)) for k, v in row.items() if k != "bearing"}
        for row in study.table1.to_dict(orient="records")
    }
    info: dict[str, Any] = {
        "settings": study.settings,
        "runs": runs,
        "timings [s]": study.timings,
        "table1": table,
    }
    if study.hydrodynamic:
        info["films"] = {
            config: {k: _json_value(v) for k, v in film_rows(run.summary).items()}
            for config, run in study.hydrodynamic.items()
        }
        info["conclusion_3"] = conclusion_three(study.table1)
    info["files"] = files
    return info


def film_rows(summary: dict[str, Any]) -> dict[str, float]:
    """Film results of one hydrodynamic run: smallest film [m], largest eccentricity
    ratio [-], peak film pressure [Pa] and friction power [W] per journal."""
    keys = (
        "min_film_thickness_{} [m]",
        "max_eccentricity_ratio_{} [-]",
        "max_film_pressure_{} [Pa]",
        "friction_power_{} [W]",
    )
    return {k.format(j): float(summary[k.format(j)]) for j in JOURNALS for k in keys}


def conclusion_three(table1: pd.DataFrame) -> str:
    """The paper's conclusion 3 (hydrodynamic loads close to pinned) tested on Table 1.

    Parameters
    ----------
    table1 : pandas.DataFrame
        The study's Table 1 with the hydrodynamic columns.

    Returns
    -------
    str
        One paragraph: whether the journals' RMS loads on films are within
        :data:`CLOSE_TO_PINNED` of pinned for every load, with the figures.
    """
    t = table1.set_index("bearing")
    journals = list(JOURNALS)
    worst_rms: dict[str, float] = {}
    worst_peak: dict[str, float] = {}
    for config in HYDRODYNAMIC_CONFIGURATIONS:
        rel = t.loc[journals, f"{config}_hydrodynamic_vs_pinned [-]"].to_numpy(dtype=float)
        peak = t.loc[journals, f"{config}_hydrodynamic_peak [N]"].to_numpy(dtype=float)
        pinned_peak = t.loc[journals, f"{PINNED_OF[config]}_peak [N]"].to_numpy(dtype=float)
        worst_rms[config] = float(np.max(np.abs(rel)))
        worst_peak[config] = float(np.max(np.abs(peak / pinned_peak - 1.0)))
    undamped = float(t.loc[journals, "gas_flexible_vs_pinned [-]"].abs().max())
    holds = max(worst_rms.values()) < CLOSE_TO_PINNED
    verdict = "holds" if holds else "does not hold"
    return (
        f"Conclusion 3 (hydrodynamic bearing loads close to the pinned ones) {verdict} here: "
        f"on oil films the journals' RMS loads are within "
        f"{100.0 * worst_rms['inertia']:.2f} % of pinned under the inertia load and "
        f"{100.0 * worst_rms['gas']:.2f} % under the gas load (peaks within "
        f"{100.0 * worst_peak['inertia']:.2f} % and {100.0 * worst_peak['gas']:.2f} %), "
        f"against up to {100.0 * undamped:.0f} % for the undamped linear bearings "
        f"(threshold {100.0 * CLOSE_TO_PINNED:.0f} %)."
    )


def _rms_rows(study: PaperStudy) -> list[str]:
    hydro = bool(study.hydrodynamic)
    runs = [*RUNS, *(HYDRODYNAMIC_RUNS if hydro else ())]
    head = "| bearing | " + " | ".join(r.replace("_", " ") for r in runs) + " |"
    lines = [head, "|" + " --- |" * (len(runs) + 1)]
    for _, row in study.table1.iterrows():
        cells = [str(row["bearing"])]
        for run in runs:
            cell = f"{row[f'{run}_rms [N]']:.1f}"
            config, model = run.rsplit("_", 1)
            if model != "pinned":
                cell += f" ({100.0 * row[f'{config}_{model}_vs_pinned [-]']:+.1f} %)"
            cells.append(cell)
        lines.append("| " + " | ".join(cells) + " |")
    return lines


def _film_lines(study: PaperStudy) -> list[str]:
    lines = [
        "",
        "Oil films of the hydrodynamic runs:",
        "",
        "| load | journal | smallest film [um] | largest eccentricity ratio [-] "
        "| peak film pressure [MPa] | friction power [W] |",
        "| --- | --- | --- | --- | --- | --- |",
    ]
    for config, run in study.hydrodynamic.items():
        s = run.summary
        for j in JOURNALS:
            lines.append(
                f"| {config} | {j} | {1e6 * s[f'min_film_thickness_{j} [m]']:.2f} "
                f"| {s[f'max_eccentricity_ratio_{j} [-]']:.3f} "
                f"| {1e-6 * s[f'max_film_pressure_{j} [Pa]']:.2f} "
                f"| {s[f'friction_power_{j} [W]']:.2f} |"
            )
    return lines + ["", conclusion_three(study.table1)]


def readme(study: PaperStudy, files: list[str]) -> str:
    """The content of the study's ``README.md``."""
    s = study.settings
    lines = [
        "# Bearing loads: pinned against flexible crank train",
        "",
        "The study of Kurka, Paulino & Izuka (ISMA 2010), section 4 and Table 1, run by",
        f"`recipsim.studies.paper.run_paper_study` (recipsim {s['recipsim']}).",
        "",
        f"- speed {s['crank_speed [rpm]']:.1f} rpm,"
        f" shell pressure {s['shell_pressure [Pa]']:.4g} Pa,"
        f" drive `{s['drive']}`, `{s['method']}` at rtol {s['rtol']:g},"
        f" {s['samples_per_revolution']} samples per revolution;",
        f"- undamped runs: {s['undamped_runs']};",
        f"- damped run: {s['damped_run']} (tolerance {s['periodic_tolerance']:g}).",
    ]
    if study.hydrodynamic:
        lines.append(f"- hydrodynamic runs: {s['hydrodynamic']['description']}.")
    lines += [
        "",
        "| run | mode | revolutions | converged | wall time [s] |",
        "| --- | --- | --- | --- | --- |",
    ]
    for r in study.runs.values():
        converged = "n/a (not tested)" if r.converged is None else ("yes" if r.converged else "NO")
        lines.append(f"| {r.name} | {r.mode} | {r.revolutions} | {converged} | {r.wall_time:.2f} |")
    lines += ["", "RMS bearing loads [N] (against pinned in brackets):", "", *_rms_rows(study)]
    if study.hydrodynamic:
        lines += _film_lines(study)
    lines += ["", "Files: " + ", ".join(f"`{f}`" for f in files) + ".", ""]
    return "\n".join(lines)
