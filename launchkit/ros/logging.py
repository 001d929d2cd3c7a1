"""Node loggers with ROS's levels, output shape and ``--log-level`` (rclpy's ``rclpy.logging``).

A node's logger also publishes what it prints on ``/rosout`` (rcl's rosout handler): the node
registers a sink for its logger name with :func:`add_rosout_sink`, and a message of that logger
or of one of its children goes to it.
"""

from __future__ import annotations

import enum
import os
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path
from types import FrameType
from typing import Any, TextIO


class LoggingSeverity(enum.IntEnum):
    """rcutils severities."""

    UNSET = 0
    DEBUG = 10
    INFO = 20
    WARN = 30
    ERROR = 40
    FATAL = 50


_BY_NAME = {s.name.lower(): s for s in LoggingSeverity}
_BY_NAME["warning"] = LoggingSeverity.WARN

_levels: dict[str, LoggingSeverity] = {}  # logger name -> level ("" is the default)
_default_level = LoggingSeverity.INFO
_write_lock = threading.Lock()


def severity(level: str | int | LoggingSeverity) -> LoggingSeverity:
    """A severity from a name (``"warn"``) or number."""
    if isinstance(level, str):
        try:
            return _BY_NAME[level.lower()]
        except KeyError:
            raise ValueError(
                f"unknown log level {level!r} (expected debug, info, warn, error or fatal)"
            ) from None
    return LoggingSeverity(level)


def set_logger_level(
    name: str, level: str | int | LoggingSeverity, detailed_error: bool = False
) -> None:
    """Set the level of logger ``name`` (``""`` sets the default level)."""
    global _default_level
    value = severity(level)
    if name == "":
        _default_level = LoggingSeverity.INFO if value == LoggingSeverity.UNSET else value
    else:
        _levels[name] = value


def get_logger_level(name: str) -> LoggingSeverity:
    """The level set for logger ``name`` itself (UNSET if none)."""
    if name == "":
        return _default_level
    return _levels.get(name, LoggingSeverity.UNSET)


def get_logger_effective_level(name: str) -> LoggingSeverity:
    """The level that applies to logger ``name`` (its own, an ancestor's, or the default)."""
    while name:
        level = _levels.get(name, LoggingSeverity.UNSET)
        if level != LoggingSeverity.UNSET:
            return level
        name = name.rpartition(".")[0]
    return _default_level


def get_logging_severity_from_string(log_severity: str) -> LoggingSeverity:
    """A severity from its name (``"warn"``, ``"WARNING"``...)."""
    return severity(log_severity)


def initialize() -> None:
    """Start the logging system (nothing to do: it is ready at import)."""


def shutdown() -> None:
    """Stop the logging system (nothing to release)."""


def clear_config() -> None:
    """Forget every logger level: all loggers at the default level, INFO."""
    global _default_level
    _levels.clear()
    _default_level = LoggingSeverity.INFO


def get_logging_directory() -> Path:
    """Where ROS log files go (``ROS_LOG_DIR``, else ``$ROS_HOME/log``, else ``~/.ros/log``)."""
    explicit = os.environ.get("ROS_LOG_DIR")
    if explicit:
        return Path(explicit).expanduser()
    home = os.environ.get("ROS_HOME")
    return (Path(home).expanduser() if home else Path.home() / ".ros") / "log"


# (severity, logger name, message, file, function, line, stamp in ns)
RosoutSink = Callable[[LoggingSeverity, str, str, str, str, int, int], None]
_rosout: dict[str, RosoutSink] = {}
_in_sink = threading.local()


def add_rosout_sink(logger_name: str, sink: RosoutSink) -> None:
    """Send what ``logger_name`` and its children log to ``sink`` (a node's /rosout)."""
    _rosout[logger_name] = sink


def remove_rosout_sink(logger_name: str, sink: RosoutSink) -> None:
    """Stop sending ``logger_name``'s messages to ``sink``."""
    if _rosout.get(logger_name) == sink:
        del _rosout[logger_name]


def _sink_for(name: str) -> RosoutSink | None:
    while name:
        sink = _rosout.get(name)
        if sink is not None:
            return sink
        name = name.rpartition(".")[0]
    return None


def apply_log_levels(levels: dict[str, str]) -> None:
    """Apply ``--log-level`` settings (``{"": "debug", "talker": "warn"}``)."""
    for name, level in levels.items():
        set_logger_level(name, level)


def _stream() -> TextIO:
    return sys.stdout if os.environ.get("RCUTILS_LOGGING_USE_STDOUT") == "1" else sys.stderr


