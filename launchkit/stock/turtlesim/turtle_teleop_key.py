"""The ``turtle_teleop_key`` executable: arrow keys in a terminal to ``turtle1/cmd_vel``.

As Jazzy's: node ``teleop_turtle``, parameters ``scale_linear`` and ``scale_angular`` (2.0 each,
read at every key, so ``param set`` changes them while it runs), one twist a key press, the same
instructions printed at start, ``q`` to quit (Ctrl-C too). The keys ``G|B|V|C|D|E|R|T`` send
turtle1's ``rotate_absolute`` action a goal for a heading and ``F`` cancels the last goal the
action server answered, as Jazzy's does.
"""

from __future__ import annotations

import sys
import threading
from typing import Any

import launchkit.ros as ros
from launchkit.ros.action import ActionClient, ClientGoalHandle
from launchkit.ros.msgs.geometry_msgs.msg import Twist, Vector3
from launchkit.ros.msgs.turtlesim.action import RotateAbsolute
from launchkit.stock import _entry
from launchkit.stock.teleop_twist_keyboard.terminal import KeyReader, stop_on_signals
from launchkit.stock.turtlesim.qos import TOPIC_QOS
from launchkit.stock.turtlesim.teleop_keys import INSTRUCTIONS, action_for

#: How often the key loop wakes up to notice a stop request.
POLL_SEC = 0.1


def main(argv: list[str]) -> int:
    """Read keys until ``q``, Ctrl-C or a stop request; the terminal is always restored."""
    reader = KeyReader(sys.stdin.fileno(), "turtle_teleop_key", "turtlesim")
    with _entry.ros_node(argv, "teleop_turtle") as node:
        stop = stop_on_signals()
        node.declare_parameter("scale_angular", 2.0)
        node.declare_parameter("scale_linear", 2.0)
        publisher = node.create_publisher(Twist, "turtle1/cmd_vel", TOPIC_QOS)
        rotation = Rotations(node)
        # the parameter services answer while the key loop waits, as Jazzy's spin thread does
        executor = ros.SingleThreadedExecutor()
        executor.add_node(node)
        spinner = threading.Thread(target=_spin, args=(executor, stop), daemon=True)
        spinner.start()
        for line in INSTRUCTIONS:
            print(line, flush=True)
        try:
            with reader:
                _key_loop(node, reader, publisher, rotation, stop)
        finally:
            stop.set()
            spinner.join(5 * POLL_SEC)
    return 0


class Rotations:
    """turtle1's ``rotate_absolute`` as the keys use it: a goal a key, cancel the last one."""

    def __init__(self, node: ros.Node) -> None:
        self._node = node
        self._client = ActionClient(node, RotateAbsolute, "turtle1/rotate_absolute")
        self._goal_handle: ClientGoalHandle | None = None

    def send(self, theta: float) -> None:
        """Ask for heading ``theta``; the goal handle is kept when the server answers."""
        sent = self._client.send_goal_async(RotateAbsolute.Goal(theta=theta))
        sent.add_done_callback(self._answered)

    def _answered(self, sent: Any) -> None:
        self._node.get_logger().debug("Goal response received")
        self._goal_handle = sent.result()

    def cancel(self) -> None:
        """Cancel the last goal answered (nothing if none was)."""
        if self._goal_handle is not None:
            self._node.get_logger().debug("Sending cancel request")
            self._goal_handle.cancel_goal_async()


def _key_loop(
    node: ros.Node,
    reader: KeyReader,
    publisher: Any,
    rotation: Rotations,
    stop: threading.Event,
) -> None:
    while ros.ok() and not stop.is_set():
        key = reader.read_key(POLL_SEC)
        if key is None:
            continue
        action = action_for(key)
        if action.quit:
            return
        if action.heading is not None:
            rotation.send(action.heading)
        if action.cancel:
            rotation.cancel()
        if action.moves:
            linear = float(node.get_parameter("scale_linear").value) * action.linear
            angular = float(node.get_parameter("scale_angular").value) * action.angular
            publisher.publish(Twist(linear=Vector3(x=linear), angular=Vector3(z=angular)))


def _spin(executor: ros.SingleThreadedExecutor, stop: threading.Event) -> None:
    while ros.ok() and not stop.is_set():
        executor.spin_once(timeout_sec=POLL_SEC)


if __name__ == "__main__":
    _entry.run(main, "turtle_teleop_key")
