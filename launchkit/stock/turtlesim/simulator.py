"""The turtlesim node's behaviour (Jazzy's ``TurtleFrame``): parameters, ``/spawn``, ``/kill``,
``/clear``, ``/reset``, the 16 ms update of every turtle, and the picture for the viewer.

What it says, and when, is Jazzy's: ``Starting turtlesim with node name /turtlesim``, then
``Spawning turtle [turtle1] at x=[5.544445], y=[5.544445], theta=[0.000000]``; ``Clearing
turtlesim.`` and ``Resetting turtlesim.``; an error for a spawn under a taken name or a kill of
an unknown turtle (the reply is then empty, as Jazzy's is).
"""

from __future__ import annotations

import random
import time
from typing import Any

import launchkit.ros as ros
from launchkit.ros.msgs.rcl_interfaces.msg import (
    IntegerRange,
    ParameterDescriptor,
    ParameterEvent,
)
from launchkit.ros.msgs.std_msgs.msg import String
from launchkit.ros.msgs.std_srvs.srv import Empty
from launchkit.ros.msgs.turtlesim.srv import Kill, Spawn
from launchkit.stock.turtlesim import scene
from launchkit.stock.turtlesim.canvas import PathImage
from launchkit.stock.turtlesim.turtle_endpoints import TurtleEndpoints
from launchkit.stock.turtlesim.world import (
    DEFAULT_BACKGROUND,
    HEIGHT_M,
    TURTLE_IMAGES,
    UPDATE_PERIOD_S,
    WIDTH_M,
    Turtle,
    World,
    f32,
)

#: The background parameters' channels: name suffix, word in the description, default.
BACKGROUND = (
    ("r", "Red", DEFAULT_BACKGROUND[0]),
    ("g", "Green", DEFAULT_BACKGROUND[1]),
    ("b", "Blue", DEFAULT_BACKGROUND[2]),
)
#: The picture's topics: the last message kept for pages that open later.
LATCHED = ros.QoSProfile(depth=1, durability=ros.DurabilityPolicy.TRANSIENT_LOCAL)
PARAMETER_EVENTS_QOS = ros.QoSProfile(depth=100, reliability=ros.ReliabilityPolicy.BEST_EFFORT)


def _declare_parameters(node: ros.Node) -> None:
    for channel, name, default in BACKGROUND:
        descriptor = ParameterDescriptor(
            description=f"{name} channel of the background color",
            integer_range=[IntegerRange(from_value=0, to_value=255, step=1)],
        )
        node.declare_parameter(f"background_{channel}", default, descriptor)
    holonomic = ParameterDescriptor(description="If true, then turtles will be holonomic")
    node.declare_parameter("holonomic", False, holonomic)


