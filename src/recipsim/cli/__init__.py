"""The ``recipsim`` command line: one module per subcommand, on top of the library.

:mod:`.main` (the parser and ``recipsim run``), :mod:`.options` (options and exit
statuses shared by the subcommands), :mod:`.sweep`, :mod:`.compare`, :mod:`.paper`,
:mod:`.bench`, :mod:`.check`, :mod:`.cases` (the list of shipped cases).
"""

from recipsim.cli.main import main

__all__ = ["main"]
