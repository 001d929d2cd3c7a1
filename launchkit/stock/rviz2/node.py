"""The ``rviz2`` executable: ``rviz2 [-d CONFIG.rviz] [-f FRAME] [--port N] [--ros-args ...]``.

There is no 3D window of its own: the node serves a viewer page to the browser
(``http://127.0.0.1:8765/``: the robot model, TF, laser scans, odometry, camera images, the
topic list, driving keys and joint sliders, laid out as the ``-d`` config says) and the same
topics to Foxglove apps over the Foxglove WebSocket protocol, on one loopback port.

Parameters (defaults from the command line): ``port`` (8765, or ``$LAUNCHKIT_VIEWER_PORT``; 0
picks a free port), ``address`` (``127.0.0.1``: this machine only), ``allowed_origins``
(web pages of other origins allowed to connect; ``*`` for any), ``asset_folders`` (folders
whose mesh and texture files may be served besides the package share folders) and
``robot_description`` (a URDF given at start: the folders of its meshes are trusted too).
Under ``launchkit run`` the ``viewer: http://...`` line goes to the launcher's console whatever
the node's ``output``. A port that another launchkit viewer holds (turtlesim_node's, run beside
a launch with rviz2 as the tutorials do) makes rviz2 serve on a free port, and say so.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import launchkit.ros as ros
from launchkit.errors import UserError
from launchkit.runtime.supervisor_client import SupervisorClient, SupervisorError
from launchkit.stock import _entry
from launchkit.stock.rviz2.access import AccessPolicy
from launchkit.stock.rviz2.assets import AssetCatalog
from launchkit.stock.rviz2.cli import parse_args
from launchkit.stock.rviz2.config import RvizConfig, default_config, load_config
from launchkit.stock.rviz2.hub import Hub
from launchkit.stock.rviz2.ros_link import RosLink
from launchkit.stock.rviz2.server import PortInUse, ViewerServer
from launchkit.stock.rviz2.viewer_probe import is_viewer


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


def start_server(
    make_server: Callable[[int], ViewerServer], port: int, address: str
) -> tuple[ViewerServer, str]:
    """A started server on ``port`` and the line that announces it. When another launchkit
    viewer holds the port (turtlesim_node's, or another launch's rviz2), a free port instead,
    and the line says why; a port another program holds stays a :class:`PortInUse` error."""
    server = make_server(port)
    try:
        server.start()
    except PortInUse:
        if not (port and is_viewer(address, port)):
            raise
    else:
        return server, f"viewer: {server.url} (open it in a browser)"
    server = make_server(0)
    server.start()
    return server, (
        f"viewer: {server.url} (open it in a browser; port {port} already serves another "
        "launchkit viewer, without this rviz2's displays)"
    )


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
        folders = _param(
            node,
            "asset_folders",
            [str(folder) for folder in args.asset_folder],
            "a list of folders (strings)",
        )
        description = _param(node, "robot_description", "", "a URDF (a string)")
        if not 0 <= port <= 65535:
            raise UserError(f"parameter 'port' is {port}", expected="0 to 65535")
        policy = AccessPolicy(address, origins)
        catalog = AssetCatalog(folders=[Path(folder).expanduser() for folder in folders])
        if description:
            catalog.trust_description(description)
        hub = Hub(link, catalog)
        logger = node.get_logger()

        def make_server(on_port: int) -> ViewerServer:
            hello = {"config": config.to_page()}
            return ViewerServer(hub, policy, on_port, hello, lambda text: logger.warn(text))

        server, line = start_server(make_server, port, address)
        link.connect(hub, server)
        announce(line)
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
