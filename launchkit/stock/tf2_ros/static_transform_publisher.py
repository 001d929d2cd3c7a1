"""The ``static_transform_publisher`` executable: latch one transform on ``/tf_static``.

``ros2 run tf2_ros static_transform_publisher --x 1 --frame-id a --child-frame-id b`` (see
:mod:`static_transform_args` for every form). As tf2_ros' node it is called
``static_transform_publisher_`` and 16 random letters and digits (unless ``-r __node:=`` names
it), keeps the transform in read-only parameters (``translation.x`` ... ``rotation.w``,
``frame_id``, ``child_frame_id``), stamps it with the node's clock and spins until stopped.
"""

from __future__ import annotations

import random
import string
import sys
from typing import Any

import launchkit.ros as ros
from launchkit.errors import UserError
from launchkit.ros.arguments import remove_ros_args
from launchkit.ros.logging import RcutilsLogger
from launchkit.ros.msgs import get_message
from launchkit.ros.tf2 import StaticTransformBroadcaster
from launchkit.stock import _entry
from launchkit.stock.tf2_ros.static_transform_args import USAGE, StaticTransform, parse

_NAME_LETTERS = string.digits + string.ascii_lowercase + string.ascii_uppercase


def node_name() -> str:
    """tf2_ros' name for the node: unique enough that several publishers never clash."""
    return "static_transform_publisher_" + "".join(random.choices(_NAME_LETTERS, k=16))


def _transform_message(node: ros.Node, given: StaticTransform) -> Any:
    """The transform as the node's read-only parameters have it (they may be overridden)."""
    descriptor = get_message("rcl_interfaces/msg/ParameterDescriptor")(read_only=True)

    def declared(name: str, value: object) -> Any:
        return node.declare_parameter(name, value, descriptor).value

    message = get_message("geometry_msgs/msg/TransformStamped")()
    message.header.stamp = node.get_clock().now().to_msg()
    t, r = message.transform.translation, message.transform.rotation
    x, y, z = given.translation
    t.x, t.y, t.z = (
        declared("translation.x", x),
        declared("translation.y", y),
        declared("translation.z", z),
    )
    qx, qy, qz, qw = given.rotation
    r.x, r.y = declared("rotation.x", qx), declared("rotation.y", qy)
    r.z, r.w = declared("rotation.z", qz), declared("rotation.w", qw)
    message.header.frame_id = declared("frame_id", given.parent)
    message.child_frame_id = declared("child_frame_id", given.child)
    if message.header.frame_id == message.child_frame_id:
        raise UserError(
            f"cannot publish static transform from '{message.header.frame_id}' to "
            f"'{message.child_frame_id}'",
            expected="a child frame other than the parent frame",
        )
    return message


def main(argv: list[str]) -> int:
    """Publish the transform of the command line until Ctrl-C."""
    arguments = parse(remove_ros_args(argv)[1:], RcutilsLogger("").warn)
    if arguments.help or arguments.transform is None:
        print(USAGE, flush=True)
        return 0
    with _entry.ros_node(argv, node_name()) as node:
        given = arguments.transform
        StaticTransformBroadcaster(node).sendTransform(_transform_message(node, given))
        # as tf2_ros, what the command line said (parameter overrides are not shown)
        x, y, z = given.translation
        qx, qy, qz, qw = given.rotation
        node.get_logger().info(
            "Spinning until stopped - publishing transform\n"
            f"translation: ('{x:f}', '{y:f}', '{z:f}')\n"
            f"rotation: ('{qx:f}', '{qy:f}', '{qz:f}', '{qw:f}')\n"
            f"from '{given.parent}' to '{given.child}'"
        )
        ros.spin(node)
    return 0


if __name__ == "__main__":
    sys.exit(_entry.run(main, "static_transform_publisher"))
