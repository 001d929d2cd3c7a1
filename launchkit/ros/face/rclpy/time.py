"""``rclpy.time``: points in time."""

from launchkit.ros.ros_time import Time

__all__ = ["Time"]
