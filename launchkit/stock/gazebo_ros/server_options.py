"""The simulator server's command line, as Gazebo's: ``[--verbose] [-s LIB]... [-g LIB]... [-u]
[--gui] [WORLD] [--ros-args ...]``."""

from __future__ import annotations

import argparse
from dataclasses import dataclass
from typing import Any

from launchkit.errors import UserError

INIT_PLUGIN = "libgazebo_ros_init.so"
FACTORY_PLUGIN = "libgazebo_ros_factory.so"


class UsageError(UserError):
    """A bad command line or world (exit status 2)."""


@dataclass(frozen=True)
class ServerOptions:
    """The Gazebo-style part of the command line."""

    world: str = "empty"
    verbose: bool = False
    server_plugins: tuple[str, ...] = ()
    gui: bool = False
    paused: bool = False

    @property
    def ros_init(self) -> bool:
        """Whether ``/clock`` is published (``-s libgazebo_ros_init.so``, or no ``-s`` at all)."""
        return not self.server_plugins or INIT_PLUGIN in self.server_plugins

    @property
    def factory(self) -> bool:
        """Whether the spawn/delete services exist."""
        return not self.server_plugins or FACTORY_PLUGIN in self.server_plugins


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> Any:
        raise UsageError(message)


def parse_server_args(argv: list[str]) -> ServerOptions:
    """Parse Gazebo's options (everything before ``--ros-args``); :class:`UsageError` if bad."""
    if "--ros-args" in argv:
        argv = argv[: argv.index("--ros-args")]
    parser = _Parser(prog="gazebo", add_help=False)
    parser.add_argument("world", nargs="?", default="")
    parser.add_argument("--verbose", action="store_true")
    parser.add_argument("-s", "--server-plugin", action="append", default=[])
    parser.add_argument("-g", "--gui-plugin", action="append", default=[])
    parser.add_argument("-u", "--pause", action="store_true")
    parser.add_argument("--gui", action="store_true")
    args = parser.parse_args(argv)
    return ServerOptions(
        world=args.world or "empty",
        verbose=args.verbose,
        server_plugins=tuple(p.strip() for p in args.server_plugin),
        gui=args.gui,
        paused=args.pause,
    )
