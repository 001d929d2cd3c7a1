"""``rclpy.parameter_client``: another node's parameters."""

from launchkit.ros.parameter_client import AsyncParameterClient

__all__ = ["AsyncParameterClient"]
