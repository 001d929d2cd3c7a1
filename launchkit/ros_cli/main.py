"""``launchkit topic|node|service|param|interface|router``: argument parsing and dispatch."""

from __future__ import annotations

import argparse
import signal
from types import FrameType

from launchkit._argparse import CommandParser
from launchkit.ros_cli import (
    interface_commands,
    node_commands,
    param_commands,
    router_commands,
    service_commands,
    topic_commands,
)

_FAMILIES = {
    "topic": topic_commands,
    "node": node_commands,
    "service": service_commands,
    "param": param_commands,
    "interface": interface_commands,
    "router": router_commands,
}


def build_parser() -> argparse.ArgumentParser:
    """The parser of every ROS command."""
    parser = CommandParser(prog="launchkit")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    for family in _FAMILIES.values():
        family.add_parser(commands)
    return parser


def _terminate(signum: int, frame: FrameType | None) -> None:
    raise KeyboardInterrupt


def main(command: str, argv: list[str]) -> int:
    """Run ``launchkit COMMAND ARGV...``; user mistakes raise ``UserError`` (exit 2).

    Long-running commands (echo, hz, pub, router) stop on Ctrl-C or SIGTERM with status 0.
    """
    args = build_parser().parse_args([command, *argv])
    previous = signal.signal(signal.SIGTERM, _terminate)
    try:
        return int(args.run(args))
    except KeyboardInterrupt:
        return 0
    finally:
        signal.signal(signal.SIGTERM, previous)
