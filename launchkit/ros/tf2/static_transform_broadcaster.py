"""tf2_ros' ``StaticTransformBroadcaster``: latches transforms on ``/tf_static``.

Each send republishes everything this broadcaster has sent, one transform per child frame, so
the one latched message a late listener gets holds them all. As in tf2_ros for Python (Jazzy),
a child frame keeps the first transform sent for it: a later one with the same child is ignored.
"""

from __future__ import annotations

from typing import Any

from launchkit.ros.msgs import get_message
from launchkit.ros.qos import DurabilityPolicy, HistoryPolicy, QoSProfile
from launchkit.ros.tf2.transform_broadcaster import as_list

#: tf2_ros' QoS for /tf_static publishers: latched, the last message only
STATIC_BROADCASTER_QOS = QoSProfile(
    depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL, history=HistoryPolicy.KEEP_LAST
)


class StaticTransformBroadcaster:
    """Publishes the transforms sent so far, latched, on ``/tf_static``."""

    def __init__(self, node: Any, qos: QoSProfile | int | None = None) -> None:
        message = get_message("tf2_msgs/msg/TFMessage")
        self.pub_tf = node.create_publisher(
            message, "/tf_static", STATIC_BROADCASTER_QOS if qos is None else qos
        )
        self.net_message = message()
        self._child_frame_ids: set[str] = set()

    def sendTransform(self, transform: Any) -> None:
        """Add one transform or a list of them (new child frames only) and publish all."""
        for added in as_list(transform):
            if added.child_frame_id not in self._child_frame_ids:
                self._child_frame_ids.add(added.child_frame_id)
                self.net_message.transforms.append(added)
        self.pub_tf.publish(self.net_message)
