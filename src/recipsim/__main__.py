"""``python -m recipsim``: the ``recipsim`` command."""

from recipsim.cli import main

raise SystemExit(main())
