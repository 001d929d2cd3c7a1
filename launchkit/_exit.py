"""Ending a launchkit process promptly once its work is done (or Ctrl-C ended it).

A node or CLI process that has imported the ROS layer (zenoh, the message types, numpy; the
stock nodes also PyBullet) spends 0.3 to 2.5 s of a busy machine's time in the
interpreter's own teardown of thousands of modules and objects after ``main`` returns: long
enough for a supervisor or a test to give up on it after SIGINT. Nothing in that teardown is
needed: the sockets close with the process, and the cleanup that matters is done here first.
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
    context = sys.modules.get("launchkit.ros.context")
    if context is not None:
        status = context.exit_status(status)
    watchdog = threading.Timer(cleanup_within, os._exit, (status,))
    watchdog.daemon = True
    watchdog.start()
    try:
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
