"""The browser viewer turtlesim_node serves itself, in place of Jazzy's window.

``launchkit exec turtlesim turtlesim_node`` prints ``viewer: http://127.0.0.1:8765/ (open it in
a browser)``, as a robot launch prints the rviz2 stand-in's. It is the rviz2 stand-in's own
server (:mod:`launchkit.stock.rviz2`), run in this process for a hidden node of its own beside
turtlesim's (``/_turtlesim_viewer``: left out of ``node list`` as ROS 2 leaves hidden nodes
out, and made without the process's ``--ros-args``, which are turtlesim's). Its page shows the
turtlesim panel as soon as the picture's topics (:mod:`.scene`) appear, and every other topic
of the graph as the viewer always does.

A viewer already listening on the port (a second turtlesim, or a robot launch's rviz2) shows
every turtlesim of the graph, so the node then only says where it is. The port is
``$LAUNCHKIT_VIEWER_PORT`` or 8765 (``--viewer-port N``, 0: a free one); ``--no-viewer`` serves
none.
"""

from __future__ import annotations

from dataclasses import dataclass

import launchkit.ros as ros
from launchkit.errors import UserError
from launchkit.stock.rviz2.access import AccessPolicy
from launchkit.stock.rviz2.config import default_config
from launchkit.stock.rviz2.hub import Hub
from launchkit.stock.rviz2.node import announce
from launchkit.stock.rviz2.ros_link import RosLink
from launchkit.stock.rviz2.server import ViewerServer
from launchkit.stock.rviz2.viewer_probe import is_viewer

ADDRESS = "127.0.0.1"


@dataclass
class EmbeddedViewer:
    """A running viewer server and the hidden node that feeds it."""

    node: ros.Node
    server: ViewerServer
    link: RosLink

    def close(self) -> None:
        """Stop serving and remove the hidden node."""
        self.link.close()
        self.server.close()
        self.node.destroy_node()


def start(port: int, owner: ros.Node) -> EmbeddedViewer | None:
    """Serve the viewer on ``port`` and announce its address; None when a viewer already
    serves there (announced too) or the port cannot be used (``owner`` warns why)."""
    node = ros.Node(
        f"_{owner.get_name()}_viewer",
        namespace=owner.get_namespace(),
        context=owner.context,
        use_global_arguments=False,
        start_parameter_services=False,
        enable_rosout=False,
    )
    link = RosLink(node)
    hub = Hub(link)
    logger = node.get_logger()
    policy = AccessPolicy(ADDRESS, [])
    hello = {"config": default_config().to_page()}
    server = ViewerServer(hub, policy, port, hello, logger.warn, name="launchkit turtlesim")
    try:
        server.start()
    except UserError as error:
        node.destroy_node()
        url = f"http://{ADDRESS}:{port}/"
        if port and is_viewer(ADDRESS, port):
            announce(f"viewer: {url} (the viewer already running there shows this turtlesim)")
        else:
            owner.get_logger().warn(f"not serving a viewer: {error.message}")
        return None
    link.connect(hub, server)
    announce(f"viewer: {server.url} (open it in a browser)")
    return EmbeddedViewer(node, server, link)