class TurtleSim:
    """Jazzy's turtlesim on ``node``: made, it has turtle1 and updates every 16 ms."""

    def __init__(self, node: ros.Node, rng: random.Random | None = None) -> None:
        self.node = node
        self.log = node.get_logger()
        rng = rng or random.Random()
        self.world = World(lambda: rng.randrange(TURTLE_IMAGES))
        self.endpoints: dict[str, TurtleEndpoints] = {}
        self.feed = scene.SceneFeed(PathImage())
        self._started = False

        _declare_parameters(node)
        node.create_service(Empty, "clear", self._clear)
        node.create_service(Empty, "reset", self._reset)
        node.create_service(Spawn, "spawn", self._spawn)
        node.create_service(Kill, "kill", self._kill)
        node.create_subscription(
            ParameterEvent, "/parameter_events", self._parameter_event, PARAMETER_EVENTS_QOS
        )
        scene_topic, trails_topic = scene.topics(node.get_fully_qualified_name())
        self._scene = node.create_publisher(String, scene_topic, LATCHED)
        self._trails = node.create_publisher(String, trails_topic, LATCHED)
        self.log.info(f"Starting turtlesim with node name {node.get_fully_qualified_name()}")
        self.spawn("", WIDTH_M / 2.0, HEIGHT_M / 2.0, 0.0)
        node.create_timer(UPDATE_PERIOD_S, self.update)

    # -- turtles ----------------------------------------------------------------------------

    def spawn(self, name: str, x: float, y: float, theta: float) -> str:
        """A new turtle with its topics and services; its name ("" when ``name`` is taken)."""
        turtle = self.world.spawn(name, x, y, theta, self._now_ns())
        if turtle is None:
            self.log.error(f"A turtle named [{name}] already exists")
            return ""
        try:
            self.endpoints[turtle.name] = TurtleEndpoints(self.node, turtle, self._command)
        except Exception as error:  # a name that makes no valid topic name ("1a", "a b")
            self.world.kill(turtle.name)
            self.log.error(f"Cannot spawn a turtle named [{turtle.name}]: {error}")
            return ""
        self.log.info(
            f"Spawning turtle [{turtle.name}] at x=[{f32(x):f}], y=[{f32(y):f}], "
            f"theta=[{f32(theta):f}]"
        )
        return turtle.name

    def _forget(self, turtle: Turtle) -> None:
        endpoints = self.endpoints.pop(turtle.name, None)
        if endpoints is not None:
            endpoints.destroy()

    def _command(self, turtle: Turtle, twist: Any) -> None:
        holonomic = bool(self.node.get_parameter("holonomic").value)
        linear_y = float(twist.linear.y) if holonomic else None
        aborted = turtle.command(
            float(twist.linear.x), float(twist.angular.z), self._now_ns(), linear_y
        )
        if aborted:
            self.log.warn("Velocity command received during rotation goal. Aborting goal")

    # -- services ----------------------------------------------------------------------------

    def _spawn(self, request: Any, response: Any) -> Any:
        response.name = self.spawn(
            str(request.name), float(request.x), float(request.y), float(request.theta)
        )
        return response

    def _kill(self, request: Any, response: Any) -> Any:
        turtle = self.world.kill(str(request.name))
        if turtle is None:
            self.log.error(f"Tried to kill turtle [{request.name}], which does not exist")
        else:
            self._forget(turtle)
        return response

    def _clear(self, request: Any, response: Any) -> Any:
        self.log.info("Clearing turtlesim.")
        self.feed.clear()
        return response

    def _reset(self, request: Any, response: Any) -> Any:
        self.log.info("Resetting turtlesim.")
        for turtle in self.world.reset():
            self._forget(turtle)
        self.spawn("", WIDTH_M / 2.0, HEIGHT_M / 2.0, 0.0)
        self.feed.clear()
        return response

    def _parameter_event(self, event: Any) -> None:
        # Jazzy repaints when its own parameters change, reading the background as it paints.
        # (The update reads them too, for a ROS layer that publishes no parameter events.)
        if event.node == self.node.get_fully_qualified_name():
            self.publish_picture()

    # -- the update --------------------------------------------------------------------------

    def update(self) -> None:
        """Move every turtle one step (the first tick only starts the clock, as Jazzy's does),
        publish their poses and colours, and the picture when it changed."""
        if not self._started:
            self._started = True
            return
        now_ns = self._now_ns()
        for name in sorted(self.world.turtles):
            turtle = self.world.turtles[name]
            step = turtle.update(UPDATE_PERIOD_S, now_ns, self.feed.stroke, self._log)
            color = self.feed.path.color_at(*turtle.pixel())
            self.endpoints[name].publish(step.pose, color)
            if step.stroke is not None:
                self.feed.stroke(step.stroke)
        self.publish_picture()

    def publish_picture(self) -> None:
        """Publish the trails snapshot when one is due, and the scene when it changed."""
        snapshot = self.feed.snapshot(time.monotonic())
        if snapshot is not None:
            self._trails.publish(String(data=snapshot))
        text = self.feed.scene(self.background(), self.world.turtles.values())
        if text is not None:
            self._scene.publish(String(data=text))

    def background(self) -> tuple[int, int, int]:
        """The background colour the parameters say now."""
        r, g, b = (int(self.node.get_parameter(f"background_{c}").value) for c, _, _ in BACKGROUND)
        return (_channel(r), _channel(g), _channel(b))

    def _log(self, level: str, text: str) -> None:
        if level == "warn":
            self.log.warn(text)
        else:
            self.log.info(text)

    def _now_ns(self) -> int:
        return int(self.node.get_clock().now().nanoseconds)


def _channel(value: int) -> int:
    return min(max(value, 0), 255)
