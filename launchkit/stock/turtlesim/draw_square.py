"""The ``draw_square`` executable: turtle1 resets, then drives a square of 2 m sides.

As Jazzy's: node ``draw_square`` calls ``reset``, then every 16 ms commands ``turtle1/cmd_vel``
from ``turtle1/pose``: forward at 1 m/s until 2 m from where the side began (within 0.1 m),
stop, turn at 0.4 rad/s until a quarter turn further (within 0.01 rad), stop, and again, logging
``New goal [x y, theta]`` and ``Reached goal`` as it goes. The arithmetic is in 32-bit floats,
as the original's.
"""

from __future__ import annotations

import enum
import math
from typing import Any

import launchkit.ros as ros
from launchkit.ros.msgs.geometry_msgs.msg import Twist, Vector3
from launchkit.ros.msgs.std_srvs.srv import Empty
from launchkit.ros.msgs.turtlesim.msg import Pose
from launchkit.stock import _entry
from launchkit.stock.turtlesim.qos import TOPIC_QOS
from launchkit.stock.turtlesim.world import f32

PI = f32(3.141592)
PERIOD_S = 0.016


class State(enum.Enum):
    """Where the square is."""

    FORWARD = 1
    STOP_FORWARD = 2
    TURN = 3
    STOP_TURN = 4


class DrawSquare:
    """The square's state machine on ``node``."""

    def __init__(self, node: ros.Node) -> None:
        self.node = node
        self.log = node.get_logger()
        self.publisher = node.create_publisher(Twist, "turtle1/cmd_vel", TOPIC_QOS)
        node.create_subscription(Pose, "turtle1/pose", self._on_pose, TOPIC_QOS)
        self.reset = node.create_client(Empty, "reset")
        self.reset_sent: Any = None
        self.pose: Any = None
        self.goal = (0.0, 0.0, 0.0)
        self.state: State | None = None
        node.create_timer(PERIOD_S, self._tick)

    def _on_pose(self, pose: Any) -> None:
        # poses count once the reset is done: earlier ones are of the turtle before it
        if self.reset_sent is not None and self.reset_sent.done():
            self.pose = pose

    def _tick(self) -> None:
        if self.reset_sent is None:
            if self.reset.service_is_ready():
                self.reset_sent = self.reset.call_async(Empty.Request())
            return
        if self.pose is None:
            return
        if self.state is None:
            self.state = State.FORWARD
            self._side_goal()
        if self.state is State.FORWARD:
            self._drive(State.STOP_FORWARD, 1.0, 0.0)
        elif self.state is State.TURN:
            self._drive(State.STOP_TURN, 0.0, 0.4)
        elif self._stopped():
            self.log.info("Reached goal")
            if self.state is State.STOP_FORWARD:
                self.state = State.TURN
                self._turn_goal()
            else:
                self.state = State.FORWARD
                self._side_goal()
        else:
            self._command(0.0, 0.0)

    def _drive(self, then: State, linear: float, angular: float) -> None:
        if self._reached():
            self.state = then
            self._command(0.0, 0.0)
        else:
            self._command(linear, angular)

    def _side_goal(self) -> None:
        x, y, theta = self.pose.x, self.pose.y, self.pose.theta
        self._set_goal(math.cos(theta) * 2 + x, math.sin(theta) * 2 + y, theta)

    def _turn_goal(self) -> None:
        theta = f32(math.fmod(f32(self.pose.theta + PI / 2.0), f32(2.0 * PI)))
        if theta >= PI:  # into [-pi, pi)
            theta = f32(theta - 2.0 * PI)
        self._set_goal(self.pose.x, self.pose.y, theta)

    def _set_goal(self, x: float, y: float, theta: float) -> None:
        self.goal = (f32(x), f32(y), f32(theta))
        self.log.info(f"New goal [{self.goal[0]:f} {self.goal[1]:f}, {self.goal[2]:f}]")

    def _reached(self) -> bool:
        x, y, theta = self.goal
        return (
            abs(f32(self.pose.x - x)) < 0.1
            and abs(f32(self.pose.y - y)) < 0.1
            and abs(f32(self.pose.theta - theta)) < 0.01
        )

    def _stopped(self) -> bool:
        return bool(self.pose.angular_velocity < 0.0001 and self.pose.linear_velocity < 0.0001)

    def _command(self, linear: float, angular: float) -> None:
        self.publisher.publish(Twist(linear=Vector3(x=linear), angular=Vector3(z=angular)))


def main(argv: list[str]) -> int:
    """Draw squares until Ctrl-C or SIGTERM."""
    return _entry.spin(argv, "draw_square", DrawSquare)


if __name__ == "__main__":
    _entry.run(main, "draw_square")
