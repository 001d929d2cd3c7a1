"""How every stock node starts: the one ``__main__`` wrapper, turning a user error into one line
and exit status 2 (no traceback), and Ctrl-C into a clean exit.

Each node module ends with ``sys.exit(_entry.run(main, "program"))``; its ``main(argv)`` raises a
:class:`launchkit.errors.UserError` (or a subclass) for a bad command line, parameter or file.
"""

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
        print(f"{program}: {exc.format()}", file=sys.stderr, flush=True)
        return exc.exit_status
    except KeyboardInterrupt:
        return 0
