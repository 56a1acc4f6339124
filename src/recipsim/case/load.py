"""Load and validate a case file into frozen dataclasses, in SI.

A case is one TOML file: refrigerant, operating point, geometry, valves, leakage,
heat transfer, mechanism data, an ``[options]`` table with one entry per submodel
slot and a ``[solver]`` table. ``--set KEY=VALUE`` overrides are applied to the raw
TOML data before validation, so they are checked exactly like the file itself.
Everything that can be checked before integrating is checked here: ranges, unknown
keys, unknown refrigerant, a suction state inside the two-phase dome, condensing
below evaporating.
"""

from __future__ import annotations

import copy
import json
import math
import tomllib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from functools import lru_cache
from pathlib import Path
from typing import TYPE_CHECKING, Any

from recipsim.atomic import checked_name, name_from_stem
from recipsim.case.files import (
    MAX_EXTENDS_DEPTH,
    read_toml,
    resolve_reference,
    shipped_path,
)
from recipsim.case.mechanism import MechanismSpec, mechanism_from_dict
from recipsim.case.motor import case_motor
from recipsim.case.motor_losses import friction_option
from recipsim.case.pressure_curve import read_pressure_curve
from recipsim.case.rating import (
    RATING_SPEC,
    SATURATED_LIQUID_BAND,
    ambient_temperature,
    liquid_temperature,
    rating_standard,
    suction_gas_temperature,
)
from recipsim.case.refrigerant import RefrigerantSpec, case_fluid, load_refrigerant
from recipsim.case.schema import Choice, Field, Flag, Spec, Text, check_keys, read_table
from recipsim.case.thermal import ThermalSpec, parse_thermal
from recipsim.errors import CaseError
from recipsim.physics.mechanics.tabulated import PressureCurve
from recipsim.physics.motor import MotorSpec
from recipsim.physics.motor_circuit import MotorCircuit

if TYPE_CHECKING:
    from recipsim.case.refrigerant import AnyFluid

OPTION_SPEC: Spec = {
    "pressure": Choice(("cylinder", "tabulated"), "cylinder", "pressure source"),
    "properties": Choice(("heos", "table"), "heos", "property backend"),
    "valves": Choice(("ideal", "quasi_static", "reed"), "reed", "valve model"),
    "heat_transfer": Choice(("adiabatic", "annand", "adair"), "adiabatic", "in-cylinder heat"),
    "leakage": Choice(("none", "piston_gap"), "none", "piston-cylinder leakage"),
    "mechanics": Choice(("pinned", "flexible"), "pinned", "crank train"),
    "bearing_law": Choice(
        ("linear", "short_journal", "finite_journal"),
        "linear",
        "law of the journal bearings (primary, secondary, eccentric) whose table names none",
    ),
    "drive": Choice(("constant_speed", "torque_profile", "induction_motor"), "constant_speed"),
    "friction": Choice(
        ("off", "mean", "films"),
        None,
        "mechanical friction: none, mean Petroff journals and viscous skirt, or the oil films "
        "(default: films where a bearing runs on one, else off)",
    ),
    "motor": Choice(
        ("lossless", "equivalent_circuit"), "lossless", "motor losses and electrical power"
    ),
    "thermal": Choice(
        ("fixed_wall", "network"),
        "fixed_wall",
        "suction plenum at the inlet state and the given wall temperature, or the shell's "
        "thermal network ([thermal])",
    ),
    "speed": Choice(
        ("case", "motor_slip"),
        "case",
        "crank speed: operating_point.shaft_speed, or the speed at which the equivalent "
        "circuit carries the cycle's load torque (constant speed, equivalent_circuit motor)",
    ),
}

OPERATING_POINT_SPEC: Spec = {
    "rating_point": Text(None, "name of a rating point in the refrigerant file"),
    "evaporating_temperature": Field("K", None, lo=50.0, hi=700.0),
    "condensing_temperature": Field("K", None, lo=50.0, hi=700.0),
    "suction_pressure": Field("Pa", None, lo=0.0, open_lo=True, hi=1e9),
    "discharge_pressure": Field("Pa", None, lo=0.0, open_lo=True, hi=1e9),
    "suction_temperature": Field("K", None, lo=50.0, hi=700.0),
    "liquid_temperature": Field("K", None, lo=50.0, hi=700.0),
    "shell_pressure": Field("Pa", None, lo=0.0, open_lo=True, hi=1e9),
    "shaft_speed": Field("rad/s", lo=0.0, hi=2000.0, open_lo=True, doc="e.g. '3500 rpm'"),
    **RATING_SPEC,
}

GEOMETRY_SPEC: Spec = {
    "bore": Field("m", lo=1e-3, hi=0.5),
    "stroke": Field("m", lo=1e-3, hi=0.5),
    "connecting_rod_length": Field("m", lo=1e-3, hi=2.0),
    "clearance_ratio": Field("dimensionless", None, lo=0.0, hi=1.0, open_lo=True),
    "clearance_volume": Field("m^3", None, lo=0.0, open_lo=True),
    "liner_length": Field("m", None, lo=1e-3, hi=1.0, doc="head to open end of the bore"),
}

