"""The ``mimic`` executable: one turtle copies another's motion.

As Jazzy's: node ``turtle_mimic`` turns each ``input/pose`` (turtlesim/Pose) into a twist on
``output/cmd_vel`` with the pose's linear and angular velocity. Remap ``input`` and ``output``
to two turtles: ``launchkit exec turtlesim mimic --ros-args -r input/pose:=/turtlesim1/turtle1/
pose -r output/cmd_vel:=/turtlesim2/turtle1/cmd_vel``.
"""

from __future__ import annotations

from typing import Any

import launchkit.ros as ros
from launchkit.ros.msgs.geometry_msgs.msg import Twist, Vector3
from launchkit.ros.msgs.turtlesim.msg import Pose
from launchkit.stock import _entry
from launchkit.stock.turtlesim.qos import TOPIC_QOS


def setup(node: ros.Node) -> None:
    """Copy every pose's velocities to a twist."""
    publisher = node.create_publisher(Twist, "output/cmd_vel", TOPIC_QOS)

    def on_pose(pose: Any) -> None:
        twist = Twist(
            linear=Vector3(x=float(pose.linear_velocity)),
            angular=Vector3(z=float(pose.angular_velocity)),
        )
        publisher.publish(twist)

    node.create_subscription(Pose, "input/pose", on_pose, TOPIC_QOS)


def main(argv: list[str]) -> int:
    """Mimic until Ctrl-C or SIGTERM."""
    return _entry.spin(argv, "turtle_mimic", setup)


if __name__ == "__main__":
    _entry.run(main, "mimic")
