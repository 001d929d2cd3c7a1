"""``launchkit topic|node|service|param|interface|router|tf``: argument parsing and dispatch."""

from __future__ import annotations

import argparse
import importlib
import signal
from types import FrameType

from launchkit._argparse import CommandParser

# each family's module, imported only when its command runs (interface and param load the
# message types, router the router's code: a `topic list` needs none of them)
_FAMILIES = {
    "topic": "launchkit.ros_cli.topic_commands",
    "node": "launchkit.ros_cli.node_commands",
    "service": "launchkit.ros_cli.service_commands",
    "param": "launchkit.ros_cli.param_commands",
    "interface": "launchkit.ros_cli.interface_commands",
    "router": "launchkit.ros_cli.router_commands",
    "tf": "launchkit.ros_cli.tf_commands",
}


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The parser of ``command``'s family (of every ROS command when None)."""
    parser = CommandParser(prog="launchkit")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    for name, module in _FAMILIES.items():
        if command is None or command == name:
            importlib.import_module(module).add_parser(commands)
    return parser


def _terminate(signum: int, frame: FrameType | None) -> None:
    raise KeyboardInterrupt


def main(command: str, argv: list[str]) -> int:
    """Run ``launchkit COMMAND ARGV...``; user mistakes raise ``UserError`` (exit 2).

    Long-running commands (echo, hz, pub, router) stop on Ctrl-C or SIGTERM with status 0.
    """
    args = build_parser(command if command in _FAMILIES else None).parse_args([command, *argv])
    previous = signal.signal(signal.SIGTERM, _terminate)
    try:
        return int(args.run(args))
    except KeyboardInterrupt:
        return 0
    finally:
        signal.signal(signal.SIGTERM, previous)
