"""``python -m launchkit`` is the ``launchkit`` command."""

from launchkit.cli import main

raise SystemExit(main())
