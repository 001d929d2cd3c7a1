"""``rclpy.clock_type``: the kinds of clock."""

from launchkit.ros.ros_time import ClockType

__all__ = ["ClockType"]
