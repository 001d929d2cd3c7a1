"""The ``robot_state_publisher`` executable.

Parameters as ROS's: ``robot_description`` (URDF text, required), ``publish_frequency`` (Hz,
default 20: the most often ``/tf`` is sent; 0 sends on every joint state) and ``frame_prefix``.
Publishes ``/robot_description`` (std_msgs/String) and ``/tf_static`` (the fixed joints) once,
transient local, so late subscribers get them; publishes ``/tf`` for the moving joints named in
each ``/joint_states`` message.
"""

from __future__ import annotations

import sys
from typing import Any

import launchkit.ros as ros
from launchkit.errors import Location, UserError
from launchkit.ros.msgs.sensor_msgs.msg import JointState
from launchkit.ros.msgs.std_msgs.msg import String
from launchkit.ros.msgs.tf2_msgs.msg import TFMessage
from launchkit.stock import _entry
from launchkit.stock._tf import tf_message
from launchkit.stock.urdf import RobotModel, parse_urdf

LATCHED = ros.QoSProfile(
    depth=1,
    reliability=ros.ReliabilityPolicy.RELIABLE,
    durability=ros.DurabilityPolicy.TRANSIENT_LOCAL,
)


class RobotStatePublisher:
    """The node: the robot model, its latched publications and the ``/joint_states`` handler."""

    def __init__(self, node: ros.Node) -> None:
        self.node = node
        description = str(node.declare_parameter("robot_description", "").value)
        frequency = float(node.declare_parameter("publish_frequency", 20.0).value)
        self.frame_prefix = str(node.declare_parameter("frame_prefix", "").value)
        if not description.strip():
            raise UserError(
                "parameter robot_description is empty or not set",
                Location("robot_description"),
                expected="the robot's URDF text, e.g. robot_description:=\"$(command 'cat "
                "robot.urdf')\"",
            )
        if frequency < 0.0:
            raise UserError(
                f"parameter publish_frequency is {frequency}", expected="a rate >= 0 Hz"
            )
        self.model: RobotModel = parse_urdf(description, source="robot_description")
        self.min_interval_ns = int(1e9 / frequency) if frequency > 0.0 else 0
        self._last_ns: int | None = None
        for joint in self.model.joints:
            node.get_logger().debug(f"got segment {joint.child}")

        self.description = node.create_publisher(String, "robot_description", LATCHED)
        self.tf_static = node.create_publisher(TFMessage, "/tf_static", LATCHED)
        self.tf = node.create_publisher(TFMessage, "/tf", 100)
        self._publish_model(description)
        node.create_subscription(JointState, "joint_states", self.on_joint_states, 10)
        node.add_on_set_parameters_callback(self.on_set_parameters)

    def _publish_model(self, description: str) -> None:
        """Send the (new) description and the fixed transforms on their latched topics."""
        self.description.publish(String(data=description))
        now = self.node.get_clock().now().to_msg()
        self.tf_static.publish(tf_message(self.model.fixed_transforms(self.frame_prefix), now))
        self.node.get_logger().info(
            f"publishing robot {self.model.name!r}: {len(self.model.fixed_transforms())} fixed "
            f"and {len(self.model.moving_joints)} moving joints"
        )

    def on_set_parameters(self, params: list[Any]) -> Any:
        """Accept a new ``robot_description`` only when it is a valid URDF, then republish."""
        for param in params:
            if param.name != "robot_description":
                continue
            try:
                model = parse_urdf(str(param.value), source="robot_description")
            except UserError as exc:
                return ros.SetParametersResult(successful=False, reason=exc.format())
            self.model = model
            self._publish_model(str(param.value))
        return ros.SetParametersResult(successful=True)

    def on_joint_states(self, msg: Any) -> None:
        """Send ``/tf`` for the joints in ``msg``, at most ``publish_frequency`` times a second."""
        now = self.node.get_clock().now()
        if self._last_ns is not None and now.nanoseconds - self._last_ns < self.min_interval_ns:
            return
        positions = dict(zip(msg.name, (float(p) for p in msg.position), strict=False))
        transforms = self.model.moving_transforms(positions, self.frame_prefix)
        if not transforms:
            return
        stamp = msg.header.stamp
        if stamp.sec == 0 and stamp.nanosec == 0:
            stamp = now.to_msg()
        self.tf.publish(tf_message(transforms, stamp))
        self._last_ns = now.nanoseconds


def main(argv: list[str]) -> int:
    """Run the node until shutdown (Ctrl-C or SIGTERM)."""
    return _entry.spin(argv, "robot_state_publisher", RobotStatePublisher)


if __name__ == "__main__":
    sys.exit(_entry.run(main, "robot_state_publisher"))