VALVE_SPEC: Spec = {
    "port_diameter": Field("m", lo=1e-4, hi=0.2),
    "reed_width": Field("m", lo=1e-4, hi=0.2),
    "reed_thickness": Field("m", lo=1e-6, hi=0.01),
    "reed_length": Field("m", lo=1e-4, hi=0.5),
    "port_position": Field("m", None, lo=1e-4, hi=0.5, doc="clamp to port centre"),
    "stop_height": Field("m", lo=1e-5, hi=0.05),
    "youngs_modulus": Field("Pa", 1.93e11, lo=1e9, hi=1e12),
    "density": Field("kg/m^3", 7800.0, lo=100.0, hi=30000.0),
    "damping_ratio": Field("dimensionless", 0.02, lo=0.0, hi=2.0),
    "restitution": Field("dimensionless", 0.3, lo=0.0, hi=1.0),
    "preload": Field("N", 0.0, lo=0.0, hi=1e4),
    "flow_coefficient": Field("dimensionless", 0.8, lo=0.0, hi=2.0, open_lo=True),
    "force_coefficient": Field("dimensionless", 1.1, lo=0.0, hi=3.0, open_lo=True),
    "flow_area": Choice(
        ("port", "reed_diameter"),
        "port",
        "curtain pi d x on the port's diameter (edge of the port) or the reed's (its rim)",
    ),
    "momentum_force": Flag(False, "the jet's momentum flux mdot^2/(rho A) pushes on the reed"),
}

VALVES_TOP_SPEC: Spec = {
    "flow_model": Choice(("real_gas", "ideal_gas"), "real_gas", "isentropic nozzle form"),
    "laminar_pressure_difference": Field(
        "Pa", 100.0, lo=0.0, hi=1e5, open_lo=True, doc="below it the flow goes linear in dp"
    ),
    "stick_velocity": Field("m/s", 0.01, lo=0.0, hi=10.0, doc="impacts slower than this stick"),
}

LEAKAGE_SPEC: Spec = {
    "model": Choice(
        ("isothermal", "incompressible"),
        "isothermal",
        "gap law: compressible isothermal (mean-pressure density) or upstream density",
    ),
    "radial_clearance": Field("m", 6e-6, lo=0.0, hi=1e-3, open_lo=True),
    "eccentricity_ratio": Field(
        "dimensionless",
        0.0,
        lo=0.0,
        hi=1.0,
        open_hi=True,
        doc="piston offset/clearance, rigid crank",
    ),
}

HEAT_TRANSFER_SPEC: Spec = {
    "wall_temperature": Field("K", None, lo=50.0, hi=900.0),
    "coefficient": Field("dimensionless", None, lo=0.0, hi=100.0, doc="correlation constant a"),
}

SOLVER_SPEC: Spec = {
    "method": Choice(("dopri5", "dopri5_stiff", "ros34pw2"), "dopri5", "integrator"),
    "rtol": Field("dimensionless", 1e-6, lo=1e-13, hi=1e-2),
    "atol": Field("dimensionless", None, lo=1e-16, hi=1e-2, doc="on scaled states; default rtol"),
    "cycle_tolerance": Field("dimensionless", 1e-4, lo=1e-12, hi=0.1),
    "max_revolutions": Field("dimensionless", 60, lo=1, hi=10000, integer=True),
    "min_revolutions": Field("dimensionless", 2, lo=1, hi=1000, integer=True),
    "samples_per_revolution": Field("dimensionless", 720, lo=36, hi=100000, integer=True),
    "max_step": Field(
        "rad", math.radians(2.0), lo=1e-7, hi=math.pi, doc="largest crank-angle step"
    ),
    "start": Choice(
        ("periodic", "rest"),
        "periodic",
        "periodic steady state; 'rest': start-up from standstill (induction_motor drive)",
    ),
    "standstill_pressure": Field(
        "Pa",
        None,
        lo=0.0,
        open_lo=True,
        hi=1e9,
        doc="start = 'rest': equalised pressure; default saturation at the ambient temperature",
    ),
    "pull_down_time": Field(
        "s",
        2.5,
        lo=0.0,
        hi=60.0,
        doc="start = 'rest': plenums ramp from the standstill to the case's pressures",
    ),
    "periodic": Choice(("auto", "revolutions", "shooting"), "auto", "periodic steady-state solver"),
    "envelope": Choice(
        ("refuse", "ignore"), "refuse", "a point outside the refrigerant's [envelope]"
    ),
}

TOP_KEYS = {
    "name",
    "description",
    "refrigerant",
    "options",
    "operating_point",
    "geometry",
    "valves",
    "leakage",
    "heat_transfer",
    "solver",
    "mechanism",
    "bearings",
    "pressure_curve",
    "motor",
    "oil",
    "thermal",
}


@dataclass(frozen=True)
class Options:
    """One choice per submodel slot (see the README's option table)."""

    pressure: str
    properties: str
    valves: str
    heat_transfer: str
    leakage: str
    mechanics: str
    bearing_law: str
    drive: str
    #: "off", "mean" or "films" (resolved from the bearings when the case gives none)
    friction: str = "off"
    motor: str = "lossless"
    thermal: str = "fixed_wall"
    #: "case" (operating_point.shaft_speed) or "motor_slip" (the motor's speed at load)
    speed: str = "case"


