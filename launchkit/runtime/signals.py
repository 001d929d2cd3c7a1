"""Signals to the launcher, delivered to the supervisor's loop as data on a pipe.

The Python-level handlers do nothing; ``signal.set_wakeup_fd`` writes each signal's number to
a pipe that the loop's selector watches, so a signal is handled on the loop, in order with the
children's output and exits, never in the middle of something else.
"""

from __future__ import annotations

import os
import signal

#: What the launcher handles: each starts an orderly shutdown, a second one escalates.
HANDLED_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT)


class SignalPipe:
    """The wakeup pipe and the handlers installed while a launch runs."""

    def __init__(self) -> None:
        self._read_fd, self._write_fd = os.pipe()
        self._previous: dict[int, signal._HANDLER] = {}

    @property
    def fd(self) -> int:
        """The end the loop watches for readability."""
        return self._read_fd

    def install(self) -> None:
        """Route :data:`HANDLED_SIGNALS` to the pipe (main thread only)."""
        os.set_blocking(self._read_fd, False)
        os.set_blocking(self._write_fd, False)
        signal.set_wakeup_fd(self._write_fd, warn_on_full_buffer=False)
        for signum in HANDLED_SIGNALS:
            self._previous[signum] = signal.signal(signum, _ignore)

    def pending(self) -> list[int]:
        """The signals received since the last call, in order."""
        try:
            return list(os.read(self._read_fd, 512))
        except BlockingIOError:
            return []

    def close(self) -> None:
        """Put the previous handlers back (if :meth:`install` ran), then close the pipe."""
        if self._previous:
            for signum, handler in self._previous.items():
                signal.signal(signum, handler)
            self._previous.clear()
            signal.set_wakeup_fd(-1)
        os.close(self._read_fd)
        os.close(self._write_fd)


def _ignore(signum: int, frame: object) -> None:
    """Python-level handler: the wakeup fd carries the signal to the loop."""
