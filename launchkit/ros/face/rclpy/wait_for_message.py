"""``rclpy.wait_for_message``: the next message of a topic."""

from launchkit.ros.wait_for_message import wait_for_message

__all__ = ["wait_for_message"]
