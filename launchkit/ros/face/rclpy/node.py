"""``rclpy.node``: the node."""

from launchkit.ros.node import Node
from launchkit.ros.params import Parameter

__all__ = ["Node", "Parameter"]
