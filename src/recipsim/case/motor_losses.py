"""The motor circuit's keys of ``[motor]`` and the ``options.friction`` choice.

With ``options.motor = "equivalent_circuit"`` the ``[motor]`` table describes the
single-phase induction motor's equivalent circuit (:mod:`recipsim.physics.motor_circuit`)
in one of two ways:

- nameplate data (:func:`recipsim.physics.motor_nameplate.motor_circuit_from_nameplate`
  picks the circuit that reproduces them): ``type`` (``RSIR`` or ``PSC``), ``voltage``,
  ``line_frequency``, ``poles``, ``rated_speed``, the rated output (``rated_power`` or
  ``rated_torque``), ``rated_efficiency`` or ``rated_input_power``, ``rated_power_factor``
  or ``rated_current``, ``breakdown_torque_ratio`` or ``breakdown_torque``, and the
  per-unit loss assumptions ``core_loss_fraction``, ``friction_windage_fraction``,
  ``stray_loss_fraction``, ``leakage_reactance_ratio``. A PSC motor's run capacitor and
  auxiliary winding are chosen to balance the fields at the rated point;
- circuit values: ``main_resistance``, ``main_leakage_reactance``,
  ``magnetising_reactance``, ``rotor_resistance``, ``rotor_leakage_reactance`` (rotor
  referred to the main winding), optional ``core_conductance``,
  ``friction_windage_loss``, ``stray_loss_fraction``, and for ``PSC``
  ``aux_turns_ratio``, ``aux_resistance``, ``aux_leakage_reactance``, ``run_capacitance``.

The shared keys ``line_frequency``, ``poles``, ``rated_speed``, ``rated_torque`` and
``breakdown_torque`` also define the induction-motor drive's torque curve
(:mod:`recipsim.case.motor`).
"""

from __future__ import annotations

from collections.abc import Mapping
from functools import lru_cache
from typing import Any

from recipsim.errors import CaseError
from recipsim.physics.friction_models import FILM_FRICTION, FRICTION_MODELS, default_friction
from recipsim.physics.mechanics.bearing_laws.registry import BEARING_LAWS
from recipsim.physics.mechanics.crank_trains import CRANK_TRAINS
from recipsim.physics.motor_circuit import MotorCircuit
from recipsim.physics.motor_nameplate import MotorNameplate, motor_circuit_from_nameplate
from recipsim.schema import Choice, Field, Spec

_ONE = "dimensionless"
_CIRCUIT_VALUES = (
    "main_resistance",
    "main_leakage_reactance",
    "magnetising_reactance",
    "rotor_resistance",
    "rotor_leakage_reactance",
)
_AUX_VALUES = ("aux_turns_ratio", "aux_resistance", "aux_leakage_reactance", "run_capacitance")
_EXPLICIT_ONLY = (*_CIRCUIT_VALUES, "core_conductance", "friction_windage_loss", *_AUX_VALUES)
_NAMEPLATE_ONLY = (
    "rated_power",
    "rated_efficiency",
    "rated_input_power",
    "rated_power_factor",
    "rated_current",
    "breakdown_torque_ratio",
    "core_loss_fraction",
    "friction_windage_fraction",
    "leakage_reactance_ratio",
)


def _ohm(doc: str) -> Field:
    return Field("ohm", None, lo=0.0, hi=1e5, doc=doc)


