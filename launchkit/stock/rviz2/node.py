"""The ``rviz2`` executable: ``rviz2 [-d CONFIG.rviz] [-f FRAME] [--port N] [--ros-args ...]``.

There is no 3D window: the node serves every topic of the ROS graph over a Foxglove WebSocket
on 127.0.0.1 (port 8765 unless ``--port``) and prints how to open it in the Foxglove app. The
config's fixed frame and display topics are printed so the same view can be set up there.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from typing import Any

import launchkit.ros as ros
from launchkit.stock import _entry
from launchkit.stock.rviz2.cli import parse_args
from launchkit.stock.rviz2.config import RvizConfig, load_config
from launchkit.stock.rviz2.relay import FoxgloveRelay

#: How often the graph is looked at for topics that appeared.
DISCOVERY_PERIOD_SEC = 0.5


@dataclass(frozen=True)
class Endpoint:
    """A topic as its publishers offer it."""

    topic: str
    type_name: str
    latched: bool
    best_effort: bool


def publisher_endpoints(node: ros.Node) -> list[Endpoint]:
    """Every topic with a publisher in the graph, with the QoS a subscriber must match."""
    found: dict[str, Endpoint] = {}
    for token in node.context.graph.tokens("MP"):
        qos = token.qos
        latched = qos is not None and qos.durability == ros.DurabilityPolicy.TRANSIENT_LOCAL
        best_effort = qos is not None and qos.reliability == ros.ReliabilityPolicy.BEST_EFFORT
        seen = found.get(token.topic)
        if seen is not None:
            latched = latched or seen.latched
            best_effort = best_effort or seen.best_effort
        found[token.topic] = Endpoint(token.topic, token.type_name, latched, best_effort)
    return sorted(found.values(), key=lambda e: e.topic)


class Rviz2:
    """The node: follows the graph and relays each topic's CDR bytes to Foxglove clients."""

    def __init__(self, node: ros.Node, relay: FoxgloveRelay) -> None:
        self.node = node
        self.relay = relay
        self.relayed: set[str] = set()
        self.discover()
        node.create_timer(DISCOVERY_PERIOD_SEC, self.discover)

    def discover(self) -> None:
        """Subscribe to the topics that appeared since the last look."""
        from launchkit.ros.msgs import get_message, message_definition

        for endpoint in publisher_endpoints(self.node):
            if endpoint.topic in self.relayed:
                continue
            try:
                msg_type = get_message(endpoint.type_name)
                definition = message_definition(endpoint.type_name)
            except Exception as exc:  # a type this installation does not know: skip it, once
                self.node.get_logger().warn(
                    f"not relaying {endpoint.topic}: unknown type {endpoint.type_name} ({exc})"
                )
                self.relayed.add(endpoint.topic)
                continue
            self.relay.add_topic(endpoint.topic, endpoint.type_name, definition, endpoint.latched)
            qos = ros.QoSProfile(
                depth=10,
                reliability=ros.ReliabilityPolicy.BEST_EFFORT
                if endpoint.best_effort
                else ros.ReliabilityPolicy.RELIABLE,
                durability=ros.DurabilityPolicy.TRANSIENT_LOCAL
                if endpoint.latched
                else ros.DurabilityPolicy.VOLATILE,
            )
            self.node.create_subscription(
                msg_type, endpoint.topic, self._forward(endpoint.topic), qos, raw=True
            )
            self.relayed.add(endpoint.topic)
            self.node.get_logger().debug(f"relaying {endpoint.topic} ({endpoint.type_name})")

    def _forward(self, topic: str) -> Any:
        def forward(payload: bytes) -> None:
            self.relay.publish(topic, payload)

        return forward


def connect_lines(relay: FoxgloveRelay, config: RvizConfig) -> list[str]:
    """What the node prints so a user can connect a viewer."""
    lines = [
        f"Foxglove WebSocket server on {relay.url} (every ROS topic, ros2msg schemas, CDR)",
        f"  open in a browser: {relay.app_url()}",
        f"  or in Foxglove desktop: Open connection -> Foxglove WebSocket -> {relay.url}",
        f"  fixed frame: {config.fixed_frame}",
    ]
    if config.topics:
        lines.append("  displays: " + ", ".join(config.topics))
    return lines


def main(argv: list[str]) -> int:
    """Serve until shutdown (Ctrl-C or SIGTERM)."""
    args = parse_args(argv[1:])
    config = load_config(args.display_config) if args.display_config else RvizConfig()
    if args.fixed_frame:
        config = RvizConfig(args.fixed_frame, config.displays)
    relay = FoxgloveRelay(port=args.port)
    try:
        ros.init(argv)
        node = ros.Node("rviz2")
        try:
            Rviz2(node, relay)
            for line in connect_lines(relay, config):  # for the user: plain stdout, like rviz2's
                print(line, flush=True)
            ros.spin(node)
        finally:
            node.destroy_node()
            ros.shutdown()
    finally:
        relay.close()
    return 0


if __name__ == "__main__":
    sys.exit(_entry.run(main, "rviz2"))
