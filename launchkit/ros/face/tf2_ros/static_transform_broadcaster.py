"""``tf2_ros.static_transform_broadcaster`` on launchkit."""

from launchkit.ros.tf2.static_transform_broadcaster import StaticTransformBroadcaster

__all__ = ["StaticTransformBroadcaster"]