CIRCUIT_SPEC: Spec = {
    "type": Choice(("RSIR", "PSC"), "RSIR", "main winding alone in run, or run capacitor"),
    "voltage": Field("V", None, lo=1.0, hi=1000.0, doc="supply voltage, rms"),
    "rated_power": Field("W", None, lo=0.0, open_lo=True, hi=1e5, doc="shaft output, rated"),
    "rated_efficiency": Field(
        _ONE,
        None,
        lo=0.0,
        hi=1.0,
        open_lo=True,
        open_hi=True,
        doc="or rated_input_power",
        plausible=(0.55, 0.88),
        plausible_source="household compressor motors: RSIR/CSIR "
        "0.65-0.80, with a run capacitor 0.75-0.88, small frames lowest (US EPA-430-R-93-009, "
        "1993: small compressors lose most in their motors); a 1/4 kW single-phase motor 0.56",
    ),
    "rated_input_power": Field("W", None, lo=0.0, open_lo=True, hi=1e5, doc="electrical"),
    "rated_power_factor": Field(
        _ONE,
        None,
        lo=0.0,
        hi=1.0,
        open_lo=True,
        doc="or rated_current",
        plausible=(0.5, 0.95),
        plausible_source="fractional-kW single-phase motors 0.55-0.75 without a run capacitor, "
        "up to 0.95 with one",
    ),
    "rated_current": Field("A", None, lo=0.0, open_lo=True, hi=1e3, doc="rms"),
    "breakdown_torque_ratio": Field(
        _ONE, None, lo=1.0, hi=10.0, open_lo=True, doc="or breakdown_torque"
    ),
    "core_loss_fraction": Field(_ONE, None, lo=0.0, hi=0.5, doc="of rated input; 0.04"),
    "friction_windage_fraction": Field(_ONE, None, lo=0.0, hi=0.5, doc="of rated output; 0.01"),
    "stray_loss_fraction": Field(_ONE, None, lo=0.0, hi=0.5, doc="of output; default IEC"),
    "leakage_reactance_ratio": Field(_ONE, None, lo=0.05, hi=20.0, doc="X1 / X2; 1"),
    "main_resistance": _ohm("R1m"),
    "main_leakage_reactance": _ohm("X1m"),
    "magnetising_reactance": _ohm("Xm"),
    "rotor_resistance": _ohm("R2, referred to the main winding"),
    "rotor_leakage_reactance": _ohm("X2, referred to the main winding"),
    "core_conductance": Field("S", None, lo=0.0, hi=10.0, doc="core loss G_c V^2"),
    "friction_windage_loss": Field("W", None, lo=0.0, hi=1e4, doc="at synchronous speed"),
    "aux_turns_ratio": Field(_ONE, None, lo=0.0, hi=10.0, open_lo=True, doc="PSC"),
    "aux_resistance": _ohm("R1a (PSC)"),
    "aux_leakage_reactance": _ohm("X1a (PSC)"),
    "run_capacitance": Field("F", None, lo=0.0, hi=0.01, open_lo=True, doc="PSC"),
}


@lru_cache(maxsize=32)
def _fitted_circuit(plate: MotorNameplate) -> MotorCircuit:
    """The nameplate's circuit
    (:func:`~recipsim.physics.motor_nameplate.motor_circuit_from_nameplate`), fitted once
    per nameplate in a process: the points of a sweep that share a motor share its fit."""
    return motor_circuit_from_nameplate(plate)


def _or(value: float | None, default: float) -> float:
    """``value``, or the nameplate's per-unit default where the case gives none."""
    return default if value is None else value


def _exactly_one(v: Mapping[str, Any], a: str, b: str, file: str) -> str:
    if (v[a] is None) == (v[b] is None):
        raise CaseError(file, f"motor.{a}", f"give exactly one of {a} and {b}")
    return a if v[a] is not None else b


def _explicit_circuit(v: Mapping[str, Any], raw: Mapping[str, Any], file: str) -> MotorCircuit:
    mixed = [k for k in _NAMEPLATE_ONLY if k in raw]
    if mixed:
        raise CaseError(
            file, f"motor.{mixed[0]}", "give nameplate data or circuit values, not both"
        )
    needed = ["voltage", *_CIRCUIT_VALUES] + (list(_AUX_VALUES) if v["type"] == "PSC" else [])
    for key in needed:
        if v[key] is None:
            raise CaseError(file, f"motor.{key}", f"required by a {v['type']} circuit")
    extra = {k: float(v[k]) for k in _AUX_VALUES if v[k] is not None}
    return MotorCircuit(
        voltage=v["voltage"],
        frequency=v["line_frequency"],
        poles=int(v["poles"]),
        **{k: float(v[k]) for k in _CIRCUIT_VALUES},
        core_conductance=v["core_conductance"] or 0.0,
        friction_windage_loss=v["friction_windage_loss"] or 0.0,
        stray_loss_fraction=v["stray_loss_fraction"] or 0.0,
        variant=v["type"],
        **extra,
    )


