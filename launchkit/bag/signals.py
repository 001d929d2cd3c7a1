"""Stopping a long-running bag command on SIGINT or SIGTERM, as rosbag2 does."""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from types import FrameType

#: How often a command's main thread looks at the stop event (seconds).
POLL = 0.1


@contextmanager
def stop_on_signals() -> Iterator[threading.Event]:
    """An event that SIGINT and SIGTERM set; the previous handlers are restored after.

    The handler only sets the event: it runs in the main thread between two bytecodes, maybe
    while that thread holds a queue's lock, so it must take no lock the main thread could hold.
    The main thread therefore never waits on this event; it looks at it every :data:`POLL`
    seconds. A second signal while the command finishes its bag changes nothing: closing a bag
    properly is the point of stopping on a signal (the launcher's SIGKILL still ends it).
    """
    stop = threading.Event()

    def on_signal(signum: int, frame: FrameType | None) -> None:
        stop.set()

    previous = {sig: signal.signal(sig, on_signal) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield stop
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
