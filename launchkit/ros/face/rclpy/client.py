"""``rclpy.client``: service clients."""

from launchkit.ros.services import Client

__all__ = ["Client"]
