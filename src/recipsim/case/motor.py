"""The ``[motor]`` table of a case: nameplate values of the induction motor, validated,
and the breakdown slip fitted so that the torque curve
(:func:`recipsim.physics.motor.induction_motor_torque`) passes through the rated point.

The same table carries the equivalent circuit's keys (:mod:`recipsim.case.motor_losses`):
:data:`MOTOR_SPEC` declares both; the torque curve's keys are required only where the
curve is built.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Any

from recipsim.case.motor_losses import CIRCUIT_SPEC, motor_circuit_from_table
from recipsim.errors import CaseError
from recipsim.physics.mechanics.drives import DRIVES
from recipsim.physics.motor import MotorSpec, kloss
from recipsim.physics.motor_circuit import MotorCircuit
from recipsim.physics.motor_models import MOTOR_MODELS
from recipsim.schema import Field, Spec, read_table

CURVE_SPEC: Spec = {
    "line_frequency": Field("Hz", 50.0, lo=1.0, hi=1000.0, doc="supply frequency"),
    "poles": Field("dimensionless", 2, lo=2, hi=24, integer=True, doc="even"),
    "rated_speed": Field("rad/s", None, lo=0.0, open_lo=True, doc="e.g. '2900 rpm'"),
    "rated_torque": Field("N*m", None, lo=0.0, open_lo=True),
    "breakdown_torque": Field("N*m", None, lo=0.0, open_lo=True, doc="peak of the forward field"),
    "backward_field_ratio": Field(
        "dimensionless", 0.0, lo=0.0, hi=1.0, doc="0 balanced capacitor motor, 1 main winding"
    ),
    "rated_displacement": Field(
        "m^3", None, lo=0.0, hi=0.01, open_lo=True,
        doc="the displacement this motor is matched to: a case with another displacement "
        "(a member of the family with another bore) gets the rated and breakdown torques, "
        "powers and current scaled in proportion, at the same speed, efficiency and power "
        "factor",
    ),
}  # fmt: skip
#: Keys of a motor matched to a displacement that scale with it (torques, powers, current).
DISPLACEMENT_SCALED = (
    "rated_torque",
    "breakdown_torque",
    "rated_power",
    "rated_input_power",
    "rated_current",
)
#: every key of ``[motor]``: the torque curve's and the equivalent circuit's
MOTOR_SPEC: Spec = {**CURVE_SPEC, **CIRCUIT_SPEC}
#: keys the torque curve needs (required where it is built)
CURVE_REQUIRED = ("rated_speed", "rated_torque", "breakdown_torque")


def read_motor_table(raw: Any, file: str) -> dict[str, Any]:
    """Every key of the ``[motor]`` table in SI (None where not given).

    Raises
    ------
    CaseError
        For an unknown key, a value out of range or of the wrong dimension.
    """
    return read_table(raw, MOTOR_SPEC, file, "motor")


@lru_cache(maxsize=256)
def breakdown_slip(s_r: float, rated_torque: float, t_k: float, u: float) -> float | None:
    """The breakdown slip [-] that puts the torque curve through the rated point.

    Parameters
    ----------
    s_r : float
        Rated slip [-].
    rated_torque, t_k : float
        Rated and breakdown torque [N m].
    u : float
        Backward-field ratio [-].

    Returns
    -------
    float or None
        None when no curve passes through the rated point. Found once per motor and
        process (a sweep validates its case at every point).
    """

    def excess(s_k: float) -> float:  # decreasing in s_k on (s_r, inf)
        return t_k * (kloss(s_r, s_k) - u * kloss(2.0 - s_r, s_k)) - rated_torque

    s_hi = 1e3
    if excess(s_r) <= 0.0:
        return None
    # bisection on the bracket (not scipy.optimize's brentq: loading a case would then
    # import scipy.optimize); 200 halvings reach adjacent floats
    s_lo = s_r
    for _ in range(200):
        mid = 0.5 * (s_lo + s_hi)
        if mid in (s_lo, s_hi):
            break
        if excess(mid) > 0.0:
            s_lo = mid
        else:
            s_hi = mid
    return 0.5 * (s_lo + s_hi)


def motor_from_table(raw: Any, file: str) -> MotorSpec:
    """Validate the ``[motor]`` table and fit the breakdown slip to the rated point.

    Raises
    ------
    CaseError
        Naming the file and key: a rated speed at or above synchronous speed, a
        breakdown torque not above the rated torque, or a curve that cannot pass
        through the rated point.
    """
    v = read_motor_table(raw, file)
    for key in CURVE_REQUIRED:
        if v[key] is None:
            raise CaseError(file, f"motor.{key}", "missing required key (the torque curve's)")
    poles = int(v["poles"])
    if poles % 2:
        raise CaseError(file, "motor.poles", f"{poles} is odd; a motor has pole pairs")
    sync = 4.0 * math.pi * v["line_frequency"] / poles
    rated_speed, rated_torque = v["rated_speed"], v["rated_torque"]
    t_k, u = v["breakdown_torque"], v["backward_field_ratio"]
    if rated_speed >= sync:
        raise CaseError(
            file,
            "motor.rated_speed",
            f"{rated_speed * 30 / math.pi:.1f} rpm is not below the synchronous speed "
            f"{sync * 30 / math.pi:.1f} rpm ({v['line_frequency']:g} Hz, {poles} poles)",
        )
    if t_k <= rated_torque:
        raise CaseError(
            file,
            "motor.breakdown_torque",
            f"{t_k:g} N m must exceed the rated torque {rated_torque:g} N m",
        )
    s_r = (sync - rated_speed) / sync
    s_k = breakdown_slip(s_r, rated_torque, t_k, u)
    if s_k is None:
        raise CaseError(
            file,
            "motor.backward_field_ratio",
            f"{u:g} leaves no curve through the rated point with this breakdown torque; "
            "lower it or raise motor.breakdown_torque",
        )
    return MotorSpec(
        line_frequency=float(v["line_frequency"]),
        poles=poles,
        rated_speed=rated_speed,
        rated_torque=rated_torque,
        breakdown_torque=t_k,
        backward_field_ratio=u,
        breakdown_slip=s_k,
    )


def matched_to_displacement(raw: Any, swept_volume: float | None, file: str) -> Any:
    """The ``[motor]`` table as written, with the keys of :data:`DISPLACEMENT_SCALED`
    scaled by ``swept_volume / rated_displacement`` (in SI) where the table gives a
    ``rated_displacement`` and the case's swept volume [m3] is known."""
    if raw is None or swept_volume is None:
        return raw
    values = read_motor_table(raw, file)
    rated = values["rated_displacement"]
    if rated is None:
        return raw
    ratio = swept_volume / rated
    scaled = dict(raw)
    for key in DISPLACEMENT_SCALED:
        if values.get(key) is not None:
            scaled[key] = values[key] * ratio
    return scaled


