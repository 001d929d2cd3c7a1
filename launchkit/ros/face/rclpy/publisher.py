"""``rclpy.publisher``: publishers."""

from launchkit.ros.topics import Publisher

__all__ = ["Publisher"]
