"""The hub's ROS side: the graph, lazy subscriptions and the publishers clients drive with.

The graph is followed through its liveliness tokens (no polling): every change schedules one
refresh of the topic list a moment later, on the server's loop. Subscriptions are raw (the CDR
bytes as they came) with the QoS the publishers offer: best effort if any publisher is best
effort, transient local if any is latched. They are made and dropped from the server's loop
thread as clients come and go; their callbacks run in the node's spinning thread and post each
message to the loop.
"""

from __future__ import annotations

import functools
import threading
import time
from collections.abc import Callable
from typing import Any

import launchkit.ros as ros
from launchkit.ros.keyexpr import Token
from launchkit.ros.msgs import get_message, get_service, message_definition
from launchkit.stock.rviz2.graph_view import describe_graph
from launchkit.stock.rviz2.hub import Endpoint, Hub
from launchkit.stock.rviz2.server import ViewerServer

#: The topic joint_state_publisher_gui takes slider positions on (``~/slider_positions``).
SLIDER_SUFFIX = "/slider_positions"
JOINT_STATE = "sensor_msgs/msg/JointState"
#: Seconds a service the page calls has to answer.
CALL_TIMEOUT = 10.0
#: Graph changes come in bursts (a node brings several topics up): refresh once after this.
REFRESH_DELAY = 0.1


def publisher_endpoints(tokens: list[Token]) -> list[Endpoint]:
    """Every topic with a publisher, with the QoS a subscriber must use to hear them all."""
    found: dict[str, Endpoint] = {}
    for token in tokens:
        if token.kind != "MP":
            continue
        qos = token.qos
        latched = qos is not None and qos.durability == ros.DurabilityPolicy.TRANSIENT_LOCAL
        best_effort = qos is not None and qos.reliability == ros.ReliabilityPolicy.BEST_EFFORT
        seen = found.get(token.topic)
        if seen is not None:
            latched = latched or seen.latched
            best_effort = best_effort or seen.best_effort
            if seen.type_name != token.type_name:  # two types on one topic: keep the first
                continue
        found[token.topic] = Endpoint(token.topic, token.type_name, latched, best_effort)
    return sorted(found.values(), key=lambda e: e.topic)


def slider_topic(tokens: list[Token]) -> str | None:
    """Where a running joint_state_publisher_gui listens for slider positions, if it runs."""
    topics = sorted(
        t.topic
        for t in tokens
        if t.kind == "MS" and t.type_name == JOINT_STATE and t.topic.endswith(SLIDER_SUFFIX)
    )
    return topics[0] if topics else None


@functools.cache
def _definition(type_name: str) -> str | None:
    try:
        return message_definition(type_name)
    except Exception:  # a type this installation does not know
        return None


