"""Ending a launchkit process once its work is done (or Ctrl-C ended it), in bounded time.

Two things can keep a node or CLI process that has used the ROS layer from ending after
``main`` returns. A Zenoh session that will not close holds non-daemon threads, which the
interpreter joins at exit: the process would hang until the launcher's SIGKILL, or forever
without a launcher. And the interpreter's own teardown of the modules it imported (zenoh, the
message types, numpy; the stock nodes also PyBullet) took 0.3 to 2.6 s on a busy two-core
machine, long enough for a supervisor to escalate to SIGKILL after SIGINT and report a clean
stop as a kill (issue 9: ``topic hz`` was SIGKILLed in a loaded CI run). So the cleanup that
matters (the ROS sessions, ``atexit``, the output streams) runs here under a bound, and then the
process ends without the teardown, whose work the kernel does anyway.
"""

from __future__ import annotations

import atexit
import os
import sys
import threading
from typing import NoReturn

CLEANUP_BOUND = 0.5  # seconds the cleanup may take before the process exits regardless


def exit_promptly(status: int, cleanup_within: float = CLEANUP_BOUND) -> NoReturn:
    """Exit with ``status`` now: close the ROS sessions, run the ``atexit`` handlers and flush
    stdout and stderr, then end the process without the interpreter's teardown.

    If the cleanup has not finished within ``cleanup_within`` seconds (a transport that will
    not close), the process exits anyway: stopping must never hang.
    """
    watchdog = threading.Timer(cleanup_within, os._exit, (status,))
    watchdog.daemon = True
    watchdog.start()
    try:
        context = sys.modules.get("launchkit.ros.context")
        if context is not None:
            context.shutdown_all()
        atexit._run_exitfuncs()
    finally:
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except (OSError, ValueError):
                pass  # the reader went away; nothing more to say
        os._exit(status)
