"""The ``turtlesim_node`` executable: ``turtlesim_node [--no-viewer] [--viewer-port N]
[--ros-args ...]``.

ROS 2 Jazzy's turtlesim (:mod:`.simulator`), drawn in the browser instead of a window: unless
``--no-viewer`` is given, the node serves the viewer page itself and prints its address
(:mod:`.viewer`), or names the viewer already running on the port.
"""

from __future__ import annotations

import argparse
from typing import NoReturn

import launchkit.ros as ros
from launchkit.errors import UserError
from launchkit.ros.arguments import remove_ros_args
from launchkit.stock import _entry
from launchkit.stock.rviz2.cli import default_port
from launchkit.stock.turtlesim import viewer
from launchkit.stock.turtlesim.simulator import TurtleSim


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:
        raise UserError(message, expected=self.format_usage().strip())


def parse_args(argv: list[str]) -> argparse.Namespace:
    """The node's own options (the ``--ros-args`` sections are the ROS layer's)."""
    parser = _Parser(prog="turtlesim_node", description="ROS 2 Jazzy's turtlesim")
    parser.add_argument(
        "--no-viewer",
        dest="viewer",
        action="store_false",
        help="serve no viewer page (the turtles are simulated all the same)",
    )
    parser.add_argument(
        "--viewer-port",
        type=int,
        default=None,
        help="the viewer's port (default $LAUNCHKIT_VIEWER_PORT or 8765; 0 picks a free one)",
    )
    args = parser.parse_args(remove_ros_args(argv))
    if args.viewer_port is not None and not 0 <= args.viewer_port <= 65535:
        raise UserError(f"--viewer-port is {args.viewer_port}", expected="0 to 65535")
    return args


def main(argv: list[str]) -> int:
    """Simulate (and serve the viewer) until Ctrl-C or SIGTERM."""
    args = parse_args(argv[1:])
    port = default_port() if args.viewer and args.viewer_port is None else args.viewer_port
    with _entry.ros_node(argv, "turtlesim") as node:
        TurtleSim(node)
        executor = ros.SingleThreadedExecutor()
        executor.add_node(node)
        served = viewer.start(port, node) if args.viewer else None
        if served is not None:
            executor.add_node(served.node)
        try:
            executor.spin()
        finally:
            if served is not None:
                served.close()
    return 0


if __name__ == "__main__":
    _entry.run(main, "turtlesim_node")
