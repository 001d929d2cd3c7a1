"""The shared ``__main__`` wrapper of every stock node: user errors as one line and exit 2."""

from __future__ import annotations

import sys
from collections.abc import Callable

from launchkit.errors import LaunchkitError


def run(main: Callable[[list[str]], int], program: str) -> int:
    """Run ``main(sys.argv)``; report a launchkit error as ``program: error: ...``, no traceback.

    Returns the process exit status: ``main``'s own, the error's (2 for a user mistake), or 0
    after Ctrl-C.
    """
    try:
        return main(sys.argv)
    except LaunchkitError as exc:
        print(f"[{program}] {exc.format()}", file=sys.stderr, flush=True)
        return exc.exit_status
    except KeyboardInterrupt:
        return 0
