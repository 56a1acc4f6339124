"""Exceptions with messages meant for the user (no traceback is shown for them)."""

from __future__ import annotations


class RecipsimError(Exception):
    """Base class of errors that the command line reports as one message."""


class CaseError(RecipsimError):
    """A case, refrigerant or sweep file is invalid.

    Parameters
    ----------
    file : str
        Path of the offending file.
    key : str
        Dotted key inside the file (``""`` for the whole file).
    message : str
        What is wrong and what is allowed.
    """

    def __init__(self, file: str, key: str, message: str) -> None:
        self.file = str(file)
        self.key = key
        self.message = message
        where = f"{self.file}: {key}: " if key else f"{self.file}: "
        super().__init__(where + message)


class SolverError(RecipsimError):
    """The integration failed; the message names crank angle and state."""