class RosLink:
    """Implements the hub's :class:`~.hub.Source` with a launchkit.ros node."""

    def __init__(self, node: ros.Node) -> None:
        self.node = node
        self._lock = threading.Lock()
        self._subscriptions: dict[str, Any] = {}
        self._publishers: dict[tuple[str, str], Any] = {}
        self._hub: Hub | None = None
        self._server: ViewerServer | None = None
        self._refresh_pending = False
        self._unknown: set[str] = set()

    def connect(self, hub: Hub, server: ViewerServer) -> None:
        """Start following the graph for ``hub``, whose loop runs in ``server``."""
        self._hub, self._server = hub, server
        self.node.context.graph.add_listener(self._graph_event)
        server.post(self._refresh_soon)

    def close(self) -> None:
        """Stop following the graph."""
        self.node.context.graph.remove_listener(self._graph_event)

    # -- the graph ---------------------------------------------------------------------------

    def _graph_event(self, token: Token, appeared: bool) -> None:  # zenoh's thread
        if self._server is not None:  # any kind: the node graph shows nodes and services too
            self._server.post(self._refresh_soon)

    def _refresh_soon(self) -> None:  # the loop's thread
        if not self._refresh_pending and self._server is not None:
            self._refresh_pending = True
            self._server.loop.call_later(REFRESH_DELAY, self._refresh)

    def _refresh(self) -> None:
        self._refresh_pending = False
        tokens = self.node.context.graph.tokens()
        endpoints = publisher_endpoints(tokens)
        for endpoint in endpoints:
            unknown = self.definition(endpoint.type_name) is None
            if unknown and endpoint.type_name not in self._unknown:
                self._unknown.add(endpoint.type_name)
                self.node.get_logger().warn(
                    f"not showing {endpoint.topic}: unknown type {endpoint.type_name}"
                )
        if self._hub is not None:
            self._hub.graph_changed(endpoints, slider_topic(tokens))
            viewer = self.node.get_fully_qualified_name()
            self._hub.nodes_changed({**describe_graph(tokens), "viewer": viewer})

    # -- Source ------------------------------------------------------------------------------

    def definition(self, type_name: str) -> str | None:
        """The ``.msg`` text of ``type_name``; None when it is unknown."""
        return _definition(type_name)

    def subscribe(self, endpoint: Endpoint) -> None:
        """Subscribe raw to ``endpoint``'s topic with QoS that matches every publisher."""
        self.unsubscribe(endpoint.topic)
        qos = ros.QoSProfile(
            depth=10,
            reliability=ros.ReliabilityPolicy.BEST_EFFORT
            if endpoint.best_effort
            else ros.ReliabilityPolicy.RELIABLE,
            durability=ros.DurabilityPolicy.TRANSIENT_LOCAL
            if endpoint.latched
            else ros.DurabilityPolicy.VOLATILE,
        )
        topic = endpoint.topic
        subscription = self.node.create_subscription(
            get_message(endpoint.type_name), topic, self._forwarder(topic), qos, raw=True
        )
        with self._lock:
            self._subscriptions[topic] = subscription
        self.node.get_logger().debug(f"subscribed to {topic} ({endpoint.type_name})")

    def _forwarder(self, topic: str) -> Any:
        def forward(payload: bytes) -> None:  # the spinning thread
            if self._hub is not None and self._server is not None:
                self._server.post(self._hub.receive, topic, payload, time.time_ns())

        return forward

    def unsubscribe(self, topic: str) -> None:
        """Drop the subscription to ``topic``."""
        with self._lock:
            subscription = self._subscriptions.pop(topic, None)
        if subscription is not None:
            self.node.destroy_subscription(subscription)
            self.node.get_logger().debug(f"unsubscribed from {topic}")

    def subscribed(self) -> list[str]:
        """The topics subscribed now."""
        with self._lock:
            return sorted(self._subscriptions)

    def acquire_publisher(self, topic: str, type_name: str) -> None:
        """A publisher of ``type_name`` on ``topic`` (reliable, volatile, depth 10)."""
        with self._lock:
            if (topic, type_name) in self._publishers:
                return
        publisher = self.node.create_publisher(get_message(type_name), topic, 10)
        with self._lock:
            self._publishers[(topic, type_name)] = publisher

    def release_publisher(self, topic: str, type_name: str) -> None:
        """Drop the publisher."""
        with self._lock:
            publisher = self._publishers.pop((topic, type_name), None)
        if publisher is not None:
            self.node.destroy_publisher(publisher)

    def publish(self, topic: str, type_name: str, payload: bytes) -> None:
        """Send CDR bytes on an acquired publisher."""
        with self._lock:
            publisher = self._publishers.get((topic, type_name))
        if publisher is not None:
            publisher.publish(payload)

    def call_service(
        self, service: str, type_name: str, request: Any, reply: Callable[[Any, str | None], None]
    ) -> None:
        """Call ``service`` once with ``request`` (a ``type_name`` request message) through a
        client made for the call; ``reply(response, error)`` runs on the server's loop."""
        client = self.node.create_client(get_service(type_name), service)

        def done(future: ros.Future) -> None:  # the spinning thread
            error = future.exception()
            response = None if error is not None else future.result()
            self.node.destroy_client(client)
            if self._server is not None:
                self._server.post(reply, response, None if error is None else str(error))

        if not client.service_is_ready():
            self.node.destroy_client(client)
            if self._server is not None:
                self._server.post(reply, None, f"no server of {service} ({type_name}) is running")
            return
        client.call_async(request, CALL_TIMEOUT).add_done_callback(done)