def case_motor(
    raw: Any, drive: str, motor: str, file: str, swept_volume: float | None = None
) -> tuple[MotorSpec | None, MotorCircuit | None]:
    """The ``[motor]`` table of a case: the torque curve (required by the induction motor
    drive, built whenever its keys are there: a study may switch the drive with ``--set``)
    and the equivalent circuit (``options.motor = "equivalent_circuit"``).

    Parameters
    ----------
    raw : mapping or None
        The table as written (None: the case has none).
    drive, motor : str
        ``options.drive`` and ``options.motor``.
    file : str
        The case file, for messages.
    swept_volume : float, optional
        The case's displacement [m3], for a motor matched to one
        (:func:`matched_to_displacement`).

    Raises
    ------
    CaseError
        A table missing where needed, or its keys invalid.
    """
    raw = matched_to_displacement(raw, swept_volume, file)
    if raw is None:
        if DRIVES[drive].motor_curve or MOTOR_MODELS[motor].circuit:
            need = f"options.drive = {drive!r}"
            if not DRIVES[drive].motor_curve:
                need = f"options.motor = {motor!r}"
            raise CaseError(
                file,
                "motor",
                f"{need} needs a [motor] table: rated_speed, rated_torque, "
                "breakdown_torque (line_frequency, poles, backward_field_ratio optional); the "
                "equivalent circuit also voltage, rated_efficiency, rated_power_factor",
            )
        return None, None
    values = read_motor_table(raw, file)
    spec = None
    if DRIVES[drive].motor_curve or all(values[k] is not None for k in CURVE_REQUIRED):
        spec = motor_from_table(raw, file)
    if not MOTOR_MODELS[motor].circuit:
        return spec, None
    return spec, motor_circuit_from_table(values, raw, file)


def check_motor_speed(
    circuit: MotorCircuit | None, drive: str, shaft_speed: float, file: str
) -> None:
    """Refuse a constant shaft speed [rad/s] at or above the synchronous speed of the
    equivalent circuit (None: the case has none, nothing to check).

    Raises
    ------
    CaseError
        Naming ``operating_point.shaft_speed``.
    """
    if (
        circuit is not None
        and not DRIVES[drive].free_speed
        and shaft_speed >= circuit.synchronous_speed
    ):
        raise CaseError(
            file,
            "operating_point.shaft_speed",
            f"{shaft_speed * 30 / math.pi:.1f} rpm: an induction motor cannot drive the shaft "
            f"at or above its synchronous speed {circuit.synchronous_speed * 30 / math.pi:.1f} "
            "rpm ([motor] line_frequency, poles)",
        )
