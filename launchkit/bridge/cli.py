"""``launchkit bridge``: join launchkit's graph and the DDS graph of ``ROS_DOMAIN_ID``."""

from __future__ import annotations

import argparse
import signal
import threading
from typing import Any

from launchkit.bridge.bridge import Bridge, BridgeOptions
from launchkit.bridge.plan import NameFilter
from launchkit.errors import UserError


class BridgeUsageError(UserError):
    """A bad ``launchkit bridge`` option."""


def build_parser() -> argparse.ArgumentParser:
    """The options of ``launchkit bridge`` (ROS arguments go after ``--ros-args``)."""
    parser = argparse.ArgumentParser(
        prog="launchkit bridge",
        description="Bridge launchkit's ROS graph (Zenoh) and a ROS 2 DDS graph (the real "
        "rclpy) on the current ROS_DOMAIN_ID: topics both ways as they appear, services both "
        "ways. Needs rclpy: pip install 'launchkit[ros2]' or a sourced ROS 2 Jazzy.",
    )
    parser.add_argument(
        "--topics",
        action="append",
        default=[],
        metavar="REGEX",
        help="bridge only topics and services whose whole name matches (repeatable)",
    )
    parser.add_argument(
        "--exclude",
        action="append",
        default=[],
        metavar="REGEX",
        help="never bridge topics and services whose whole name matches (repeatable)",
    )
    parser.add_argument("--no-services", action="store_true", help="bridge topics only")
    parser.add_argument(
        "--poll",
        type=float,
        default=0.1,
        metavar="SECONDS",
        help="how often to look at the DDS graph for new topics (default 0.1)",
    )
    parser.add_argument(
        "--router", metavar="tcp/HOST:PORT", help="launchkit's router (default $LAUNCHKIT_ROUTER)"
    )
    parser.add_argument("--debug", action="store_true", help=argparse.SUPPRESS)
    return parser


def main(argv: list[str], program: str = "launchkit-bridge") -> int:
    """Run the bridge until SIGINT or SIGTERM; 0 then."""
    own, ros_args = _split_ros_args(argv)
    args = build_parser().parse_args(own)
    if not args.poll > 0:
        raise BridgeUsageError(f"--poll {args.poll}", expected="a number of seconds > 0")
    options = BridgeOptions(
        names=NameFilter.parse(args.topics, args.exclude),
        services=not args.no_services,
        poll_period=args.poll,
        router=args.router,
        ros_argv=[program, *ros_args],
    )
    stop = threading.Event()

    def on_signal(signum: int, frame: Any) -> None:
        stop.set()

    previous = {s: signal.signal(s, on_signal) for s in (signal.SIGINT, signal.SIGTERM)}
    try:
        bridge = Bridge(options)
        try:
            bridge.run(stop)
        finally:
            bridge.close()
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
    return 0


def _split_ros_args(argv: list[str]) -> tuple[list[str], list[str]]:
    """(the bridge's own options, ``--ros-args ...`` up to a ``--``) as rcl splits them."""
    if "--ros-args" not in argv:
        return argv, []
    start = argv.index("--ros-args")
    end = argv.index("--", start) if "--" in argv[start:] else len(argv)
    return argv[:start] + argv[end + 1 :], argv[start:end]
