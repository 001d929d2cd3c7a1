"""The launcher's node host (:mod:`launchkit.runtime.node_host`): a process that imports the
ROS layer and the stock nodes' modules once, opens no session and starts no thread, and forks
each node a trampoline asks for (:class:`launchkit.runtime.fork_host.ForkHost`).

    python -m launchkit.stock._node_host FD LAUNCHER_PID MODULE...

FD is the listening socket the launcher made; the host dies with the launcher.
"""

from __future__ import annotations

import importlib
import os
import signal
import socket
import sys

from launchkit.runtime.fork_host import ForkHost

#: The services every node serves (:class:`launchkit.ros.parameter_service.ParameterService`).
PARAMETER_SERVICES = tuple(
    f"rcl_interfaces/srv/{name}"
    for name in (
        "ListParameters",
        "GetParameters",
        "GetParameterTypes",
        "SetParameters",
        "SetParametersAtomically",
        "DescribeParameters",
    )
)
#: The types the first wave of stock nodes (the server, spawn_entity.py, robot_state_publisher)
#: build before the robot moves, built once here instead of in each of them.
FIRST_WAVE_SERVICES = ("gazebo_msgs/srv/SpawnEntity", "gazebo_msgs/srv/DeleteEntity")
FIRST_WAVE_MESSAGES = (
    "rosgraph_msgs/msg/Clock",
    "sensor_msgs/msg/JointState",
    "nav_msgs/msg/Odometry",
    "sensor_msgs/msg/LaserScan",
    "std_msgs/msg/String",
    "tf2_msgs/msg/TFMessage",
)
_PR_SET_PDEATHSIG = 1
#: Environment variables that change what the interpreter imports: a node whose own differ
#: from the host's starts cold.
INTERPRETER_SETTINGS = ("PYTHON", "LD_")


def preload() -> None:
    """Import and build what every stock node needs: the node API (with numpy, rosbags'
    type store and zenoh, no session) and the parameter services' types."""
    from launchkit.ros.msgs import get_service

    importlib.import_module("launchkit.ros.node")
    for service in PARAMETER_SERVICES:
        get_service(service)


def _die_with_parent(launcher: int) -> None:
    import ctypes  # only here: a stock node does not need it

    libc = ctypes.CDLL(None, use_errno=True)
    libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    if os.getppid() != launcher:
        os._exit(1)  # the launcher died before the line above


def _warm(modules: list[str]) -> None:
    from launchkit.ros.msgs import codec, get_message, get_service

    preload()
    for module in modules:
        importlib.import_module(module)
    if modules:
        for service in FIRST_WAVE_SERVICES:
            get_service(service)
        for message in FIRST_WAVE_MESSAGES:
            codec(get_message(message)._TYPE_NAME)
    threads = len(os.listdir("/proc/self/task"))
    if threads != 1:
        print(
            f"node host: {threads} threads after its imports, forking it is not safe: "
            "the stock nodes start on their own",
            file=sys.stderr,
            flush=True,
        )
        raise SystemExit(1)


def main(argv: list[str]) -> int:
    """Serve the launcher whose pid and listening socket ``argv`` names."""
    fd, launcher, modules = int(argv[1]), int(argv[2]), argv[3:]
    _die_with_parent(launcher)
    listener = socket.socket(fileno=fd)
    return ForkHost(listener, None, lambda: _warm(modules), INTERPRETER_SETTINGS).serve()


if __name__ == "__main__":
    sys.exit(main(sys.argv))