# rcutils' colours: DEBUG green, INFO plain, WARN yellow, ERROR and FATAL red (whole line)
_COLOURS = {
    LoggingSeverity.DEBUG: "\033[32m",
    LoggingSeverity.WARN: "\033[33m",
    LoggingSeverity.ERROR: "\033[31m",
    LoggingSeverity.FATAL: "\033[31m",
}
_RESET = "\033[0m"


def colourize(stream: TextIO) -> bool:
    """Whether log lines on ``stream`` get colours: ``RCUTILS_COLORIZED_OUTPUT=1`` or ``0``
    says so; unset, only on a terminal (as rcutils decides)."""
    setting = os.environ.get("RCUTILS_COLORIZED_OUTPUT", "").strip()
    if setting in ("0", "1"):
        return setting == "1"
    try:
        return stream.isatty()
    except (AttributeError, ValueError):
        return False


class RcutilsLogger:
    """A named logger: ``debug/info/warn/error/fatal(msg, once=, throttle_duration_sec=, ...)``."""

    def __init__(self, name: str = "") -> None:
        self.name = name
        self._once: set[Any] = set()
        self._last: dict[Any, float] = {}
        self._skipped: set[Any] = set()

    def get_child(self, name: str) -> RcutilsLogger:
        """The logger ``<this>.<name>``."""
        if not name:
            raise ValueError("Child logger name must not be empty.")
        return RcutilsLogger(f"{self.name}.{name}" if self.name else name)

    def set_level(self, level: str | int | LoggingSeverity) -> None:
        """Set this logger's level."""
        set_logger_level(self.name, level)

    def get_effective_level(self) -> LoggingSeverity:
        """This logger's level, else its nearest ancestor's, else the default."""
        return get_logger_effective_level(self.name)

    def is_enabled_for(self, level: str | int | LoggingSeverity) -> bool:
        """Whether a message of ``level`` would be printed."""
        return severity(level) >= self.get_effective_level()

    def log(self, message: Any, level: str | int | LoggingSeverity, **options: Any) -> bool:
        """Print ``message`` at ``level``; returns whether it was printed."""
        value = severity(level)
        name = str(options.get("name", self.name))
        if value < get_logger_effective_level(name):
            return False
        caller = _caller()
        site = (caller.f_code.co_filename, caller.f_lineno)
        if options.get("once"):
            if site in self._once:
                return False
            self._once.add(site)
        if options.get("skip_first") and site not in self._skipped:
            self._skipped.add(site)
            return False
        throttle = options.get("throttle_duration_sec")
        if throttle:
            now = time.monotonic()
            last = self._last.get(site)
            if last is not None and now - last < float(throttle):
                return False
            self._last[site] = now
        stamp = time.time_ns()
        text = str(message)
        seconds, nanoseconds = divmod(stamp, 1_000_000_000)
        line = f"[{value.name}] [{seconds}.{nanoseconds:09d}] [{name}]: {text}"
        stream = _stream()
        colour = _COLOURS.get(value)
        if colour is not None and colourize(stream):
            line = f"{colour}{line}{_RESET}"
        line += "\n"
        with _write_lock:
            stream.write(line)
            stream.flush()
        sink = _sink_for(name)
        if sink is not None and not getattr(_in_sink, "active", False):
            _in_sink.active = True  # a message logged while publishing is not published
            try:
                code = caller.f_code
                sink(value, name, text, code.co_filename, code.co_name, caller.f_lineno, stamp)
            finally:
                _in_sink.active = False
        return True

    def debug(self, message: Any, **options: Any) -> bool:
        """Log at DEBUG."""
        return self.log(message, LoggingSeverity.DEBUG, **options)

    def info(self, message: Any, **options: Any) -> bool:
        """Log at INFO."""
        return self.log(message, LoggingSeverity.INFO, **options)

    def warn(self, message: Any, **options: Any) -> bool:
        """Log at WARN."""
        return self.log(message, LoggingSeverity.WARN, **options)

    warning = warn

    def error(self, message: Any, **options: Any) -> bool:
        """Log at ERROR."""
        return self.log(message, LoggingSeverity.ERROR, **options)

    def fatal(self, message: Any, **options: Any) -> bool:
        """Log at FATAL."""
        return self.log(message, LoggingSeverity.FATAL, **options)


def get_logger(name: str) -> RcutilsLogger:
    """A logger by name (like ``rclpy.logging.get_logger``)."""
    if not name:
        raise ValueError("Logger name must not be empty.")
    return RcutilsLogger(name)


def _caller() -> FrameType:
    """The first frame outside this module: who logged."""
    frame = sys._getframe(1)
    while frame.f_back is not None and frame.f_code.co_filename == __file__:
        frame = frame.f_back
    return frame
