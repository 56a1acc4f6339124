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
from difflib import get_close_matches
from functools import cache
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


#: The package that each kind of shipped file is installed as: the top-level folders
#: ``cases/`` and ``refrigerants/`` of the source tree, mapped onto these subpackages by
#: ``[tool.setuptools.package-dir]`` in ``pyproject.toml``.
SHIPPED_PACKAGES = {
    "cases": "recipsim.shipped_cases",
    "refrigerants": "recipsim.shipped_refrigerants",
}


@cache
def shipped_dir(kind: str) -> Path:
    """The folder of the shipped case files (``kind`` ``"cases"``) or refrigerant files
    (``"refrigerants"``).

    When recipsim runs from a source tree (``<root>/src/recipsim``, whether installed in
    editable mode or put on ``PYTHONPATH``), the tree's own ``<root>/<kind>/`` folder,
    so that the code and the data always come from the same checkout. Otherwise (a wheel
    installed with ``pip install .``) the installed package of :data:`SHIPPED_PACKAGES`,
    found with :mod:`importlib.resources`; an editable install finds the same top-level
    folder that way. Found once per process: a sweep asks at every point.

    Parameters
    ----------
    kind : str
        ``"cases"`` or ``"refrigerants"``.

    Returns
    -------
    Path
        The folder, resolved (recipsim is installed as files, never zipped).
    """
    package = SHIPPED_PACKAGES[kind]
    here = Path(__file__).resolve()  # <root>/src/recipsim/case/files.py in a source tree
    root = here.parents[3]
    if here.parents[2].name == "src" and (root / kind / "__init__.py").is_file():
        return root / kind
    return Path(str(resources.files(package))).resolve()


def case_dirs(folder: str = "") -> list[Path]:
    """The folders searched for a case given by name, in order.

    First the working directory's own ``cases/<folder>`` (a user's case shadows the
    shipped case of the same name), then the shipped ``cases/<folder>``
    (:func:`shipped_dir`); only the folders that exist, each once, resolved.

    Parameters
    ----------
    folder : str
        ``""`` for cases, ``"sweeps"`` for sweep files.
    """
    dirs: list[Path] = []
    for base in (Path.cwd() / "cases", shipped_dir("cases")):
        candidate = (base / folder).resolve()
        if candidate.is_dir() and candidate not in dirs:
            dirs.append(candidate)
    return dirs


def shipped_path(path: str | Path, folder: str = "") -> Path:
    """``path`` itself, or the local or shipped case file or folder that a bare name means.

    Order: an existing file ``path``; a file ``<name>.toml`` in :func:`case_dirs`
    (``folder``: ``""`` for cases, ``"sweeps"`` for sweep files), the working
    directory's ``cases/`` before the shipped one; an existing folder ``path``; a folder
    ``<name>`` in :func:`case_dirs` (``hard``), or a file ``<name>`` there
    (``reference_r134a_lbp.toml``). A path with a separator is returned unchanged, and
    so is a name found nowhere, so that reading it reports it missing
    (:func:`find_case_file` reports it with the closest names).
    """
    text = str(path)
    local = Path(path)
    if local.is_file() or any(c in text for c in "/\\"):
        return local
    dirs = case_dirs(folder)
    for candidate in [d / f"{text}.toml" for d in dirs] + [local] + [d / text for d in dirs]:
        if candidate.exists():
            return candidate
    return local


def find_case_file(path: str | Path, folder: str = "", kind: str = "case") -> Path:
    """The file that ``path`` names: :func:`shipped_path`, refusing a bare name that is
    neither a file nor the name of a case.

    Parameters
    ----------
    path : str or Path
        A file, or the name of a case in the working directory's ``cases/<folder>`` or
        among the shipped ones.
    folder : str
        ``""`` for cases, ``"sweeps"`` for sweep files.
    kind : str
        What the file is, for the message (``"case"``, ``"sweep"``).

    Returns
    -------
    Path
        The file; ``path`` itself when it names a folder or a path with a separator
        (reading it then reports what is wrong).

    Raises
    ------
    CaseError
        A bare name found nowhere: one line naming it, with the closest names of
        :func:`case_names` (``did you mean reference_r134a_lbp?``).
    """
    found = shipped_path(path, folder)
    if found.is_file():
        return found
    text = str(path)
    if found.exists() or any(c in text for c in "/\\"):
        return Path(path)
    where = "./cases" + (f"/{folder}" if folder else "")
    stem = text.removesuffix(".toml")
    close = get_close_matches(stem, case_names(folder), n=3)
    hint = f"did you mean {_alternatives(close)}?" if close else "`recipsim cases` lists them"
    raise CaseError(
        text,
        "",
        f"no such {kind} file: {text} (not a file, nor the name of a {kind} in {where} "
        f"or of a shipped {kind}); {hint}",
    )


def _alternatives(names: list[str]) -> str:
    """``a``, ``a or b``, ``a, b or c``."""
    return names[0] if len(names) == 1 else f"{', '.join(names[:-1])} or {names[-1]}"


def case_names(folder: str = "") -> list[str]:
    """The names that :func:`shipped_path` finds in :func:`case_dirs`: the stems of the
    ``*.toml`` files there, sorted, each once."""
    return sorted({p.stem for d in case_dirs(folder) for p in d.glob("*.toml")})


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
    ``allow_external`` (``--allow-external-paths``); the shipped cases' folder is always
    allowed, and so is the working directory's ``cases/`` for a case found there by
    name. With ``by_name``, a bare name without suffix
    (``"reference_r134a_lbp"``) that is not a file beside ``file`` is looked up in
    :func:`case_dirs`: the working directory's ``cases/``, then the shipped cases.

    Raises
    ------
    CaseError
        Not a string, escaping without permission, or no such file.
    """
    if not isinstance(reference, str) or not reference.strip():
        raise CaseError(file, key, f"expected the file name of a {kind}, e.g. 'base.toml'")
    here = Path(file).resolve().parent
    candidates = [here / reference]
    named = by_name and "/" not in reference and "\\" not in reference
    named = named and not reference.endswith(".toml")
    # a name may find a case in ./cases or the shipped ones; a path, the shipped ones
    allowed = case_dirs() if named else [shipped_dir("cases")]
    if named:
        candidates = [here / f"{reference}.toml"] + [d / f"{reference}.toml" for d in allowed]
    for candidate in candidates:
        resolved = candidate.resolve()
        if not resolved.exists():
            continue
        inside = resolved.is_relative_to(here) or any(resolved.is_relative_to(d) for d in allowed)
        if not inside and not allow_external:
            raise CaseError(
                file,
                key,
                f"{reference!r} lies outside the directory of {Path(file).name}; name a file "
                "beside it (or a shipped case by name), or pass --allow-external-paths "
                "(allow_external_paths=True) to read it",
            )
        return resolved
    names = "" if not by_name else " or a case name, e.g. 'reference_r134a_lbp'"
    close = get_close_matches(reference, case_names(), n=3) if named else []
    hint = f"; did you mean {_alternatives(close)}?" if close else ""
    raise CaseError(file, key, f"no such {kind}: {reference!r} (a file beside {file}{names}){hint}")
