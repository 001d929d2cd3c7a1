"""Reading single keys from a terminal, always giving the terminal back as it was found."""

from __future__ import annotations

import os
import select
import signal
import termios
import threading
import tty
from types import TracebackType

from launchkit.errors import UserError


class KeyReader:
    """Reads one key at a time from a terminal in raw mode.

    ``program`` (of ``package``) names the node in the error for an input that is not a
    terminal. Raw mode lasts only while a key is awaited, so what the node prints in between
    keeps the terminal's normal line endings; leaving the ``with`` block restores the saved settings
    whatever happened (exception, signal turned into an exception, Ctrl-C).
    """

    def __init__(
        self, fd: int, program: str = "teleop_twist_keyboard", package: str | None = None
    ) -> None:
        if not os.isatty(fd):
            raise UserError(
                f"{program} reads keys from a terminal, and its input is not one",
                expected=f"to be run in a terminal, e.g. `launchkit exec {package or program} "
                f"{program}` in a second terminal",
            )
        self.fd = fd
        self._saved = termios.tcgetattr(fd)

    def __enter__(self) -> KeyReader:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.restore()

    def restore(self) -> None:
        """Put the terminal back into the mode it had when the reader was made."""
        termios.tcsetattr(self.fd, termios.TCSADRAIN, self._saved)

    def read_key(self, timeout: float | None = None) -> str | None:
        """The next key pressed, or None when ``timeout`` seconds pass without one."""
        # TCSANOW, not setraw's default TCSAFLUSH: keys typed ahead (the rest of an arrow key's
        # three bytes) must not be thrown away
        tty.setraw(self.fd, termios.TCSANOW)
        try:
            ready, _, _ = select.select([self.fd], [], [], timeout)
            if not ready:
                return None
            data = os.read(self.fd, 1)
            if not data:
                raise EOFError("the terminal closed")
            return data.decode("latin-1")
        finally:
            self.restore()


def stop_on_signals() -> threading.Event:
    """An event set by SIGINT, SIGTERM or SIGHUP.

    These replace the ROS layer's handlers, which would shut the node down at once: a key loop
    stops instead, and can finish what it must do before the node closes.
    """
    stop = threading.Event()
    for signum in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
        signal.signal(signum, lambda *_: stop.set())
    return stop