@dataclass(frozen=True)
class OperatingPoint:
    """Thermodynamic operating point, in SI.

    ``condensing_temperature`` is ``nan`` for a transcritical point given by its
    discharge pressure.
    """

    evaporating_temperature: float
    condensing_temperature: float
    suction_pressure: float
    discharge_pressure: float
    suction_temperature: float
    liquid_temperature: float
    shell_pressure: float
    shaft_speed: float  # [rad/s]
    #: air around the compressor shell [K]
    ambient_temperature: float = 305.35
    #: rating standard that set the temperatures ("none": the case's own)
    standard: str = "none"

    @property
    def pressure_ratio(self) -> float:
        return self.discharge_pressure / self.suction_pressure


@dataclass(frozen=True)
class Geometry:
    """Cylinder and crank geometry [m, m3]."""

    bore: float
    stroke: float
    connecting_rod_length: float
    clearance_volume: float
    liner_length: float  # head to the open end of the bore [m]

    @property
    def crank_radius(self) -> float:
        return 0.5 * self.stroke

    @property
    def piston_area(self) -> float:
        return math.pi * self.bore**2 / 4.0

    @property
    def swept_volume(self) -> float:
        return self.piston_area * self.stroke


@dataclass(frozen=True)
class ValveSpec:
    """One reed valve (also used for the port of ``quasi_static``)."""

    port_diameter: float
    reed_width: float
    reed_thickness: float
    reed_length: float
    port_position: float
    stop_height: float
    youngs_modulus: float
    density: float
    damping_ratio: float
    restitution: float
    preload: float
    flow_coefficient: float
    force_coefficient: float
    #: curtain of the flow area: "port" (pi d_port x) or "reed_diameter" (pi reed_width x)
    flow_area: str = "port"
    #: the jet's momentum flux adds to the pressure force on the reed
    momentum_force: bool = False

    @property
    def curtain_diameter(self) -> float:
        """Diameter of the curtain flow area pi d x [m]: the port's or the reed's."""
        return self.reed_width if self.flow_area == "reed_diameter" else self.port_diameter

    @property
    def port_area(self) -> float:
        return math.pi * self.port_diameter**2 / 4.0

    @property
    def stiffness(self) -> float:
        """Cantilever stiffness at the port centre, 6 E I / (a^2 (3 l - a)) [N/m]."""
        inertia = self.reed_width * self.reed_thickness**3 / 12.0
        a, length = self.port_position, self.reed_length
        return 6.0 * self.youngs_modulus * inertia / (a * a * (3.0 * length - a))

    @property
    def mass(self) -> float:
        """Equivalent moving mass, one third of the reed [kg]."""
        return self.density * self.reed_length * self.reed_width * self.reed_thickness / 3.0

    @property
    def natural_frequency(self) -> float:
        """[Hz]"""
        return math.sqrt(self.stiffness / self.mass) / (2.0 * math.pi)


@dataclass(frozen=True)
class Valves:
    suction: ValveSpec
    discharge: ValveSpec
    flow_model: str
    laminar_pressure_difference: float
    stick_velocity: float


@dataclass(frozen=True)
class Leakage:
    radial_clearance: float
    eccentricity_ratio: float
    #: "isothermal" (compressible) or "incompressible" gap law
    model: str = "isothermal"


@dataclass(frozen=True)
class HeatTransfer:
    wall_temperature: float
    coefficient: float  # nan: the correlation's own


@dataclass(frozen=True)
class SolverSettings:
    method: str
    rtol: float
    atol: float
    cycle_tolerance: float
    max_revolutions: int
    min_revolutions: int
    samples_per_revolution: int
    max_step: float  # crank angle [rad]
    #: periodic steady-state solver: "revolutions", "shooting" or "auto"
    periodic: str = "auto"
    #: "periodic", or "rest": the start-up transient first (:mod:`recipsim.solve.startup`)
    start: str = "periodic"
    #: equalised pressure at standstill [Pa] (nan: saturation at the ambient temperature)
    standstill_pressure: float = math.nan
    #: time over which the plenums move from the standstill to the case's pressures [s]
    pull_down_time: float = 2.5
    #: outside the refrigerant's envelope: "refuse" or "ignore" (recipsim.case.envelope)
    envelope: str = "refuse"


