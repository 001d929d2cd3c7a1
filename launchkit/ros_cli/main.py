"""``launchkit topic|node|service|param|interface|pkg|doctor|router|tf``: the ROS 2
command-line verbs (``ros2 <verb> ...`` as ``launchkit <verb> ...``), their argument parsing and
dispatch.

Each family is one module with an ``add_parser(commands)`` that registers its verbs, each verb's
``run(args) -> int`` set as the parser default; a new family (``action``) is one more line in
:data:`FAMILIES` and one in ``launchkit.cli.ROS_COMMANDS``.
"""

from __future__ import annotations

import argparse
import importlib
import signal
from types import FrameType

from launchkit._argparse import CommandParser

#: each family's module, imported only when its command runs (interface and param load the
#: message types, router the router's code: a `topic list` needs none of them)
FAMILIES = {
    "topic": "launchkit.ros_cli.topic_commands",
    "node": "launchkit.ros_cli.node_commands",
    "service": "launchkit.ros_cli.service_commands",
    "param": "launchkit.ros_cli.param_commands",
    "interface": "launchkit.ros_cli.interface_commands",
    "pkg": "launchkit.ros_cli.pkg_commands",
    "doctor": "launchkit.ros_cli.doctor_commands",
    "wtf": "launchkit.ros_cli.doctor_commands",
    "router": "launchkit.ros_cli.router_commands",
    "tf": "launchkit.ros_cli.tf_commands",
    "action": "launchkit.ros_cli.action_commands",
}


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The parser of ``command``'s family (of every ROS command when None)."""
    parser = CommandParser(prog="launchkit")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    modules = FAMILIES.values() if command is None else [FAMILIES[command]]
    for module in dict.fromkeys(modules):
        importlib.import_module(module).add_parser(commands)
    return parser


def _terminate(signum: int, frame: FrameType | None) -> None:
    raise KeyboardInterrupt


def main(command: str, argv: list[str]) -> int:
    """Run ``launchkit COMMAND ARGV...``; user mistakes raise ``UserError`` (exit 2).

    Long-running commands (echo, hz, pub, router) stop on Ctrl-C or SIGTERM with status 0.
    """
    args = build_parser(command if command in FAMILIES else None).parse_args([command, *argv])
    previous = signal.signal(signal.SIGTERM, _terminate)
    try:
        return int(args.run(args))
    except KeyboardInterrupt:
        return 0
    finally:
        signal.signal(signal.SIGTERM, previous)
