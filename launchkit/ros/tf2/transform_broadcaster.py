"""tf2_ros' ``TransformBroadcaster``: sends transforms on ``/tf``."""

from __future__ import annotations

from typing import Any

from launchkit.ros.msgs import get_message
from launchkit.ros.qos import QoSProfile


def as_list(transform: Any) -> list[Any]:
    """One transform, or an iterable of them, as a list (what ``sendTransform`` accepts)."""
    if isinstance(transform, list):
        return transform
    if hasattr(transform, "__iter__"):
        return list(transform)
    return [transform]


class TransformBroadcaster:
    """Publishes TransformStamped messages on ``/tf`` (``qos``: a profile or a depth; default
    depth 100)."""

    def __init__(self, node: Any, qos: QoSProfile | int | None = None) -> None:
        self.pub_tf = node.create_publisher(
            get_message("tf2_msgs/msg/TFMessage"),
            "/tf",
            QoSProfile(depth=100) if qos is None else qos,
        )

    def sendTransform(self, transform: Any) -> None:
        """Send one transform or a list of them, in one TFMessage."""
        self.pub_tf.publish(get_message("tf2_msgs/msg/TFMessage")(transforms=as_list(transform)))
