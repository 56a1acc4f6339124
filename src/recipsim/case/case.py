"""The validated case, :class:`Case`: its sections in SI, the raw data it was built from,
and :meth:`Case.with_` for a changed copy validated like the file.

:func:`case_from_dict` builds one from raw TOML data (the file after ``extends`` and
overrides); :func:`recipsim.case.load.load_case` reads the file.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

from recipsim.case.build import case_sections, derived_sections
from recipsim.case.friction import FrictionSpec
from recipsim.case.mechanism import MechanismSpec
from recipsim.case.overrides import (
    apply_overrides,
    blamed_on_override,
    override_tables,
    override_texts,
)
from recipsim.case.refrigerant import RefrigerantSpec
from recipsim.case.sections import (
    Geometry,
    HeatTransfer,
    Leakage,
    OperatingPoint,
    Options,
    SolverSettings,
    Valves,
)
from recipsim.case.thermal import ThermalSpec, parse_thermal
from recipsim.errors import CaseError
from recipsim.physics.mechanics.tabulated import PressureCurve
from recipsim.physics.motor import MotorSpec
from recipsim.physics.motor_circuit import MotorCircuit


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
    #: the friction sources beside the journals and the piston (``[friction]``)
    friction: FrictionSpec = field(default_factory=FrictionSpec)
    raw: dict[str, Any] = field(default_factory=dict, repr=False, compare=False)
    source_text: str = field(default="", repr=False, compare=False)
    #: the ``KEY=VALUE`` overrides applied on top of the file, in order
    overrides: tuple[str, ...] = field(default=(), compare=False)
    allow_external_paths: bool = field(default=False, repr=False, compare=False)

    def with_(
        self, overrides: Mapping[str, Any] | Sequence[str] | None = None, **keys: Any
    ) -> Case:
        """A new case with some values changed, validated exactly like the file.

        Only the sections the overrides reach are validated again (the tables they
        change, and the sections and checks that use those:
        :func:`recipsim.case.build.derived_sections`); the others are this case's own,
        which validating them again would give (a case is built from its raw data). The
        result equals ``load_case(path, self.overrides + overrides)``, and so do its
        errors: where the overrides make the case invalid, it is validated whole again
        for the error the file gives first.

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
        if keys:
            texts += override_texts({key.replace("__", "."): value for key, value in keys.items()})
        raw = apply_overrides(self.raw, texts, self.path)
        overrides_now = self.overrides + tuple(texts)
        try:  # only the sections that the overrides reach are validated again
            changed = derived_sections(vars(self), raw, override_tables(texts))
        except Exception:  # validated whole again: the error the file gives first
            try:
                case = case_from_dict(
                    raw, self.path, self.source_text, allow_external_paths=self.allow_external_paths
                )
            except CaseError as exc:
                raise blamed_on_override(exc, texts) from None
            return replace(
                case, overrides=overrides_now, allow_external_paths=self.allow_external_paths
            )
        return replace(self, **changed, raw=raw, overrides=overrides_now)


def case_from_dict(
    raw: dict[str, Any], file: str, source_text: str = "", *, allow_external_paths: bool = False
) -> Case:
    """Validate the raw TOML data of a case (see :func:`recipsim.case.load.load_case`)."""
    sections = case_sections(raw, file, allow_external_paths=allow_external_paths)
    return Case(**sections, raw=raw, source_text=source_text)