@dataclass(frozen=True)
class Case:
    """A validated case, everything in SI."""

    name: str
    description: str
    path: str
    refrigerant: RefrigerantSpec
    options: Options
    operating_point: OperatingPoint
    geometry: Geometry
    valves: Valves
    leakage: Leakage
    heat_transfer: HeatTransfer
    solver: SolverSettings
    mechanism: MechanismSpec
    pressure_curve: PressureCurve | None = None
    motor: MotorSpec | None = None
    #: equivalent circuit of the motor (``options.motor = "equivalent_circuit"``)
    motor_circuit: MotorCircuit | None = None
    thermal: ThermalSpec = field(default_factory=lambda: parse_thermal(None, ""))
    raw: dict[str, Any] = field(default_factory=dict, repr=False, compare=False)
    source_text: str = field(default="", repr=False, compare=False)
    #: the ``KEY=VALUE`` overrides applied on top of the file, in order
    overrides: tuple[str, ...] = field(default=(), compare=False)
    allow_external_paths: bool = field(default=False, repr=False, compare=False)

    def with_(
        self, overrides: Mapping[str, Any] | Sequence[str] | None = None, **keys: Any
    ) -> Case:
        """A new case with some values changed, validated exactly like the file.

        Parameters
        ----------
        overrides : mapping or sequence of str, optional
            Dotted case keys to values, e.g. ``{"operating_point.shaft_speed": "3000 rpm"}``
            (a string with a unit, or a bare number in SI), or ``KEY=VALUE`` texts as
            for ``--set``.
        **keys
            The same with ``__`` for the dots: ``operating_point__shaft_speed="3000 rpm"``.

        Returns
        -------
        Case
            This case is unchanged (cases are immutable).

        Raises
        ------
        CaseError
            Naming the key and what is allowed, as for the file.
        """
        texts = override_texts(overrides)
        texts += override_texts({key.replace("__", "."): value for key, value in keys.items()})
        raw = apply_overrides(self.raw, texts, self.path)
        case = case_from_dict(
            raw, self.path, self.source_text, allow_external_paths=self.allow_external_paths
        )
        return replace(
            case,
            overrides=self.overrides + tuple(texts),
            allow_external_paths=self.allow_external_paths,
        )


def parse_override(text: str) -> tuple[list[str], Any]:
    """Split ``"a.b.c=VALUE"`` into a key path and a TOML-typed value.

    The value is read as a TOML value when it parses (``1e-9``, ``"3000 rpm"``,
    ``true``), otherwise as a bare string (``ideal``).
    """
    path, parsed = _parsed_override(text)
    return list(path), copy.deepcopy(parsed)


@lru_cache(maxsize=4096)
def _parsed_override(text: str) -> tuple[tuple[str, ...], Any]:
    """:func:`parse_override`, once per text: a sweep's points repeat their axes' few
    texts, each read twice per point (0.13 ms with :mod:`tomllib`)."""
    if "=" not in text:
        raise CaseError("--set", text, "expected KEY=VALUE, e.g. solver.rtol=1e-9")
    key, value = text.split("=", 1)
    path = tuple(k.strip() for k in key.strip().split("."))
    if not all(path):
        raise CaseError("--set", key, "empty part in the dotted key")
    try:
        parsed = tomllib.loads(f"v = {value.strip()}")["v"]
    except tomllib.TOMLDecodeError:
        parsed = value.strip()
    return path, parsed