def _nameplate(v: Mapping[str, Any], raw: Mapping[str, Any], file: str) -> MotorNameplate:
    explicit = [k for k in _EXPLICIT_ONLY if k in raw]
    if explicit:
        raise CaseError(
            file,
            f"motor.{explicit[0]}",
            "give nameplate data or circuit values, not both (with nameplate data a PSC "
            "motor's run capacitor is chosen to balance the fields at the rated point)",
        )
    for key in ("voltage", "rated_speed"):
        if v[key] is None:
            raise CaseError(file, f"motor.{key}", "required by the motor's nameplate data")
    speed = v["rated_speed"]
    output = v["rated_power"]
    if _exactly_one(v, "rated_power", "rated_torque", file) == "rated_torque":
        output = v["rated_torque"] * speed
    ratio = v["breakdown_torque_ratio"]
    if _exactly_one(v, "breakdown_torque_ratio", "breakdown_torque", file) == "breakdown_torque":
        ratio = v["breakdown_torque"] * speed / output
    _exactly_one(v, "rated_efficiency", "rated_input_power", file)
    _exactly_one(v, "rated_power_factor", "rated_current", file)
    return MotorNameplate(
        voltage=v["voltage"],
        frequency=v["line_frequency"],
        poles=int(v["poles"]),
        rated_output=output,
        rated_speed=speed,
        breakdown_torque_ratio=ratio,
        rated_efficiency=v["rated_efficiency"],
        rated_input_power=v["rated_input_power"],
        rated_power_factor=v["rated_power_factor"],
        rated_current=v["rated_current"],
        variant=v["type"],
        core_loss_fraction=_or(v["core_loss_fraction"], 0.04),
        friction_windage_fraction=_or(v["friction_windage_fraction"], 0.01),
        stray_loss_fraction=v["stray_loss_fraction"],
        leakage_reactance_ratio=_or(v["leakage_reactance_ratio"], 1.0),
    )


def motor_circuit_from_table(
    values: Mapping[str, Any], raw: Mapping[str, Any], file: str
) -> MotorCircuit:
    """The motor's equivalent circuit from the ``[motor]`` table.

    Parameters
    ----------
    values : mapping
        The table read in SI (:func:`recipsim.case.motor.read_motor_table`).
    raw : mapping
        The table as written (which keys the case gives).
    file : str
        The case file, for messages.

    Returns
    -------
    MotorCircuit

    Raises
    ------
    CaseError
        Missing or mixed keys, or nameplate data that no circuit reproduces.
    """
    explicit = any(k in raw for k in _CIRCUIT_VALUES)
    try:
        if explicit:
            return _explicit_circuit(values, raw, file)
        return _fitted_circuit(_nameplate(values, raw, file))
    except ValueError as exc:
        raise CaseError(file, "motor", str(exc)) from None


def friction_option(options: Any, mechanism: Any, file: str) -> str:
    """``options.friction`` resolved: ``films`` where the flexible crank runs a bearing on
    an oil film (whose friction the dynamics already carry), else ``off`` by default.

    Raises
    ------
    CaseError
        ``films`` without a film bearing, or ``off``/``mean`` with one (the films'
        friction cannot be switched off or counted twice).
    """
    films = CRANK_TRAINS[options.mechanics].flexible and any(
        BEARING_LAWS[b.law].film for b in mechanism.bearings
    )
    chosen = options.friction
    if chosen is None:
        return default_friction(films).name
    if films and not FRICTION_MODELS[chosen].on_films:
        raise CaseError(
            file,
            "options.friction",
            f"{chosen!r} with bearings on oil films: their friction is part of the dynamics; "
            f"use {FILM_FRICTION.name!r}, or linear bearing laws",
        )
    if FRICTION_MODELS[chosen].on_films and not films:
        raise CaseError(
            file,
            "options.friction",
            f"{chosen!r} needs the flexible crank with a bearing on an oil film (short_journal, "
            "finite_journal, skirt_film); the rigid crank takes 'mean' or 'off'",
        )
    return str(chosen)


__all__ = ["CIRCUIT_SPEC", "friction_option", "motor_circuit_from_table"]
