"""How every stock node starts: the one ``__main__`` wrapper, turning a user error into one line
and exit status 2 (no traceback), Ctrl-C into a clean exit, and exits promptly
(:mod:`launchkit._exit`).

Each node module ends with ``_entry.run(main, "program")``; its ``main(argv)`` raises a
:class:`launchkit.errors.UserError` (or a subclass) for a bad command line, parameter or file.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from typing import NoReturn

from launchkit._exit import exit_promptly
from launchkit.errors import LaunchkitError


def run(main: Callable[[list[str]], int], program: str) -> NoReturn:
    """Run ``main(sys.argv)``; report a launchkit error as ``program: error: ...``, no traceback.

    Then exit promptly (see :mod:`launchkit._exit`) with ``main``'s status, the error's (2 for
    a user mistake), or 0 after Ctrl-C (``KeyboardInterrupt``) or SIGTERM (the spinning
    executor's ``ExternalShutdownException``): a stop request is a normal end for a stock node.
    """
    from launchkit.ros.executor import ExternalShutdownException

    try:
        status = main(sys.argv)
    except LaunchkitError as exc:
        print(f"{program}: {exc.format()}", file=sys.stderr, flush=True)
        status = exc.exit_status
    except (KeyboardInterrupt, ExternalShutdownException):
        status = 0
    exit_promptly(status)
