"""The ``joint_state_publisher`` executable.

Parameters as ROS's: ``robot_description`` (URDF text; when unset the node waits for the
latched ``/robot_description`` topic), ``rate`` (Hz, default 10), ``zeros.<joint>`` (a joint's
resting position), ``source_list`` (JointState topics whose values win for the joints they
name), ``publish_default_velocities`` and ``publish_default_efforts`` (False).
"""

from __future__ import annotations

import sys
from typing import Any

import launchkit.ros as ros
from launchkit.errors import UserError
from launchkit.ros.msgs.sensor_msgs.msg import JointState
from launchkit.ros.msgs.std_msgs.msg import Header, String
from launchkit.stock import _entry
from launchkit.stock.joint_state_publisher.state import JointStateMerger
from launchkit.stock.urdf import parse_urdf

LATCHED = ros.QoSProfile(
    depth=1,
    reliability=ros.ReliabilityPolicy.RELIABLE,
    durability=ros.DurabilityPolicy.TRANSIENT_LOCAL,
)


def _param(node: ros.Node, name: str, default: Any) -> Any:
    """A parameter's value: the override when one was given (already declared), else default."""
    if node.has_parameter(name):
        return node.get_parameter(name).value
    return node.declare_parameter(name, default).value


class JointStatePublisher:
    """The node: waits for a robot description, then publishes ``/joint_states`` at ``rate``."""

    def __init__(self, node: ros.Node) -> None:
        self.node = node
        self.rate = float(_param(node, "rate", 10.0))
        if self.rate <= 0.0:
            raise UserError(f"parameter rate is {self.rate}", expected="a rate > 0 Hz")
        self.zeros = {
            name: float(p.value) for name, p in node.get_parameters_by_prefix("zeros").items()
        }
        self.with_velocities = bool(_param(node, "publish_default_velocities", False))
        self.with_efforts = bool(_param(node, "publish_default_efforts", False))
        sources = (
            node.get_parameter("source_list").value if node.has_parameter("source_list") else []
        )
        self.merger: JointStateMerger | None = None
        self.publisher = node.create_publisher(JointState, "joint_states", 10)
        for topic in sources or []:
            node.create_subscription(JointState, str(topic), self.on_source, 10)
        description = str(_param(node, "robot_description", ""))
        if description.strip():
            self.set_description(description, "robot_description")
        else:
            node.get_logger().info("waiting for the robot description on /robot_description")
            node.create_subscription(
                String, "robot_description", lambda m: self.set_description(m.data), LATCHED
            )
        node.create_timer(1.0 / self.rate, self.publish)

    def set_description(self, text: str, source: str = "/robot_description") -> None:
        """(Re)build the joint list from URDF ``text``; a bad URDF is a user error."""
        model = parse_urdf(text, source=source)
        try:
            self.merger = JointStateMerger(model, self.zeros)
        except ValueError as exc:
            raise UserError(str(exc), expected="zeros.<joint> for moving joints only") from None
        names = ", ".join(j.name for j in model.free_joints) or "none"
        self.node.get_logger().info(f"publishing joint states of {model.name!r}: {names}")

    def on_source(self, msg: Any) -> None:
        """Merge a source_list message into the current state."""
        if self.merger is not None:
            self.merger.merge(list(msg.name), msg.position, msg.velocity, msg.effort)

    def publish(self) -> None:
        """Send the current state of every moving joint (nothing until the robot is known)."""
        if self.merger is None:
            return
        state = self.merger.current()
        self.publisher.publish(
            JointState(
                header=Header(stamp=self.node.get_clock().now().to_msg()),
                name=state.name,
                position=state.position,
                velocity=state.velocity if self.with_velocities else [],
                effort=state.effort if self.with_efforts else [],
            )
        )


def main(argv: list[str], name: str = "joint_state_publisher") -> int:
    """Run the node called ``name`` until shutdown (Ctrl-C or SIGTERM)."""
    return _entry.spin(
        argv, name, JointStatePublisher, automatically_declare_parameters_from_overrides=True
    )


if __name__ == "__main__":
    sys.exit(_entry.run(main, "joint_state_publisher"))
