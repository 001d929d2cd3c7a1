"""``diff_drive``: the diff drive plugin as its own node process.

Reads ``cmd_vel`` (or ``command_topic``), the simulator's joint states and ground truth for
entity ``entity``, runs :class:`DiffDriveController` on each joint state (stamped with sim time),
sends the wheel velocity targets back to the simulator and publishes ``odom`` and the
``odom -> base`` transform. The simulator server starts one per diff drive plugin; it also runs
alone: ``launchkit exec gazebo_ros diff_drive --ros-args -p entity:=NAME -p left_joint:=... ``.
"""

from __future__ import annotations

from typing import Any

import launchkit.ros as ros
from launchkit.errors import UserError
from launchkit.stock import _entry
from launchkit.stock.gazebo_ros import messages
from launchkit.stock.gazebo_ros.sim.diff_drive import (
    BaseState,
    DiffDriveConfigError,
    DiffDriveController,
    DiffDriveParams,
    is_finite_command,
)
from launchkit.stock.gazebo_ros.state_pairs import StatePairs, nanoseconds, subscribe_halves


class DiffDriveNode:
    """Wires a :class:`DiffDriveController` to the simulator's topics."""

    def __init__(self, node: ros.Node) -> None:
        self.node = node
        entity = str(node.declare_parameter("entity", "").value)
        if not entity:
            raise DiffDriveConfigError("diff drive: parameter 'entity' is required (a model name)")
        defaults = DiffDriveParams("", "")
        values: dict[str, object] = {}
        for name in DiffDriveParams.__dataclass_fields__:
            values[name] = node.declare_parameter(name, getattr(defaults, name)).value
        self.params = DiffDriveParams.from_parameters(values)
        self.controller: DiffDriveController | None = None
        self._pairs: StatePairs[BaseState] = StatePairs()
        p = self.params
        self.odom_pub = node.create_publisher(
            messages.message_class("nav_msgs", "Odometry"), p.odometry_topic, 1
        )
        self.tf_pub = node.create_publisher(
            messages.message_class("tf2_msgs", "TFMessage"), "/tf", 100
        )
        joint_state = messages.message_class("sensor_msgs", "JointState")
        self.command_pub = node.create_publisher(
            joint_state, messages.COMMAND_TOPIC.format(entity=entity), 10
        )
        node.create_subscription(
            messages.message_class("geometry_msgs", "Twist"), p.command_topic, self._cmd, 1
        )
        subscribe_halves(node, entity, self._truth, self._joints)
        node.get_logger().info(
            f"driving '{entity}': {p.left_joint}/{p.right_joint}, separation "
            f"{p.wheel_separation} m, diameter {p.wheel_diameter} m, {p.update_rate} Hz, "
            f"{p.odometry_frame} -> {p.robot_base_frame} on '{p.odometry_topic}'"
        )
        self._pending_command = (0.0, 0.0)
        #: In lockstep, commands by the simulated time they were sent (see _cmd).
        self.lockstep = node.context.lockstep is not None
        self._queued: list[tuple[int, tuple[float, float]]] = []
        if p.publish_wheel_tf:
            node.get_logger().warn("publish_wheel_tf is not supported; no wheel transforms")

    def _cmd(self, msg: Any, info: ros.MessageInfo) -> None:
        command = (float(msg.linear.x), float(msg.angular.z))
        if not is_finite_command(*command):
            self.node.get_logger().warn(
                f"ignoring a non-finite command on '{self.params.command_topic}' "
                f"(linear.x={command[0]}, angular.z={command[1]}); keeping the last one",
                throttle_duration_sec=5.0,
            )
            return
        if self.lockstep:
            # A command sent at the instant of a state may arrive before or after that
            # state: it applies from the first state after the instant it was sent, so
            # the order of the two never shows (repeatable runs).
            self._queued.append((info["source_timestamp"], command))
            return
        self._apply(command)

    def _apply(self, command: tuple[float, float]) -> None:
        self._pending_command = command
        if self.controller is not None:
            self.controller.set_command(*command)

    def _truth(self, msg: Any) -> None:
        pose, twist = msg.pose.pose, msg.twist.twist
        pair = self._pairs.add_truth(
            nanoseconds(msg),
            BaseState(
                (pose.position.x, pose.position.y, pose.position.z),
                (pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w),
                (twist.linear.x, twist.linear.y, twist.linear.z),
                (twist.angular.x, twist.angular.y, twist.angular.z),
            ),
        )
        if pair is not None:
            self._step(*pair)

    def _joints(self, msg: Any) -> None:
        pair = self._pairs.add_joints(nanoseconds(msg), msg)
        if pair is not None:
            self._step(*pair)

    def _step(self, msg: Any, base: BaseState) -> None:
        sent_before = nanoseconds(msg)
        while self._queued and self._queued[0][0] < sent_before:
            self._apply(self._queued.pop(0)[1])
        now = messages.seconds_of(msg.header.stamp)
        if self.controller is None or now < self.controller.start_time:
            # First state, or the world was reset: start over at this sim time.
            self.controller = DiffDriveController(self.params, start_time=now)
            self.controller.set_command(*self._pending_command)
        names = list(msg.name)
        velocities = list(msg.velocity)
        p = self.params
        try:
            wheels = (
                velocities[names.index(p.left_joint)],
                velocities[names.index(p.right_joint)],
            )
        except (ValueError, IndexError):
            self.node.get_logger().error(
                f"joint states lack '{p.left_joint}' or '{p.right_joint}' (have {names})"
            )
            return
        update = self.controller.update(now, wheels, base)
        if update is None:
            return
        command = update.command
        joints = list(command.velocities)
        self.command_pub.publish(
            messages.joint_state(
                now,
                joints,
                [0.0] * len(joints),
                [command.velocities[j] for j in joints],
                [command.max_torque] * len(joints),
            )
        )
        if p.publish_odom:
            self.odom_pub.publish(messages.odometry(update.odometry))
        if p.publish_odom_tf:
            self.tf_pub.publish(messages.transform(update.odometry))


def main(argv: list[str]) -> int:
    """Run the diff drive node until stopped; ``argv`` is the whole command line."""
    try:
        return _entry.spin(argv, "gazebo_ros_diff_drive", DiffDriveNode)
    except DiffDriveConfigError as exc:
        raise UserError(str(exc)) from None


if __name__ == "__main__":
    _entry.run(main, "diff_drive")
