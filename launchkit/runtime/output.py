"""Where launch lines and child output go: the screen, ``launch.log``, per-process files.

Screen lines keep ROS's shapes: ``[LEVEL] [logger]: message`` for the launcher's own lines and
``[name-N] line`` for a child's, all on stdout; colours only when stdout is a terminal.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import IO

_LEVEL_COLOURS = {"ERROR": "\033[31m", "WARNING": "\033[33m", "DEBUG": "\033[2m"}
_NAME_COLOURS = ["\033[36m", "\033[32m", "\033[35m", "\033[34m", "\033[33m", "\033[96m"]
_RESET = "\033[0m"


class Output:
    """The launcher's output: screen and the run's log files."""

    def __init__(self, stream: IO[str] | None = None, colour: bool | None = None) -> None:
        self.stream = stream or sys.stdout
        self.colour = self.stream.isatty() if colour is None else colour
        self.run_dir: Path | None = None
        self._launch_log: IO[str] | None = None
        self._own: dict[str, IO[str]] = {}

    def open_logs(self, run_dir: Path) -> None:
        """Start writing ``launch.log`` in ``run_dir``."""
        self.run_dir = run_dir
        self._launch_log = open(run_dir / "launch.log", "a", buffering=1)

    def launch_line(self, level: str, logger: str, message: str) -> None:
        """``[LEVEL] [logger]: message`` to the screen and launch.log."""
        text = f"[{level}] [{logger}]: {message}"
        if self._launch_log is not None:
            self._launch_log.write(text + "\n")
        if self.colour and level in _LEVEL_COLOURS:
            text = f"{_LEVEL_COLOURS[level]}{text}{_RESET}"
        self._write(text)

    def child_line(self, label: str, index: int, line: str, mode: str, stream: str) -> None:
        """One line of a child's output, routed by its ``output`` mode."""
        to_screen = mode in ("screen", "both", "full") or (mode == "log" and stream == "stderr")
        to_log = mode in ("log", "both", "full")
        to_own = mode in ("own_log", "full")
        text = f"[{label}] {line}"
        if to_screen:
            if self.colour:
                colour = _NAME_COLOURS[index % len(_NAME_COLOURS)]
                self._write(f"{colour}[{label}]{_RESET} {line}")
            else:
                self._write(text)
        if to_log and self._launch_log is not None:
            self._launch_log.write(text + "\n")
        if to_own and self.run_dir is not None:
            key = f"{label}-{stream}"
            handle = self._own.get(key)
            if handle is None:
                handle = open(self.run_dir / f"{key}.log", "a", buffering=1)
                self._own[key] = handle
            handle.write(line + "\n")

    def _write(self, text: str) -> None:
        try:
            self.stream.write(text + "\n")
            self.stream.flush()
        except (BrokenPipeError, ValueError):
            pass  # the reader went away (`launchkit run ... | head`); keep supervising

    def close(self) -> None:
        """Close the log files."""
        for handle in [self._launch_log, *self._own.values()]:
            if handle is not None:
                handle.close()
        self._launch_log = None
        self._own.clear()
