"""Where launch lines and child output go: the screen, ``launch.log``, per-process files.

Screen lines keep ROS's shapes: ``[LEVEL] [logger]: message`` for the launcher's own lines and
``[name-N] line`` for a child's, all on stdout; colours only when stdout is a terminal. Control
characters in the launcher's lines and in a child's ``[name-N]`` are escaped (a child's own text
is passed on as it is). Log
files are rotated and capped (:mod:`launchkit.runtime.logfiles`).
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import IO

from launchkit.errors import printable
from launchkit.runtime.logdir import LogLimits
from launchkit.runtime.logfiles import RunLogs

_LEVEL_COLOURS = {"ERROR": "\033[31m", "WARNING": "\033[33m", "DEBUG": "\033[2m"}
_NAME_COLOURS = ["\033[36m", "\033[32m", "\033[35m", "\033[34m", "\033[33m", "\033[96m"]
_BOLD = "\033[1m"
_RESET = "\033[0m"
_LAUNCH_LOG = "launch.log"


class Output:
    """The launcher's output: screen and the run's log files."""

    def __init__(self, stream: IO[str] | None = None, colour: bool | None = None) -> None:
        self.stream = stream or sys.stdout
        self.colour = self.stream.isatty() if colour is None else colour
        self.run_dir: Path | None = None
        self._logs: RunLogs | None = None
        self.screen_writes = 0  # how many times lines went to the screen

    def open_logs(self, run_dir: Path, limits: LogLimits | None = None) -> None:
        """Start writing ``launch.log`` (and own logs) in ``run_dir``, within ``limits``."""
        self.run_dir = run_dir
        self._logs = RunLogs(run_dir, limits or LogLimits())

    def launch_line(
        self, level: str, logger: str, message: str, *, screen: bool = True, bold: bool = False
    ) -> None:
        """``[LEVEL] [logger]: message`` to the screen (unless not ``screen``; in bold on a
        terminal if ``bold``) and launch.log."""
        self._launch_lines(level, [printable(f"[{level}] [{logger}]: {message}")], screen, bold)

    def launch_error(self, formatted: str, *, screen: bool = True) -> None:
        """An error as :meth:`LaunchkitError.format` wrote it (each of its lines escaped there):
        ``[ERROR] [launch]: FILE:LINE: error: ...``, then its quoted lines and hint below it."""
        first, *rest = formatted.split("\n")
        self._launch_lines("ERROR", [printable(f"[ERROR] [launch]: {first}"), *rest], screen)

    def _launch_lines(self, level: str, lines: list[str], screen: bool, bold: bool = False) -> None:
        if self._logs is not None:
            self._logs.write(_LAUNCH_LOG, lines, child=False)
        if not screen:
            return
        if self.colour and level in _LEVEL_COLOURS:
            lines = [f"{_LEVEL_COLOURS[level]}{line}{_RESET}" for line in lines]
        elif self.colour and bold:
            lines = [f"{_BOLD}{line}{_RESET}" for line in lines]
        self._write(lines)

    def child_lines(self, label: str, index: int, lines: list[str], mode: str, stream: str) -> None:
        """Lines of a child's output, routed by its ``output`` mode, written in one go."""
        if not lines:
            return
        to_screen = mode in ("screen", "both", "full") or (mode == "log" and stream == "stderr")
        to_log = mode in ("log", "both", "full")
        to_own = mode in ("own_log", "full")
        label = printable(label)  # the child's lines are its own; launchkit's prefix is not
        if to_screen:
            if self.colour:
                prefix = f"{_NAME_COLOURS[index % len(_NAME_COLOURS)]}[{label}]{_RESET} "
            else:
                prefix = f"[{label}] "
            self._write([prefix + line for line in lines])
        if self._logs is None:
            return
        if to_log:
            self._logs.write(_LAUNCH_LOG, [f"[{label}] {line}" for line in lines], child=True)
        if to_own:
            self._logs.write(f"{label}-{stream}.log", lines, child=True)

    def _write(self, lines: list[str]) -> None:
        self.screen_writes += 1
        try:
            self.stream.write("".join(line + "\n" for line in lines))
            self.stream.flush()
        except (BrokenPipeError, ValueError):
            pass  # the reader went away (`launchkit run ... | head`); keep supervising

    def close(self) -> None:
        """Close the log files."""
        if self._logs is not None:
            self._logs.close()
            self._logs = None
