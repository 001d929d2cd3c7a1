"""Keyboard controls of ``launchkit bag play``, as ``ros2 bag play`` has them.

Only when stdin is a terminal and this process is its foreground process group: a player run
by a launch file, in the background or with stdin redirected reads nothing and changes nothing
(reading a terminal from the background would stop the process with SIGTTIN). The terminal is
put in cbreak mode (keys arrive one by one, Ctrl-C still interrupts) and restored afterwards.
"""

from __future__ import annotations

import os
import select
import sys
import termios
import threading
import tty
from collections.abc import Callable
from typing import IO, Any

#: Key names (``ros2 bag play``'s) and the bytes a terminal sends for them.
KEYS = {
    "SPACE": b" ",
    "CURSOR_RIGHT": b"\x1b[C",
    "CURSOR_UP": b"\x1b[A",
    "CURSOR_DOWN": b"\x1b[B",
    "s": b"s",
}


def controls_terminal(stream: IO[str]) -> bool:
    """Whether ``stream`` is a terminal this process may read keys from now."""
    try:
        fd = stream.fileno()
        return os.isatty(fd) and os.tcgetpgrp(fd) == os.getpgrp()
    except (OSError, ValueError, AttributeError):
        return False


def parse_keys(data: bytes) -> list[str]:
    """The key names in a chunk read from the terminal (unknown bytes are skipped)."""
    found: list[str] = []
    index = 0
    while index < len(data):
        for name, sequence in KEYS.items():
            if data.startswith(sequence, index):
                found.append(name)
                index += len(sequence)
                break
        else:
            index += 3 if data.startswith(b"\x1b[", index) else 1
    return found


class KeyboardControls:
    """Calls ``actions[key]()`` for each key pressed, from a thread, until :meth:`close`."""

    def __init__(self, actions: dict[str, Callable[[], None]], stream: IO[str] | None = None):
        self.actions = actions
        self.stream = stream if stream is not None else sys.stdin
        self._saved: list[Any] | None = None
        self._thread: threading.Thread | None = None
        self._wake_read, self._wake_write = os.pipe()

    def start(self) -> bool:
        """Begin reading keys; False (and nothing done) when the terminal is not ours."""
        if not controls_terminal(self.stream):
            return False
        fd = self.stream.fileno()
        self._saved = termios.tcgetattr(fd)
        tty.setcbreak(fd)
        self._thread = threading.Thread(target=self._read, args=(fd,), daemon=True, name="keys")
        self._thread.start()
        return True

    def _read(self, fd: int) -> None:
        while True:
            ready, _, _ = select.select([fd, self._wake_read], [], [])
            if self._wake_read in ready:
                return
            try:
                data = os.read(fd, 32)
            except OSError:
                return
            if not data:
                return
            for key in parse_keys(data):
                action = self.actions.get(key)
                if action is not None:
                    action()

    def close(self) -> None:
        """Stop reading and give the terminal its settings back (once; later calls do nothing)."""
        if self._wake_write < 0:
            return
        os.write(self._wake_write, b"x")
        if self._thread is not None:
            self._thread.join(2.0)
        if self._saved is not None:
            try:
                termios.tcsetattr(self.stream.fileno(), termios.TCSADRAIN, self._saved)
            except (OSError, termios.error):
                pass
            self._saved = None
        os.close(self._wake_read)
        os.close(self._wake_write)
        self._wake_read = self._wake_write = -1
