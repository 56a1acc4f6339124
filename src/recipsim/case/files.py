"""Reading input files safely: regular files of bounded size, UTF-8, and references
between files (``extends``, ``pressure_curve.file``, a sweep's ``base``) that stay where
the user put them.

Every failure is a :class:`CaseError` naming the file and the key; a message never
echoes the content of a file that is not a valid input.
"""

from __future__ import annotations

import os
import stat
import tomllib
from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import Any

from recipsim.errors import CaseError

#: Largest case, refrigerant, sweep or expectations file read [bytes].
MAX_TOML_BYTES = 1_000_000
#: Largest tabulated pressure curve read [bytes].
MAX_CSV_BYTES = 50_000_000
#: Deepest chain of ``extends``.
MAX_EXTENDS_DEPTH = 16
#: Deepest nesting of tables or arrays inside one TOML file.
MAX_TOML_NESTING = 12


@lru_cache(maxsize=64)
def package_data(*parts: str) -> Path:
    """A folder of the data shipped inside the package (``recipsim/data/...``; found
    once per process: a sweep asks at every point)."""
    return Path(str(resources.files("recipsim").joinpath("data", *parts)))


def shipped_path(path: str | Path, folder: str = "") -> Path:
    """``path`` itself, or the shipped case file or folder that a bare name means.

    Order: an existing file ``path``; a shipped file ``<name>.toml`` (``folder``: ``""``
    for cases, ``"sweeps"`` for sweep files); an existing folder ``path``; a shipped
    folder (``hard``). A path with a separator is returned unchanged, and so is a name
    found nowhere, so that reading it reports it missing.
    """
    text = str(path)
    local = Path(path)
    if local.is_file() or any(c in text for c in "/\\"):
        return local
    base = package_data("cases", folder) if folder else package_data("cases")
    for candidate in (base / f"{text}.toml", local, base / text):
        if candidate.exists():
            return candidate
    return local


def shipped_case_dirs() -> list[Path]:
    """Directories holding the shipped cases, searched for a case given by name."""
    return [d for d in (package_data("cases"),) if d.is_dir()]


def read_input_bytes(path: Path, kind: str, limit: int, file: str = "", key: str = "") -> bytes:
    """The content of ``path`` if it is a regular file of at most ``limit`` bytes.

    Parameters
    ----------
    path : Path
        The file to read.
    kind : str
        What the file is, for messages ("case", "pressure curve", ...).
    limit : int
        Largest size accepted [bytes].
    file, key : str
        The file and key that named ``path`` (for messages); default ``path`` itself.

    Raises
    ------
    CaseError
        Missing, not a regular file (a directory, a device, a FIFO), too large or
        unreadable. A FIFO or device is never opened, so reading cannot block.
    """
    where = file or str(path)
    try:
        info = os.stat(path)
    except FileNotFoundError:
        raise CaseError(where, key, f"no such {kind} file: {path}") from None
    except OSError as exc:
        raise CaseError(where, key, f"cannot read {kind} file {path}: {exc.strerror}") from None
    if not stat.S_ISREG(info.st_mode):
        raise CaseError(where, key, f"{path} is not a regular file; expected a {kind} file")
    if info.st_size > limit:
        raise CaseError(
            where, key, f"{kind} file {path} is {info.st_size} bytes; at most {limit} are read"
        )
    try:
        with open(path, "rb") as handle:
            data = handle.read(limit + 1)
    except OSError as exc:
        raise CaseError(where, key, f"cannot read {kind} file {path}: {exc.strerror}") from None
    if len(data) > limit:
        raise CaseError(where, key, f"{kind} file {path} is larger than {limit} bytes")
    return data


def read_input_text(path: Path, kind: str, limit: int, file: str = "", key: str = "") -> str:
    """:func:`read_input_bytes` decoded as UTF-8 (a decode error is a :class:`CaseError`)."""
    data = read_input_bytes(path, kind, limit, file, key)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise CaseError(
            file or str(path),
            key,
            f"{kind} file {path} is not UTF-8 text (invalid byte at offset {exc.start})",
        ) from None


def read_toml(path: Path, kind: str) -> tuple[dict[str, Any], str]:
    """Parse the TOML file ``path``; returns its data and its text.

    Raises
    ------
    CaseError
        If the file is missing, not a regular file, too large, not UTF-8, not valid
        TOML or nested deeper than :data:`MAX_TOML_NESTING`.
    """
    text = read_input_text(Path(path), kind, MAX_TOML_BYTES)
    return parse_toml(text, str(path)), text


def parse_toml(text: str, file: str) -> dict[str, Any]:
    """Parse TOML ``text`` (from ``file``), refusing very deep nesting."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise CaseError(file, "", f"not valid TOML: {exc}") from None
    except RecursionError:
        raise CaseError(file, "", f"nested deeper than {MAX_TOML_NESTING} levels") from None
    if _depth(data) > MAX_TOML_NESTING:
        raise CaseError(file, "", f"nested deeper than {MAX_TOML_NESTING} levels")
    return data


def _depth(value: Any, level: int = 0) -> int:
    if level > MAX_TOML_NESTING:
        return level
    if isinstance(value, dict):
        return max((_depth(v, level + 1) for v in value.values()), default=level + 1)
    if isinstance(value, list):
        return max((_depth(v, level + 1) for v in value), default=level + 1)
    return level


def resolve_reference(
    reference: object,
    file: str,
    key: str,
    kind: str,
    allow_external: bool = False,
    by_name: bool = False,
) -> Path:
    """The file that ``reference`` (a value of ``key`` in ``file``) names.

    A relative path is taken relative to ``file``'s directory and must stay inside it,
    an absolute path or one that climbs out (``..``, a symbolic link) needs
    ``allow_external`` (``--allow-external-paths``); the shipped cases' directory is
    always allowed. With ``by_name``, a bare name
    without suffix (``"reference_r134a_lbp"``) that is not a file beside ``file`` is
    looked up among the shipped cases.

    Raises
    ------
    CaseError
        Not a string, escaping without permission, or no such file.
    """
    if not isinstance(reference, str) or not reference.strip():
        raise CaseError(file, key, f"expected the file name of a {kind}, e.g. 'base.toml'")
    here = Path(file).resolve().parent
    candidates = [here / reference]
    if by_name and "/" not in reference and "\\" not in reference:
        if not reference.endswith(".toml"):
            candidates = [here / f"{reference}.toml"]
            candidates += [d / f"{reference}.toml" for d in shipped_case_dirs()]
    for candidate in candidates:
        resolved = candidate.resolve()
        if not resolved.exists():
            continue
        inside = resolved.is_relative_to(here) or any(
            resolved.is_relative_to(d) for d in shipped_case_dirs()
        )
        if not inside and not allow_external:
            raise CaseError(
                file,
                key,
                f"{reference!r} lies outside the directory of {Path(file).name}; name a file "
                "beside it (or a shipped case by name), or pass --allow-external-paths "
                "(allow_external_paths=True) to read it",
            )
        return resolved
    names = "" if not by_name else " or a shipped case name, e.g. 'reference_r134a_lbp'"
    raise CaseError(file, key, f"no such {kind}: {reference!r} (a file beside {file}{names})")
