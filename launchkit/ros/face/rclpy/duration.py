"""``rclpy.duration``: spans of time."""

from launchkit.ros.ros_time import Duration, Infinite

__all__ = ["Duration", "Infinite"]
