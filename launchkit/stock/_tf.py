"""Turning :class:`launchkit.stock.urdf.Transform` values into tf2_msgs/TFMessage messages."""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from launchkit.ros.msgs.geometry_msgs.msg import Quaternion, TransformStamped, Vector3
from launchkit.ros.msgs.geometry_msgs.msg import Transform as TransformMsg
from launchkit.ros.msgs.std_msgs.msg import Header
from launchkit.ros.msgs.tf2_msgs.msg import TFMessage
from launchkit.stock.urdf import Transform


def tf_message(transforms: Iterable[Transform], stamp: Any) -> Any:
    """A TFMessage holding ``transforms``, every one stamped ``stamp`` (a Time message)."""
    stamped = []
    for t in transforms:
        x, y, z = t.translation
        qx, qy, qz, qw = t.rotation
        stamped.append(
            TransformStamped(
                header=Header(stamp=stamp, frame_id=t.parent),
                child_frame_id=t.child,
                transform=TransformMsg(
                    translation=Vector3(x=x, y=y, z=z),
                    rotation=Quaternion(x=qx, y=qy, z=qz, w=qw),
                ),
            )
        )
    return TFMessage(transforms=stamped)
