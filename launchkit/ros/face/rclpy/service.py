"""``rclpy.service``: service servers."""

from launchkit.ros.services import Service

__all__ = ["Service"]
