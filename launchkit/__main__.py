"""``python -m launchkit`` is the ``launchkit`` command."""

from launchkit.cli import console_main

console_main()
