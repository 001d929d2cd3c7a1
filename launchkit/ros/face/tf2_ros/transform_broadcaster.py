"""``tf2_ros.transform_broadcaster`` on launchkit."""

from launchkit.ros.tf2.transform_broadcaster import TransformBroadcaster

__all__ = ["TransformBroadcaster"]
