"""``python -m launchkit.bridge``: the bridge as a launch's node (``launchkit_bridge bridge``)."""

from __future__ import annotations

import sys

from launchkit.bridge.cli import main
from launchkit.stock import _entry

if __name__ == "__main__":
    sys.exit(_entry.run(lambda argv: main(argv[1:], argv[0]), "launchkit_bridge"))
