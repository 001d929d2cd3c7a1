"""Bounded shutdown for the gazebo_ros processes."""

from __future__ import annotations

import os
import sys
import threading
from typing import Any


def shutdown_within(ros: Any, seconds: float, code: int) -> None:
    """``ros.shutdown()``, but exit with ``code`` anyway if it has not returned in ``seconds``.

    A node process must never outlive its supervisor's stop request because closing the
    transport blocked; the supervisor's SIGKILL may not come if the supervisor itself is gone.
    """
    done = threading.Event()

    def _close() -> None:
        try:
            ros.try_shutdown()
        finally:
            done.set()

    threading.Thread(target=_close, daemon=True, name="shutdown").start()
    if not done.wait(seconds):
        print("shutdown of the ROS session timed out; exiting", file=sys.stderr, flush=True)
        sys.stdout.flush()
        os._exit(code)
