"""The ``rviz2`` executable: ``rviz2 [-d CONFIG.rviz] [-f FRAME] [--port N] [--ros-args ...]``.

There is no 3D window of its own: the node serves a viewer page to the browser
(``http://127.0.0.1:8765/``: the robot model, TF, laser scans, odometry, camera images, the
topic list, driving keys and joint sliders, laid out as the ``-d`` config says) and the same
topics to Foxglove apps over the Foxglove WebSocket protocol, on one loopback port.

Parameters (defaults from the command line): ``port`` (8765, or ``$LAUNCHKIT_VIEWER_PORT``; 0
picks a free port), ``address`` (``127.0.0.1``: this machine only) and ``allowed_origins``
(web pages of other origins allowed to connect; ``*`` for any). Under ``launchkit run`` the
``viewer: http://...`` line goes to the launcher's console whatever the node's ``output``.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

import launchkit.ros as ros
from launchkit.errors import UserError
from launchkit.runtime.supervisor_client import SupervisorClient, SupervisorError
from launchkit.stock import _entry
from launchkit.stock.rviz2.access import AccessPolicy
from launchkit.stock.rviz2.cli import parse_args
from launchkit.stock.rviz2.config import RvizConfig, default_config, load_config
from launchkit.stock.rviz2.hub import Hub
from launchkit.stock.rviz2.ros_link import RosLink
from launchkit.stock.rviz2.server import ViewerServer


def _param(node: ros.Node, name: str, default: Any, expected: str) -> Any:
    """A parameter's value (declared with ``default``), checked to have ``default``'s type."""
    try:
        value = (
            node.get_parameter(name).value
            if node.has_parameter(name)
            else node.declare_parameter(name, default).value
        )
    except ros.InvalidParameterTypeException as error:
        raise UserError(str(error), expected=expected) from None
    if isinstance(default, list):
        ok = isinstance(value, (list, tuple)) and all(isinstance(v, str) for v in value)
    else:
        ok = type(value) is type(default)
    if not ok:
        raise UserError(f"parameter {name!r} is {value!r}", expected=expected)
    return list(value) if isinstance(default, list) else value


def connect_lines(server: ViewerServer, config: RvizConfig) -> list[str]:
    """What the node prints (its own output) so a user can connect Foxglove too."""
    lines = [
        f"Foxglove WebSocket on {server.ws_url} (every ROS topic, ros2msg schemas, CDR; "
        "subprotocols foxglove.websocket.v1 and foxglove.sdk.v1)",
        f"  Foxglove desktop or Lichtblick: Open connection -> Foxglove WebSocket -> "
        f"{server.ws_url}",
        "  web apps of other sites (app.foxglove.dev) need their origin in allowed_origins",
        f"  fixed frame: {config.fixed_frame}",
    ]
    if config.topics:
        lines.append("  displays: " + ", ".join(config.topics))
    return lines


def announce(line: str) -> None:
    """Print ``line`` on the launcher's console when run by ``launchkit run`` (whatever this
    node's ``output``), else on stdout."""
    try:
        client = SupervisorClient.from_environment()
    except OSError:
        client = None
    if client is not None:
        try:
            with client:
                client.announce(line)
            return
        except SupervisorError:
            pass  # an older launcher without announcements: print it ourselves
    print(line, flush=True)


def main(argv: list[str]) -> int:
    """Serve until shutdown (Ctrl-C or SIGTERM)."""
    args = parse_args(argv[1:])
    config = load_config(args.display_config) if args.display_config else default_config()
    if args.fixed_frame:
        config = RvizConfig(args.fixed_frame, config.displays, config.frame_rate, config.background)
    with _entry.ros_node(argv, "rviz2") as node:
        serve(node, args, config)
    return 0


def serve(node: ros.Node, args: argparse.Namespace, config: RvizConfig) -> None:
    """Serve the viewer for ``node`` until shutdown (Ctrl-C or SIGTERM)."""
    if args.ignored:
        ignored = " ".join(args.ignored)
        node.get_logger().info(f"ignoring {ignored}: no meaning for launchkit's browser viewer")
    server: ViewerServer | None = None
    link = RosLink(node)
    try:
        port = _param(node, "port", args.port, "a port number, 0 to 65535")
        address = _param(node, "address", args.address, "an IP address such as 127.0.0.1")
        origins = _param(
            node, "allowed_origins", list(args.allow_origin), "a list of origins (strings)"
        )
        if not 0 <= port <= 65535:
            raise UserError(f"parameter 'port' is {port}", expected="0 to 65535")
        policy = AccessPolicy(address, origins)
        hub = Hub(link)
        logger = node.get_logger()
        server = ViewerServer(
            hub, policy, port, {"config": config.to_page()}, lambda text: logger.warn(text)
        )
        server.start()
        link.connect(hub, server)
        announce(f"viewer: {server.url} (open it in a browser)")
        for line in connect_lines(server, config):  # after the announcement: tests rely on it
            print(line, flush=True)
        if not policy.loopback_only:
            node.get_logger().warn(
                f"serving on {address}: other machines can see and drive the robot"
            )
        ros.spin(node)
    finally:
        link.close()
        if server is not None:
            server.close()


if __name__ == "__main__":
    sys.exit(_entry.run(main, "rviz2"))
