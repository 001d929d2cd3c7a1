"""``rclpy.impl.logging_severity``: the severities."""

from launchkit.ros.logging import LoggingSeverity

__all__ = ["LoggingSeverity"]
