"""``tf2_ros.transform_listener`` on launchkit."""

from launchkit.ros.tf2.transform_listener import TransformListener

__all__ = ["TransformListener"]
