"""``rclpy.logging``: loggers, severities, levels."""

from launchkit.ros.logging import (
    LoggingSeverity,
    clear_config,
    get_logger,
    get_logger_effective_level,
    get_logger_level,
    get_logging_directory,
    get_logging_severity_from_string,
    initialize,
    set_logger_level,
    shutdown,
)

__all__ = [
    "LoggingSeverity",
    "clear_config",
    "get_logger",
    "get_logger_effective_level",
    "get_logger_level",
    "get_logging_directory",
    "get_logging_severity_from_string",
    "initialize",
    "set_logger_level",
    "shutdown",
]
