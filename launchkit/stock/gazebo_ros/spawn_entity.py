"""``spawn_entity.py``: spawn a robot into the running simulator, as gazebo_ros's script does.

``-entity NAME`` and one source: ``-file PATH``, ``-topic TOPIC`` (a ``std_msgs/String`` such as
``robot_description``, read from its latched publisher) or ``-stdin``; the pose
``-x -y -z -R -P -Y``;
``-timeout`` (seconds to wait for the topic, 30) and ``-spawn_service_timeout`` (seconds to wait
for ``/spawn_entity``, 30; gazebo_ros says 5, too short for a loaded 2-core machine starting
every node at once). Exit status 0 when the entity is spawned; 2 with one error line
otherwise.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path
from typing import Any

import launchkit.ros as ros
from launchkit.errors import UserError
from launchkit.ros.lockstep.participant import holding
from launchkit.ros.services import ServiceCallError
from launchkit.rotations import rpy_to_quaternion
from launchkit.stock import _entry
from launchkit.stock.gazebo_ros import messages


class SpawnError(UserError):
    """Spawning failed; the message says what and what was expected."""


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> Any:
        raise SpawnError(
            f"{message} (expected: -entity NAME (-file PATH | -topic TOPIC | -stdin) "
            "[-x X -y Y -z Z -R R -P P -Y Y] [-timeout S] [-spawn_service_timeout S])"
        )


def parse_args(argv: list[str]) -> argparse.Namespace:
    """Parse the command line (the part before ``--ros-args``)."""
    if "--ros-args" in argv:
        argv = argv[: argv.index("--ros-args")]
    parser = _Parser(prog="spawn_entity.py", add_help=False)
    parser.add_argument("-entity", required=True, metavar="NAME")
    source = parser.add_mutually_exclusive_group(required=True)
    source.add_argument("-file", metavar="PATH")
    source.add_argument("-topic", metavar="TOPIC")
    source.add_argument("-stdin", action="store_true")
    for axis in ("x", "y", "z", "R", "P", "Y"):
        parser.add_argument(f"-{axis}", type=float, default=0.0)
    parser.add_argument("-reference_frame", default="")
    parser.add_argument("-robot_namespace", default="")
    parser.add_argument("-timeout", type=float, default=30.0)
    parser.add_argument("-spawn_service_timeout", type=float, default=30.0)
    parser.add_argument("-unpause", action="store_true")
    return parser.parse_args(argv)


def _read_topic(node: Any, topic: str, timeout: float) -> str:
    string = messages.message_class("std_msgs", "String")
    received: list[str] = []
    qos = ros.QoSProfile(depth=1, durability=ros.DurabilityPolicy.TRANSIENT_LOCAL)
    node.create_subscription(string, topic, lambda msg: received.append(str(msg.data)), qos)
    deadline = time.monotonic() + timeout
    while not received and time.monotonic() < deadline:
        ros.spin_once(node, timeout_sec=min(0.1, max(0.0, deadline - time.monotonic())))
    if not received:
        raise SpawnError(
            f"no message on topic '{topic}' within {timeout:g} s "
            "(expected a std_msgs/String publisher, e.g. robot_state_publisher)"
        )
    return received[0]


def _call(client: Any, request: Any, deadline: float) -> Any:
    while True:
        try:
            return client.call(request, timeout_sec=60.0)
        except ServiceCallError as exc:
            # "No response" means no server took the request: the server's liveliness token can
            # reach us before its queryable does. Anything else is final.
            if "no response" not in str(exc) or time.monotonic() > deadline:
                raise SpawnError(f"calling /spawn_entity failed: {exc}") from None
        time.sleep(0.1)


def spawn(node: ros.Node, args: argparse.Namespace) -> str:
    """Do the spawn from ``node``; the service's status message on success,
    :class:`SpawnError` otherwise."""
    if args.file is not None:
        try:
            xml = Path(args.file).read_text()
        except OSError as exc:
            raise SpawnError(f"cannot read -file {args.file}: {exc.strerror}") from None
    elif args.stdin:
        xml = sys.stdin.read()
    else:
        xml = _read_topic(node, args.topic, args.timeout)
    srv = messages.service_class("gazebo_msgs", "SpawnEntity")
    pose, point, quaternion = (
        messages.message_class("geometry_msgs", name) for name in ("Pose", "Point", "Quaternion")
    )
    client = node.create_client(srv, "/spawn_entity")
    node.get_logger().info("Waiting for service /spawn_entity")
    if not client.wait_for_service(timeout_sec=args.spawn_service_timeout):
        if not ros.ok():
            raise KeyboardInterrupt  # stopped while it waited (Ctrl-C, SIGTERM): a clean end
        raise SpawnError(
            f"service /spawn_entity not available within {args.spawn_service_timeout:g} s "
            "(expected a running gzserver with libgazebo_ros_factory.so)"
        )
    qx, qy, qz, qw = rpy_to_quaternion(args.R, args.P, args.Y)
    request = srv.Request(
        name=args.entity,
        xml=xml,
        robot_namespace=args.robot_namespace,
        initial_pose=pose(
            position=point(x=args.x, y=args.y, z=args.z),
            orientation=quaternion(x=qx, y=qy, z=qz, w=qw),
        ),
        reference_frame=args.reference_frame,
    )
    node.get_logger().info("Calling service /spawn_entity")
    response = _call(client, request, time.monotonic() + args.spawn_service_timeout)
    if not response.success:
        raise SpawnError(str(response.status_message))
    return str(response.status_message)


def main(argv: list[str]) -> int:
    """Spawn the entity; ``argv`` is the whole command line."""
    args = parse_args(argv[1:])
    with _entry.ros_node(argv, "spawn_entity") as node:
        # in a lockstep launch the entity is spawned at the simulated time the spawner started
        with holding(node.context):
            message = spawn(node, args)
    print(f"[spawn_entity] {message}", flush=True)
    return 0


if __name__ == "__main__":
    _entry.run(main, "spawn_entity.py")
