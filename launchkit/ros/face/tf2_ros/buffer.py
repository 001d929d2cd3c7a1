"""``tf2_ros.buffer`` on launchkit."""

from launchkit.ros.tf2.buffer import Buffer

__all__ = ["Buffer"]
