"""``rclpy.context``: init and shutdown of one context."""

from launchkit.ros.context import Context

__all__ = ["Context"]
