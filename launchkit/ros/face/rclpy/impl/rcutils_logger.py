"""``rclpy.impl.rcutils_logger``: the logger class."""

from launchkit.ros.logging import RcutilsLogger

__all__ = ["RcutilsLogger"]
