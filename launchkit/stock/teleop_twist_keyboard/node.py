"""The ``teleop_twist_keyboard`` executable: turn keys into ``/cmd_vel`` messages.

Parameters as the original's: ``speed`` (0.5), ``turn`` (1.0), ``speed_limit`` and
``turn_limit`` (1000.0), ``stamped`` (False: geometry_msgs/Twist; True: TwistStamped) and
``frame_id`` (only with ``stamped``). A zero twist is published on exit.
"""

from __future__ import annotations

import sys
from typing import Any

import launchkit.ros as ros
from launchkit.errors import UserError
from launchkit.ros.msgs.geometry_msgs.msg import Twist, TwistStamped, Vector3
from launchkit.ros.msgs.std_msgs.msg import Header
from launchkit.stock import _entry
from launchkit.stock.teleop_twist_keyboard.keys import Teleop, Velocity
from launchkit.stock.teleop_twist_keyboard.terminal import KeyReader, stop_on_signals

#: How often the key loop wakes up to notice a shutdown (SIGTERM from a launcher).
POLL_SEC = 0.1


def main(argv: list[str]) -> int:
    """Run the node until Ctrl-C or a shutdown; the terminal is always restored."""
    reader = KeyReader(sys.stdin.fileno())  # fails before any ROS set-up when not a terminal
    with _entry.ros_node(argv, "teleop_twist_keyboard") as node:
        stop = stop_on_signals()  # the zero twist still goes out after a stop request
        stamped = bool(node.declare_parameter("stamped", False).value)
        frame_id = str(node.declare_parameter("frame_id", "").value)
        if frame_id and not stamped:
            raise UserError(
                f"parameter frame_id is {frame_id!r} but stamped is false",
                expected="frame_id only together with stamped:=true",
            )
        teleop = Teleop(
            speed=float(node.declare_parameter("speed", 0.5).value),
            turn=float(node.declare_parameter("turn", 1.0).value),
            speed_limit=float(node.declare_parameter("speed_limit", 1000.0).value),
            turn_limit=float(node.declare_parameter("turn_limit", 1000.0).value),
        )
        publish = _publisher(node, stamped, frame_id)
        with reader:
            _say(teleop.start_lines())
            try:
                while ros.ok() and not stop.is_set():
                    key = reader.read_key(POLL_SEC)
                    if key is None:
                        continue
                    outcome = teleop.press(key)
                    _say(outcome.lines)
                    publish(outcome.velocity)
                    if outcome.quit:
                        break
            finally:
                publish(Velocity())
    return 0


def _say(lines: list[str]) -> None:
    for line in lines:
        print(line, flush=True)


def _publisher(node: ros.Node, stamped: bool, frame_id: str) -> Any:
    """A function publishing a :class:`Velocity` as Twist or TwistStamped on ``cmd_vel``."""
    pub = node.create_publisher(TwistStamped if stamped else Twist, "cmd_vel", 10)

    def publish(velocity: Velocity) -> None:
        twist = Twist(
            linear=Vector3(x=velocity.x, y=velocity.y, z=velocity.z),
            angular=Vector3(z=velocity.yaw),
        )
        if not stamped:
            pub.publish(twist)
            return
        header = Header(stamp=node.get_clock().now().to_msg(), frame_id=frame_id)
        pub.publish(TwistStamped(header=header, twist=twist))

    return publish


if __name__ == "__main__":
    sys.exit(_entry.run(main, "teleop_twist_keyboard"))
