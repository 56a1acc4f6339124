"""Write a calibration: ``parameters.csv``, ``points.csv``, ``volumetric.csv`` (where the
capacity was a target), ``calibration.json`` and the calibrated case (``case.toml``, fully
resolved, with its refrigerant file), into one directory replaced atomically."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

from recipsim.atomic import atomic_directory
from recipsim.report.resolved_case import resolved_case
from recipsim.studies.calibrate.run import Calibration


def _finite(value: Any) -> Any:
    return None if isinstance(value, float) and not math.isfinite(value) else value


def write_calibration(calibration: Calibration, out_dir: str | Path) -> Path:
    """Write ``calibration`` into ``out_dir`` (replaced whole); returns the directory."""
    target = Path(out_dir)
    text, files = resolved_case(calibration.calibrated)
    fit = calibration.fit
    against = (
        ", ".join(Path(d).name for _, _, d in calibration.members) or Path(calibration.data).name
    )
    table = calibration.parameters
    verdicts = dict(zip(table["parameter"], table["verdict"], strict=True))
    header = [
        f"# Calibrated by `recipsim calibrate` against {against}:",
    ] + [
        f"#   {p.key} = {v:.6g} (from {p.initial:.6g}, bounds {p.lower:g}..{p.upper:g}; "
        f"{verdicts.get(p.key, '')})"
        for p, v in zip(fit.parameters, fit.values, strict=True)
    ]
    meta = {
        "case": calibration.case.path,
        "overrides": list(calibration.case.overrides),
        "data": calibration.data,
        "members": {name: data for name, _, data in calibration.members},
        "fit_message": fit.message,
        "evaluations": fit.evaluations,
        "residuals": [_finite(r) for r in fit.residuals],
        "parameters": {
            p.key: {
                "fitted": v,
                "initial": p.initial,
                "lower": p.lower,
                "upper": p.upper,
                "verdict": verdicts.get(p.key, ""),
            }
            for p, v in zip(fit.parameters, fit.values, strict=True)
        },
    }
    with atomic_directory(target) as tmp:
        calibration.parameters.to_csv(tmp / "parameters.csv", index=False)
        calibration.points.to_csv(tmp / "points.csv", index=False)
        if not calibration.volumetric.empty:
            calibration.volumetric.to_csv(tmp / "volumetric.csv", index=False)
        (tmp / "calibration.json").write_text(json.dumps(meta, indent=2) + "\n")
        (tmp / "case.toml").write_text("\n".join(header) + "\n" + text)
        for relative, content in files.items():
            (tmp / relative).parent.mkdir(parents=True, exist_ok=True)
            (tmp / relative).write_bytes(content)
    return target