def toml_literal(value: Any) -> str:
    """Write a scalar as a TOML value, the right-hand side of a ``--set`` override."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    raise TypeError(f"not a TOML scalar: {value!r}")


def override(key: str, value: Any) -> str:
    """``KEY=VALUE`` text for one case value (checked to read back as ``value``).

    Raises
    ------
    CaseError
        Naming the key, if ``value`` is not a TOML scalar that reads back unchanged.
    """
    try:
        literal = toml_literal(value)
    except TypeError:
        raise CaseError(
            "overrides", key, f"{value!r} is not allowed; a number, a string or a boolean"
        ) from None
    text = f"{key}={literal}"
    _, parsed = parse_override(text)
    if parsed != value and not (isinstance(value, float) and math.isnan(value)):
        raise CaseError("--set", key, f"{value!r} cannot be written as an override")
    return text


def override_texts(overrides: Mapping[str, Any] | Sequence[str] | None) -> list[str]:
    """``KEY=VALUE`` texts from a mapping of dotted keys to values, or from such texts."""
    if overrides is None:
        return []
    if isinstance(overrides, Mapping):
        return [override(str(key), value) for key, value in overrides.items()]
    if isinstance(overrides, str):
        return [overrides]
    return [str(text) for text in overrides]


def apply_overrides(raw: dict[str, Any], overrides: list[str], file: str) -> dict[str, Any]:
    """Return a copy of ``raw`` with ``--set`` overrides applied.

    Only the tables on an override's path are copied; the others are shared with
    ``raw`` (a deep copy of the whole case costs about 1 ms, which a sweep paid for
    every point when planning it and again when solving it). Case data is never
    modified in place once read, so sharing is safe.
    """
    data = dict(raw)
    for text in overrides:
        path, value = parse_override(text)
        node = data
        for part in path[:-1]:
            nxt = node.get(part, {})
            if not isinstance(nxt, dict):
                raise CaseError(file, ".".join(path), f"{part!r} is not a table")
            nxt = node[part] = dict(nxt)
            node = nxt
        node[path[-1]] = value
    return data


def load_case(
    path: str | Path,
    overrides: Mapping[str, Any] | Sequence[str] | None = None,
    *,
    allow_external_paths: bool = False,
) -> Case:
    """Read, override and validate a case file.

    Parameters
    ----------
    path : str or Path
        The TOML case file, or the name of a shipped case (``"reference_r134a_lbp"``).
    overrides : mapping or list of str, optional
        Dotted case keys to values (``{"operating_point.shaft_speed": "3000 rpm"}``), or
        ``KEY=VALUE`` strings as on the command line (``--set``); validated exactly like
        the file.
    allow_external_paths : bool
        Let ``extends`` and ``pressure_curve.file`` name files outside the case file's
        directory (absolute paths, ``..``); by default only files beside the case, below
        it, or shipped cases by name are read.

    Returns
    -------
    Case

    Raises
    ------
    CaseError
        With the file, the key and what is allowed.
    """
    path = shipped_case(path)
    file = str(path)
    texts = override_texts(overrides)
    raw, text = read_toml(path, "case")
    raw = resolve_extends(raw, path, [path.resolve()], allow_external_paths)
    raw = apply_overrides(raw, texts, file)
    case = case_from_dict(raw, file, text, allow_external_paths=allow_external_paths)
    return replace(case, overrides=tuple(texts), allow_external_paths=allow_external_paths)


def shipped_case(path: str | Path) -> Path:
    """``path`` itself, or the shipped case it names (a bare name that is not a file)."""
    found = shipped_path(path)
    return found if found.is_file() or not found.is_dir() else Path(path)


def _deep_merge(base: dict[str, Any], child: dict[str, Any]) -> dict[str, Any]:
    out = copy.deepcopy(base)
    for key, value in child.items():
        if isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = _deep_merge(out[key], value)
        else:
            out[key] = copy.deepcopy(value)
    return out


def resolve_extends(
    raw: dict[str, Any], path: Path, chain: list[Path], allow_external: bool = False
) -> dict[str, Any]:
    """Merge the case named by ``extends`` under this one.

    ``extends`` names a file beside this one (``"base.toml"``) or a shipped case by
    name (``"reference_r134a_lbp"``), see :func:`recipsim.case.files.resolve_reference`.
    ``name`` and ``description`` are not inherited: a case's name defaults to its
    file name.
    """
    parent_name = raw.pop("extends", None)
    if parent_name is None:
        return raw
    if len(chain) > MAX_EXTENDS_DEPTH:
        raise CaseError(
            str(path), "extends", f"chain of extends deeper than {MAX_EXTENDS_DEPTH} files"
        )
    parent = resolve_reference(
        parent_name, str(path), "extends", "case file", allow_external, by_name=True
    )
    if parent in chain:
        raise CaseError(str(path), "extends", f"circular extends through {parent.name}")
    base, _ = read_toml(parent, "case")
    curve = base.get("pressure_curve")
    if isinstance(curve, dict) and isinstance(curve.get("file"), str):
        # a file named in the base case is relative to the base case, not to this one:
        # resolved (and checked) here, where the base case is known
        curve["file"] = str(
            resolve_reference(
                curve["file"],
                str(parent),
                "pressure_curve.file",
                "pressure curve",
                allow_external,
            )
        )
    base = resolve_extends(base, parent, chain + [parent], allow_external)
    base.pop("name", None)
    base.pop("description", None)
    return _deep_merge(base, raw)


def case_from_dict(
    raw: dict[str, Any], file: str, source_text: str = "", *, allow_external_paths: bool = False
) -> Case:
    """Validate the raw TOML data of a case (see :func:`load_case`)."""
    check_keys(raw, TOP_KEYS, file, "")
    top = read_table(
        {k: raw[k] for k in ("name", "description", "refrigerant") if k in raw},
        {"name": Text(None), "description": Text(""), "refrigerant": Text()},
        file,
        "",
    )
    # the name becomes a directory name: a plain file name or refused
    top["name"] = (
        name_from_stem(Path(file).stem) if top["name"] is None else checked_name(top["name"], file)
    )
    search = [Path(file).resolve().parent, Path(file).resolve().parent.parent]
    refrigerant = load_refrigerant(top["refrigerant"], file, "refrigerant", search)
    options = Options(**read_table(raw.get("options"), OPTION_SPEC, file, "options"))
    fluid = case_fluid(refrigerant, options.properties)
    op = _operating_point(raw.get("operating_point"), refrigerant, fluid, file)
    geometry = _geometry(raw.get("geometry"), file)
    valves = _valves(raw.get("valves"), options, file)
    leakage = Leakage(**read_table(raw.get("leakage"), LEAKAGE_SPEC, file, "leakage"))
    ht = read_table(raw.get("heat_transfer"), HEAT_TRANSFER_SPEC, file, "heat_transfer")
    network = options.thermal == "network"  # the network gives the wall temperature
    if options.heat_transfer != "adiabatic" and ht["wall_temperature"] is None and not network:
        raise CaseError(
            file,
            "heat_transfer.wall_temperature",
            f"required with options.heat_transfer = {options.heat_transfer!r} (e.g. '60 degC')",
        )
    heat = HeatTransfer(
        wall_temperature=ht["wall_temperature"] or math.nan,
        coefficient=math.nan if ht["coefficient"] is None else ht["coefficient"],
    )
    sv = read_table(raw.get("solver"), SOLVER_SPEC, file, "solver")
    solver = SolverSettings(
        method=sv["method"],
        rtol=sv["rtol"],
        atol=sv["atol"] if sv["atol"] is not None else sv["rtol"],
        cycle_tolerance=sv["cycle_tolerance"],
        max_revolutions=int(sv["max_revolutions"]),
        min_revolutions=int(sv["min_revolutions"]),
        samples_per_revolution=int(sv["samples_per_revolution"]),
        max_step=sv["max_step"],
        periodic=sv["periodic"],
        start=sv["start"],
        standstill_pressure=math.nan
        if sv["standstill_pressure"] is None
        else sv["standstill_pressure"],
        pull_down_time=sv["pull_down_time"],
        envelope=sv["envelope"],
    )
    if sv["start"] == "rest" and options.drive != "induction_motor":
        raise CaseError(
            file,
            "solver.start",
            f"'rest' (start-up from standstill) needs a motor that starts the crank: "
            f"options.drive = 'induction_motor' (with options.mechanics = 'flexible'), "
            f"not {options.drive!r}; allowed with this drive: 'periodic'",
        )
    if sv["start"] == "rest" and options.thermal == "network":
        raise CaseError(
            file,
            "solver.start",
            "'rest' moves the plenums along the pull-down ramp, which the shell's thermal "
            "network would overwrite; allowed with options.thermal = 'network': 'periodic'",
        )
    if solver.min_revolutions > solver.max_revolutions:
        raise CaseError(file, "solver.min_revolutions", "must not exceed solver.max_revolutions")
    mechanism = mechanism_from_dict(raw, file, bore=geometry.bore, default_law=options.bearing_law)
    if geometry.liner_length is None:
        geometry = replace(
            geometry,
            liner_length=geometry.stroke
            + mechanism.piston.length
            + geometry.clearance_volume / geometry.piston_area,
        )
    options = replace(options, friction=friction_option(options, mechanism, file))
    _check_supported(options, file)
    _check_consistency(geometry, valves, options, file)
    curve = _pressure_curve(raw.get("pressure_curve"), options, file, allow_external_paths)
    motor, circuit = case_motor(
        raw.get("motor"), options.drive, options.motor, op.shaft_speed, file
    )
    thermal = parse_thermal(raw.get("thermal"), file)
    if network and op.shell_pressure != op.suction_pressure:
        raise CaseError(
            file,
            "operating_point.shell_pressure",
            f"{op.shell_pressure:.4g} Pa: options.thermal = 'network' models a low-side shell, "
            f"at the suction pressure {op.suction_pressure:.4g} Pa; allowed: not set",
        )
    return Case(
        name=top["name"],
        description=top["description"],
        path=file,
        refrigerant=refrigerant,
        options=options,
        operating_point=op,
        geometry=geometry,
        valves=valves,
        leakage=leakage,
        heat_transfer=heat,
        solver=solver,
        mechanism=mechanism,
        pressure_curve=curve,
        motor=motor,
        motor_circuit=circuit,
        thermal=thermal,
        raw=raw,
        source_text=source_text,
    )


def _check_consistency(geometry: Geometry, valves: Valves, options: Options, file: str) -> None:
    """Refuse geometry that cannot be built: ports wider than the bore, reeds narrower
    than their port, a liner too short for the stroke."""
    crown_at_bdc = geometry.stroke + geometry.clearance_volume / geometry.piston_area
    if geometry.liner_length is not None and geometry.liner_length <= crown_at_bdc:
        raise CaseError(
            file,
            "geometry.liner_length",
            f"{geometry.liner_length:.4g} m is too short: the piston crown travels "
            f"{crown_at_bdc:.4g} m from the head (stroke + clearance height); allowed: longer",
        )
    if options.valves == "ideal":
        return  # the lossless valves use no valve data
    for side in ("suction", "discharge"):
        valve: ValveSpec = getattr(valves, side)
        if valve.port_diameter >= geometry.bore:
            raise CaseError(
                file,
                f"valves.{side}.port_diameter",
                f"{valve.port_diameter:.4g} m; a port in the valve plate must be narrower than "
                f"the bore {geometry.bore:.4g} m",
            )
        if valve.reed_width <= valve.port_diameter:
            raise CaseError(
                file,
                f"valves.{side}.reed_width",
                f"{valve.reed_width:.4g} m cannot cover its port of {valve.port_diameter:.4g} m; "
                "allowed: wider than port_diameter",
            )


def _check_supported(options: Options, file: str) -> None:
    """Refuse option combinations this version cannot simulate, before integrating."""
    if options.mechanics == "pinned" and options.drive != "constant_speed":
        raise CaseError(
            file,
            "options.drive",
            f"{options.drive!r} needs a crank whose speed can vary; the pinned mechanism turns "
            "at constant speed by definition: use options.drive = 'constant_speed' or "
            "options.mechanics = 'flexible'",
        )
    if options.speed == "motor_slip" and (
        options.drive != "constant_speed" or options.motor != "equivalent_circuit"
    ):
        raise CaseError(
            file,
            "options.speed",
            "'motor_slip' runs the constant-speed cycle at the equivalent circuit's speed at "
            "load: it needs options.drive = 'constant_speed' and options.motor = "
            "'equivalent_circuit' (the induction_motor drive finds its speed itself)",
        )


PRESSURE_CURVE_SPEC: Spec = {
    "file": Text(None, "CSV with 'crank_angle [deg]' (from TDC) and 'cylinder_pressure [Pa]'"),
}


def _pressure_curve(
    raw: dict[str, Any] | None, options: Options, file: str, allow_external: bool = False
) -> PressureCurve | None:
    """The tabulated p(theta) curve: a CSV named relative to the case file."""
    table = read_table(raw, PRESSURE_CURVE_SPEC, file, "pressure_curve")
    if options.pressure != "tabulated":
        return None
    if table["file"] is None:
        raise CaseError(
            file,
            "pressure_curve.file",
            "required with options.pressure = 'tabulated': a CSV beside the case with columns "
            "'crank_angle [deg]' (0 at top dead centre) and 'cylinder_pressure [Pa]'",
        )
    path = resolve_reference(
        table["file"], file, "pressure_curve.file", "pressure curve", allow_external
    )
    return read_pressure_curve(path, file)


def _operating_point(
    raw: dict[str, Any] | None, ref: RefrigerantSpec, fluid: AnyFluid, file: str
) -> OperatingPoint:
    prefix = "operating_point"
    raw = dict(raw or {})
    values = read_table(raw, OPERATING_POINT_SPEC, file, prefix)
    if values["rating_point"] is not None:
        name = values["rating_point"]
        if name not in ref.rating_points:
            raise CaseError(
                file,
                f"{prefix}.rating_point",
                f"{name!r} is not a rating point of {ref.name}; available: "
                f"{sorted(ref.rating_points)}",
            )
        for key, value in ref.rating_points[name].items():
            if key in values and values[key] is None and key not in raw:
                values[key] = value
    standard = rating_standard(values, raw, file)
    t_lo, t_hi = ref.min_temperature, ref.max_temperature

    def need(key: str) -> float:
        if values[key] is None:
            raise CaseError(file, f"{prefix}.{key}", "missing required key")
        return float(values[key])

    def in_range(key: str, value: float) -> float:
        if not t_lo <= value <= t_hi:
            raise CaseError(
                file,
                f"{prefix}.{key}",
                f"{value:.2f} K is outside the range of {ref.name}: [{t_lo:.2f}, {t_hi:.2f}] K",
            )
        return value

    def exactly_one(a: str, b: str) -> str:
        if (values[a] is None) == (values[b] is None):
            raise CaseError(file, f"{prefix}.{a}", f"give exactly one of {a} and {b}")
        return a if values[a] is not None else b

    t_crit = ref.critical_temperature
    # suction side
    if exactly_one("evaporating_temperature", "suction_pressure") == "evaporating_temperature":
        t_evap = in_range("evaporating_temperature", need("evaporating_temperature"))
        if t_evap >= t_crit:
            raise CaseError(
                file,
                f"{prefix}.evaporating_temperature",
                f"{t_evap:.2f} K is not below the critical temperature {t_crit:.2f} K",
            )
        p_suc = fluid.saturation_pressure(t_evap, 1.0)
    else:
        p_suc = need("suction_pressure")
        if p_suc >= ref.critical_pressure:
            raise CaseError(
                file,
                f"{prefix}.suction_pressure",
                f"{p_suc:.4g} Pa is not below the critical pressure {ref.critical_pressure:.4g} Pa",
            )
        p_lo = fluid.saturation_pressure(t_lo, 1.0)
        if p_suc < p_lo:
            raise CaseError(
                file,
                f"{prefix}.suction_pressure",
                f"{p_suc:.4g} Pa is below the saturation pressure at the lowest temperature "
                f"of {ref.name} ({t_lo:.2f} K): allowed [{p_lo:.4g}, "
                f"{ref.critical_pressure:.4g}) Pa",
            )
        t_evap = fluid.saturation_temperature(p_suc, 1.0)
    # discharge side
    if exactly_one("condensing_temperature", "discharge_pressure") == "condensing_temperature":
        t_cond = in_range("condensing_temperature", need("condensing_temperature"))
        if t_cond <= t_evap:
            raise CaseError(
                file,
                f"{prefix}.condensing_temperature",
                f"{t_cond:.2f} K must be above the evaporating temperature {t_evap:.2f} K",
            )
        if t_cond >= t_crit:
            raise CaseError(
                file,
                f"{prefix}.condensing_temperature",
                f"{t_cond:.2f} K is not below the critical temperature {t_crit:.2f} K; give "
                "discharge_pressure for a transcritical point",
            )
        p_dis = fluid.saturation_pressure(t_cond, 0.0)
    else:
        p_dis = need("discharge_pressure")
        t_cond = (
            fluid.saturation_temperature(p_dis, 0.0) if p_dis < ref.critical_pressure else math.nan
        )
        if p_dis > ref.max_pressure:
            raise CaseError(
                file,
                f"{prefix}.discharge_pressure",
                f"{p_dis:.4g} Pa is above the limit of {ref.name}: {ref.max_pressure:.4g} Pa",
            )
    if p_dis <= p_suc:
        key = "condensing_temperature" if values["condensing_temperature"] else "discharge_pressure"
        raise CaseError(
            file,
            f"{prefix}.{key}",
            f"discharge pressure {p_dis:.4g} Pa must exceed suction pressure {p_suc:.4g} Pa",
        )
    t_dew = fluid.saturation_temperature(p_suc, 1.0)
    t_suc = in_range(
        "suction_temperature", suction_gas_temperature(values, raw, standard, t_dew, file)
    )
    if t_suc <= t_dew + 1e-3:
        raise CaseError(
            file,
            f"{prefix}.suction_temperature",
            f"{t_suc:.2f} K puts the suction state inside the two-phase dome (dew point at "
            f"{p_suc:.4g} Pa is {t_dew:.2f} K); wet suction is outside the model, allowed: "
            f"above {t_dew:.2f} K",
        )
    subcritical = p_dis < ref.critical_pressure
    t_bubble = fluid.saturation_temperature(p_dis, 0.0) if subcritical else math.nan
    t_liq = in_range(
        "liquid_temperature", liquid_temperature(values, raw, standard, t_bubble, file)
    )
    if subcritical:
        # within SATURATED_LIQUID_BAND of the bubble point: saturated liquid
        if t_liq > t_bubble + SATURATED_LIQUID_BAND:
            raise CaseError(
                file,
                f"{prefix}.liquid_temperature",
                f"{t_liq:.2f} K is above the bubble point {t_bubble:.2f} K at the discharge "
                "pressure: the liquid would not be liquid",
            )
    p_shell = values["shell_pressure"] if values["shell_pressure"] is not None else p_suc
    if not 0.0 < p_shell <= ref.max_pressure:
        raise CaseError(
            file,
            f"{prefix}.shell_pressure",
            f"{p_shell:.4g} Pa is outside the pressure range of {ref.name}: "
            f"(0, {ref.max_pressure:.4g}] Pa (a hermetic shell sits at suction or discharge "
            f"pressure, here {p_suc:.4g} or {p_dis:.4g} Pa)",
        )
    return OperatingPoint(
        evaporating_temperature=t_evap,
        condensing_temperature=t_cond,
        suction_pressure=p_suc,
        discharge_pressure=p_dis,
        suction_temperature=t_suc,
        liquid_temperature=t_liq,
        shell_pressure=p_shell,
        shaft_speed=float(values["shaft_speed"]),
        ambient_temperature=ambient_temperature(values, raw, standard, file),
        standard=values["standard"],
    )


def _geometry(raw: dict[str, Any] | None, file: str) -> Geometry:
    g = read_table(raw, GEOMETRY_SPEC, file, "geometry")
    area = math.pi * g["bore"] ** 2 / 4.0
    swept = area * g["stroke"]
    if (g["clearance_ratio"] is None) == (g["clearance_volume"] is None):
        raise CaseError(
            file,
            "geometry.clearance_ratio",
            "give exactly one of clearance_ratio and clearance_volume",
        )
    vc = (
        g["clearance_volume"] if g["clearance_volume"] is not None else g["clearance_ratio"] * swept
    )
    if g["connecting_rod_length"] <= 0.5 * g["stroke"]:
        raise CaseError(
            file,
            "geometry.connecting_rod_length",
            f"must exceed the crank radius {0.5 * g['stroke']:.4g} m",
        )
    return Geometry(
        bore=g["bore"],
        stroke=g["stroke"],
        connecting_rod_length=g["connecting_rod_length"],
        clearance_volume=vc,
        liner_length=g["liner_length"],  # None: set from the piston length by the caller
    )


def _valves(raw: dict[str, Any] | None, options: Options, file: str) -> Valves:
    raw = dict(raw or {})
    top = read_table(
        {k: v for k, v in raw.items() if k not in ("suction", "discharge")},
        VALVES_TOP_SPEC,
        file,
        "valves",
    )
    specs = {}
    for side in ("suction", "discharge"):
        table = raw.get(side)
        if table is None and options.valves == "ideal":
            table = _IDEAL_PLACEHOLDER
        v = read_table(table, VALVE_SPEC, file, f"valves.{side}")
        if v["port_position"] is None:
            v["port_position"] = v["reed_length"] - 0.5 * v["reed_width"]
        if v["port_position"] > v["reed_length"]:
            raise CaseError(file, f"valves.{side}.port_position", "must not exceed reed_length")
        specs[side] = ValveSpec(**v)
    return Valves(suction=specs["suction"], discharge=specs["discharge"], **top)


# the lossless valve model needs no valve data; these values are never used by it
_IDEAL_PLACEHOLDER = {
    "port_diameter": 5e-3,
    "reed_width": 6e-3,
    "reed_thickness": 2e-4,
    "reed_length": 1.5e-2,
    "stop_height": 1.5e-3,
}

__all__ = ["Case", "load_case", "apply_overrides", "parse_override"]
