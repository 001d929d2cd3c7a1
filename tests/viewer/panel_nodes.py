"""The small ROS system the rqt panel tests look at, one node per process (``panel_nodes.py ROLE``).

- ``talker`` publishes ``std_msgs/String`` on ``/chatter``; ``listener`` subscribes to it.
- ``driver`` (run in the namespace ``/robot1``) publishes ``geometry_msgs/Twist`` on
  ``/robot1/cmd`` ten times a second: ``linear.x`` counts 0, 1, ... 19 and again, ``angular.z``
  is its negative; ``follower`` (also in ``/robot1``) subscribes, and a ``std_msgs/String``
  published on ``/robot1/say`` makes it log ``heard: TEXT`` on ``/rosout``.
- ``logger`` publishes ``rcl_interfaces/msg/Log`` lines on ``/rosout`` itself (a node of
  today's launchkit.ros does not yet), one of each severity per cycle, four lines a second:
  ``tick N at SEVERITY``.
- ``tuner`` has parameters with descriptors (``speed``, ``label``, ``enabled``, ``count``,
  ``frozen``) and the service ``/tuner/shout`` (``std_srvs/SetBool``), answering
  ``shouting: on`` or ``shouting: off``.
- ``fibonacci`` has the services and topics of an action server named ``/fibonacci`` (the
  five ``/fibonacci/_action/...`` names; launchkit.ros has no action types yet, so they carry
  stand-in types) and ``fib_client`` those of its client.
"""

from __future__ import annotations

import os
import sys
import time
from typing import Any

import launchkit.ros as ros
from launchkit.ros.msgs import get_message, get_service

String = get_message("std_msgs/msg/String")
Twist = get_message("geometry_msgs/msg/Twist")
Log = get_message("rcl_interfaces/msg/Log")
Descriptor = get_message("rcl_interfaces/msg/ParameterDescriptor")
FloatRange = get_message("rcl_interfaces/msg/FloatingPointRange")
IntegerRange = get_message("rcl_interfaces/msg/IntegerRange")
GoalStatusArray = get_message("action_msgs/msg/GoalStatusArray")
SetBool = get_service("std_srvs/srv/SetBool")
Trigger = get_service("std_srvs/srv/Trigger")

LEVELS = [(10, "DEBUG"), (20, "INFO"), (30, "WARN"), (40, "ERROR"), (50, "FATAL")]
ROSOUT_QOS = ros.QoSProfile(
    depth=1000,
    reliability=ros.ReliabilityPolicy.RELIABLE,
    durability=ros.DurabilityPolicy.TRANSIENT_LOCAL,
)


def talker(node: ros.Node) -> None:
    publisher = node.create_publisher(String, "/chatter", 10)
    node.create_timer(0.2, lambda: publisher.publish(String(data="hello")))


def listener(node: ros.Node) -> None:
    node.create_subscription(String, "/chatter", lambda msg: None, 10)


def driver(node: ros.Node) -> None:
    publisher = node.create_publisher(Twist, "cmd", 10)
    count = [0]

    def tick() -> None:
        message = Twist()
        message.linear.x = float(count[0] % 20)
        message.angular.z = -message.linear.x
        publisher.publish(message)
        count[0] += 1

    node.create_timer(0.1, tick)


def rosout_line(node: ros.Node, level: int, text: str) -> Any:
    """A Log message from ``node`` as rcl fills it in."""
    stamp = node.get_clock().now().to_msg()
    return Log(
        stamp=stamp,
        level=level,
        name=node.get_name(),
        msg=text,
        file=os.path.basename(__file__),
        function="tick",
        line=1,
    )


def follower(node: ros.Node) -> None:
    rosout = node.create_publisher(Log, "/rosout", ROSOUT_QOS)
    node.create_subscription(Twist, "cmd", lambda msg: None, 10)
    node.create_subscription(
        String,
        "say",
        lambda msg: rosout.publish(rosout_line(node, 20, f"heard: {msg.data}")),
        10,
    )


def logger(node: ros.Node) -> None:
    rosout = node.create_publisher(Log, "/rosout", ROSOUT_QOS)
    count = [0]

    def tick() -> None:
        level, name = LEVELS[count[0] % len(LEVELS)]
        rosout.publish(rosout_line(node, level, f"tick {count[0]} at {name}"))
        count[0] += 1

    node.create_timer(0.25, tick)


def tuner(node: ros.Node) -> None:
    node.declare_parameter(
        "speed",
        2.5,
        Descriptor(
            description="how fast the turtle goes (m/s)",
            floating_point_range=[FloatRange(from_value=0.0, to_value=10.0, step=0.5)],
        ),
    )
    node.declare_parameter("label", "turtle", Descriptor(description="what to call it"))
    node.declare_parameter("enabled", True)
    node.declare_parameter(
        "count",
        3,
        Descriptor(integer_range=[IntegerRange(from_value=0, to_value=100, step=1)]),
    )
    node.declare_parameter("frozen", "fixed", Descriptor(read_only=True))

    def shout(request: Any, response: Any) -> Any:
        response.success = True
        response.message = f"shouting: {'on' if request.data else 'off'}"
        return response

    node.create_service(SetBool, "~/shout", shout)


def fibonacci(node: ros.Node) -> None:
    for part in ("send_goal", "cancel_goal", "get_result"):
        node.create_service(Trigger, f"/fibonacci/_action/{part}", lambda req, res: res)
    for part in ("feedback", "status"):
        node.create_publisher(GoalStatusArray, f"/fibonacci/_action/{part}", 10)


def fib_client(node: ros.Node) -> None:
    for part in ("send_goal", "cancel_goal", "get_result"):
        node.create_client(Trigger, f"/fibonacci/_action/{part}")
    for part in ("feedback", "status"):
        node.create_subscription(GoalStatusArray, f"/fibonacci/_action/{part}", print, 10)


ROLES = {
    "talker": talker,
    "listener": listener,
    "driver": driver,
    "follower": follower,
    "logger": logger,
    "tuner": tuner,
    "fibonacci": fibonacci,
    "fib_client": fib_client,
}


def main(argv: list[str]) -> int:
    """Run the node of ``argv[1]`` (its name) until interrupted."""
    role = argv[1]
    ros.init(argv)
    node = ros.Node(role)
    ROLES[role](node)
    print(f"{role} ready at {time.monotonic():.3f}", flush=True)
    try:
        ros.spin(node)
    finally:
        node.destroy_node()
        ros.shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
