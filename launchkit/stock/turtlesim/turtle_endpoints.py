"""One turtle's topics and services, named under the turtle (``turtle1/cmd_vel``, ...).

``cmd_vel`` (geometry_msgs/Twist) in; ``pose`` (turtlesim/Pose) and ``color_sensor``
(turtlesim/Color) out at every update; the services ``set_pen``, ``teleport_relative`` and
``teleport_absolute``. They live as long as the turtle: ``/kill`` and ``/reset`` destroy them.

The ``rotate_absolute`` action server (:mod:`.rotation`) is made beside the services, its
accepted goals handed to :meth:`Turtle.accept_goal
<launchkit.stock.turtlesim.world.Turtle.accept_goal>` (the update drives them).
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any

import launchkit.ros as ros
from launchkit.ros.msgs.geometry_msgs.msg import Twist
from launchkit.ros.msgs.turtlesim.msg import Color, Pose
from launchkit.ros.msgs.turtlesim.srv import SetPen, TeleportAbsolute, TeleportRelative
from launchkit.stock.turtlesim.qos import TOPIC_QOS
from launchkit.stock.turtlesim.rotation import rotate_absolute_server
from launchkit.stock.turtlesim.world import PoseReport, Teleport, Turtle

#: ``on_command(turtle, twist)``: what the simulator does with a velocity command.
OnCommand = Callable[[Turtle, Any], None]


class TurtleEndpoints:
    """The ROS side of one :class:`Turtle` of ``node``."""

    def __init__(self, node: ros.Node, turtle: Turtle, on_command: OnCommand) -> None:
        self.node = node
        self.turtle = turtle
        name = turtle.name
        self._destroyers: list[Callable[[], object]] = []
        subscription = node.create_subscription(
            Twist, f"{name}/cmd_vel", functools.partial(on_command, turtle), TOPIC_QOS
        )
        self._destroyers.append(functools.partial(node.destroy_subscription, subscription))
        self._pose = node.create_publisher(Pose, f"{name}/pose", TOPIC_QOS)
        self._color = node.create_publisher(Color, f"{name}/color_sensor", TOPIC_QOS)
        for publisher in (self._pose, self._color):
            self._destroyers.append(functools.partial(node.destroy_publisher, publisher))
        services = [
            node.create_service(SetPen, f"{name}/set_pen", self._set_pen),
            node.create_service(TeleportRelative, f"{name}/teleport_relative", self._relative),
            node.create_service(TeleportAbsolute, f"{name}/teleport_absolute", self._absolute),
        ]
        for service in services:
            self._destroyers.append(functools.partial(node.destroy_service, service))
        self._destroyers.append(rotate_absolute_server(node, turtle).destroy)

    def publish(self, pose: PoseReport, color: tuple[int, int, int]) -> None:
        """Publish the turtle's pose and the colour under it."""
        self._pose.publish(
            Pose(
                x=pose.x,
                y=pose.y,
                theta=pose.theta,
                linear_velocity=pose.linear_velocity,
                angular_velocity=pose.angular_velocity,
            )
        )
        r, g, b = color
        self._color.publish(Color(r=r, g=g, b=b))

    def destroy(self) -> None:
        """Remove the turtle's topics and services from the graph."""
        for destroy in self._destroyers:
            destroy()
        self._destroyers.clear()

    # -- services ----------------------------------------------------------------------------

    def _set_pen(self, request: Any, response: Any) -> Any:
        self.turtle.set_pen(
            int(request.r), int(request.g), int(request.b), int(request.width), bool(request.off)
        )
        return response

    def _relative(self, request: Any, response: Any) -> Any:
        self.turtle.teleport(
            Teleport(theta=float(request.angular), linear=float(request.linear), relative=True)
        )
        return response

    def _absolute(self, request: Any, response: Any) -> Any:
        self.turtle.teleport(
            Teleport(x=float(request.x), y=float(request.y), theta=float(request.theta))
        )
        return response
