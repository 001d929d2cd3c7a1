"""``rclpy.subscription``: subscriptions."""

from launchkit.ros.topics import MessageInfo, Subscription

__all__ = ["MessageInfo", "Subscription"]
