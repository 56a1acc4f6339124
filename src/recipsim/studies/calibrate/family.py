"""The members of a compressor family calibrated together: each a data file (a
catalogue) with its own case, or the family's case with another bore; the fitted
parameters are shared by all of them.

A member is written ``DATA[:case=CASE][:bore=BORE|:displacement=VOLUME][:points=ROWS]`` on
the command line (``--member danfoss_tles10kk.3_r600a.csv:bore=26.49mm``, or
``...:displacement=10cm^3`` at the family's stroke) or given as a :class:`Member`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from recipsim.case.case import Case
from recipsim.case.load import load_case
from recipsim.errors import CaseError
from recipsim.studies.calibrate.data import find_data_file

#: The options of a member after its data file.
MEMBER_OPTIONS = ("case", "bore", "displacement", "points")


@dataclass(frozen=True)
class Member:
    """One compressor of a family calibration.

    Attributes
    ----------
    data : str or Path
        Its data file (a CSV of measured points, or a shipped catalogue's file name).
    case : str or Path, optional
        Its own case (a file or a shipped case's name), run with the family case's
        overrides. Default: the family's case.
    bore : str or float, optional
        ``geometry.bore`` of the member (``"26.49 mm"``, or SI) set on its case: the
        family's geometry with another displacement.
    points : sequence of int, optional
        Its data rows to fit on. Default: the family's ``points``.
    displacement : str or float, optional
        ``geometry.displacement`` of the member (``"10 cm^3"``, or SI) instead of its
        bore: the bore follows at its case's stroke.

    Raises
    ------
    CaseError
        Both a bore and a displacement.
    """

    data: str | Path
    case: str | Path | None = None
    bore: str | float | None = None
    points: tuple[int, ...] | None = None
    displacement: str | float | None = None

    def __post_init__(self) -> None:
        if self.bore is not None and self.displacement is not None:
            raise CaseError(str(self.data), "--member", "give bore or displacement, not both")

    @property
    def name(self) -> str:
        """The data file's stem, naming the member in tables."""
        return Path(self.data).stem


def parse_member(text: str) -> Member:
    """``DATA[:case=CASE][:bore=BORE|:displacement=VOLUME][:points=ROWS]`` as a
    :class:`Member`.

    Raises
    ------
    CaseError
        An option that is not one of :data:`MEMBER_OPTIONS`, both a bore and a
        displacement, or rows that are not whole numbers.
    """
    data, *options = text.split(":")
    found: dict[str, str] = {}
    for option in options:
        key, sep, value = option.partition("=")
        if not sep or key.strip() not in MEMBER_OPTIONS or not value.strip():
            raise CaseError(
                text,
                "--member",
                f"{option!r}: expected one of {', '.join(MEMBER_OPTIONS)} "
                "as KEY=VALUE after the data file (DATA:bore=26.49mm:points=3,7)",
            )
        found[key.strip()] = value.strip()
    rows = None
    if "points" in found:
        try:
            rows = tuple(int(v) for v in found["points"].split(",") if v.strip())
        except ValueError:
            raise CaseError(text, "--member", "points: expected row numbers like 3,7") from None
    return Member(
        data.strip(), found.get("case"), found.get("bore"), rows, found.get("displacement")
    )


def member_case(family: Case, member: Member) -> Case:
    """The case of ``member``: its own (with the family case's overrides) or the
    family's, with its bore or displacement where it gives one."""
    case = family
    if member.case is not None:
        case = load_case(member.case, list(family.overrides))
    if member.bore is not None:
        case = case.with_({"geometry.bore": member.bore})
    if member.displacement is not None:
        case = case.with_({"geometry.displacement": member.displacement})
    return case


def as_members(members: Sequence[Member | str]) -> list[Member]:
    """``members`` as :class:`Member` (strings parsed by :func:`parse_member`); refuses
    two members on the same data file."""
    parsed = [m if isinstance(m, Member) else parse_member(m) for m in members]
    names = [Path(find_data_file(m.data)).name for m in parsed]
    repeated = sorted({n for n in names if names.count(n) > 1})
    if repeated:
        raise CaseError(repeated[0], "--member", "the data file is named twice; keep one")
    return parsed
