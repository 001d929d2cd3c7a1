"""``rclpy.action.client``: the action client and its goal handles."""

from launchkit.ros.action.client import ActionClient, ClientGoalHandle

__all__ = ["ActionClient", "ClientGoalHandle"]
