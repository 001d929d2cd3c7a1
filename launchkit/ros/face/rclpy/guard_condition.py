"""``rclpy.guard_condition``: callbacks run when triggered."""

from launchkit.ros.guard_condition import GuardCondition

__all__ = ["GuardCondition"]
