"""The graph queries of a node (rclpy's ``Node.count_publishers``, ``get_node_names`` and the
``*_by_node`` / ``*_info_by_topic`` queries), answered from the liveliness tokens."""

from __future__ import annotations

import enum
import time
from typing import TYPE_CHECKING, Any

from launchkit.ros import names

if TYPE_CHECKING:
    from launchkit.ros.context import Context
    from launchkit.ros.keyexpr import Token
    from launchkit.ros.qos import QoSProfile


class NodeNameNonExistentError(RuntimeError):
    """A ``*_by_node`` query for a node that is not in the graph (rclpy's error)."""


class TopicEndpointTypeEnum(enum.IntEnum):
    """What kind of endpoint a :class:`TopicEndpointInfo` describes."""

    INVALID = 0
    PUBLISHER = 1
    SUBSCRIPTION = 2


class TopicEndpointInfo:
    """A publisher or subscription of a topic: its node, type, GID and QoS."""

    def __init__(
        self,
        *,
        node_name: str = "",
        node_namespace: str = "",
        topic_type: str = "",
        topic_type_hash: str = "",
        endpoint_type: TopicEndpointTypeEnum = TopicEndpointTypeEnum.INVALID,
        endpoint_gid: list[int] | None = None,
        qos_profile: QoSProfile | None = None,
    ) -> None:
        from launchkit.ros.qos import qos_profile_unknown

        self.node_name = node_name
        self.node_namespace = node_namespace
        self.topic_type = topic_type
        self.topic_type_hash = topic_type_hash
        self.endpoint_type = TopicEndpointTypeEnum(endpoint_type)
        self.endpoint_gid = list(endpoint_gid or [])
        self.qos_profile = qos_profile or qos_profile_unknown

    def __eq__(self, other: object) -> bool:
        return isinstance(other, TopicEndpointInfo) and vars(self) == vars(other)

    __hash__ = None  # type: ignore[assignment]

    def __str__(self) -> str:
        from launchkit.ros.qos import HistoryPolicy

        gid = ".".join(format(x, "02x") for x in self.endpoint_gid)
        qos = self.qos_profile
        history = qos.history.name
        if qos.history == HistoryPolicy.KEEP_LAST:
            history = f"{history} ({qos.depth})"
        return (
            f"Node name: {self.node_name}\n"
            f"Node namespace: {self.node_namespace}\n"
            f"Topic type: {self.topic_type}\n"
            f"Topic type hash: {self.topic_type_hash}\n"
            f"Endpoint type: {self.endpoint_type.name}\n"
            f"GID: {gid}\n"
            "QoS profile:\n"
            f"  Reliability: {qos.reliability.name}\n"
            f"  History (Depth): {history}\n"
            f"  Durability: {qos.durability.name}\n"
            f"  Lifespan: {qos.lifespan}\n"
            f"  Deadline: {qos.deadline}\n"
            f"  Liveliness: {qos.liveliness.name}\n"
            f"  Liveliness lease duration: {qos.liveliness_lease_duration}\n"
        )


class GraphQueries:
    """What a node can ask about the ROS graph; mixed into ``Node``."""

    context: Context

    def resolve_topic_name(self, topic: str, *, only_expand: bool = False) -> str:
        """Expand and remap ``topic`` (``Node`` implements it)."""
        raise NotImplementedError

    def resolve_service_name(self, service: str, *, only_expand: bool = False) -> str:
        """Expand and remap ``service`` (``Node`` implements it)."""
        raise NotImplementedError

    def _tokens(self, kind: str | None = None, topic: str | None = None) -> list[Token]:
        return self.context.graph.tokens(kind, topic)

    def count_publishers(self, topic_name: str) -> int:
        """Publishers on ``topic_name`` anywhere in the graph."""
        return len(self._tokens("MP", self.resolve_topic_name(topic_name)))

    def count_subscribers(self, topic_name: str) -> int:
        """Subscriptions on ``topic_name`` anywhere in the graph."""
        return len(self._tokens("MS", self.resolve_topic_name(topic_name)))

    def count_clients(self, service_name: str) -> int:
        """Clients of ``service_name`` anywhere in the graph."""
        return len(self._tokens("SC", self.resolve_service_name(service_name)))

    def count_services(self, service_name: str) -> int:
        """Servers of ``service_name`` anywhere in the graph."""
        return len(self._tokens("SS", self.resolve_service_name(service_name)))

    def get_node_names(self) -> list[str]:
        """Names of the nodes in the graph."""
        return [name for name, _ in self.get_node_names_and_namespaces()]

    def get_fully_qualified_node_names(self) -> list[str]:
        """``/namespace/name`` of the nodes in the graph."""
        return [names.node_fqn(n, ns) for n, ns in self.get_node_names_and_namespaces()]

    def get_node_names_and_namespaces(self) -> list[tuple[str, str]]:
        """(name, namespace) of the nodes in the graph."""
        return [(n, ns) for n, ns, _ in self.get_node_names_and_namespaces_with_enclaves()]

    def get_node_names_and_namespaces_with_enclaves(self) -> list[tuple[str, str, str]]:
        """(name, namespace, enclave) of the nodes in the graph."""
        return sorted({(t.node_name, t.namespace, t.enclave) for t in self._tokens("NN")})

    def get_topic_names_and_types(self, no_demangle: bool = False) -> list[tuple[str, list[str]]]:
        """Every topic with its types."""
        return _names_and_types([*self._tokens("MP"), *self._tokens("MS")])

    def get_service_names_and_types(self) -> list[tuple[str, list[str]]]:
        """Every service with its types."""
        return _names_and_types([*self._tokens("SS"), *self._tokens("SC")])

    def _by_node(
        self, kind: str, node_name: str, node_namespace: str
    ) -> list[tuple[str, list[str]]]:
        namespace = names.normalize_namespace(node_namespace)
        nodes = {(t.node_name, t.namespace) for t in self._tokens("NN")}
        if (node_name, namespace) not in nodes:
            raise NodeNameNonExistentError(
                f"cannot get information for node '{node_name}' in namespace '{namespace}': "
                "node name does not exist"
            )
        return _names_and_types(
            [t for t in self._tokens(kind) if (t.node_name, t.namespace) == (node_name, namespace)]
        )

    def get_publisher_names_and_types_by_node(
        self, node_name: str, node_namespace: str, no_demangle: bool = False
    ) -> list[tuple[str, list[str]]]:
        """The topics a node publishes, with their types."""
        return self._by_node("MP", node_name, node_namespace)

    def get_subscriber_names_and_types_by_node(
        self, node_name: str, node_namespace: str, no_demangle: bool = False
    ) -> list[tuple[str, list[str]]]:
        """The topics a node subscribes to, with their types."""
        return self._by_node("MS", node_name, node_namespace)

    def get_service_names_and_types_by_node(
        self, node_name: str, node_namespace: str
    ) -> list[tuple[str, list[str]]]:
        """The services a node serves, with their types."""
        return self._by_node("SS", node_name, node_namespace)

    def get_client_names_and_types_by_node(
        self, node_name: str, node_namespace: str
    ) -> list[tuple[str, list[str]]]:
        """The services a node has clients of, with their types."""
        return self._by_node("SC", node_name, node_namespace)

    def _info_by_topic(self, kind: str, topic_name: str, no_mangle: bool) -> list[Any]:
        topic = topic_name if no_mangle else self.resolve_topic_name(topic_name)
        endpoint = (
            TopicEndpointTypeEnum.PUBLISHER if kind == "MP" else TopicEndpointTypeEnum.SUBSCRIPTION
        )
        return [
            TopicEndpointInfo(
                node_name=t.node_name,
                node_namespace=t.namespace,
                topic_type=t.type_name,
                topic_type_hash=t.type_hash,
                endpoint_type=endpoint,
                endpoint_gid=list(t.gid),
                qos_profile=t.qos,
            )
            for t in self._tokens(kind, topic)
        ]

    def get_publishers_info_by_topic(
        self, topic_name: str, no_mangle: bool = False
    ) -> list[TopicEndpointInfo]:
        """The publishers of a topic: node, type, GID, QoS."""
        return self._info_by_topic("MP", topic_name, no_mangle)

    def get_subscriptions_info_by_topic(
        self, topic_name: str, no_mangle: bool = False
    ) -> list[TopicEndpointInfo]:
        """The subscriptions of a topic: node, type, GID, QoS."""
        return self._info_by_topic("MS", topic_name, no_mangle)

    def wait_for_node(self, fully_qualified_node_name: str, timeout: float) -> bool:
        """Wait up to ``timeout`` seconds for a node to be in the graph."""
        if not fully_qualified_node_name.startswith("/"):
            fully_qualified_node_name = f"/{fully_qualified_node_name}"
        deadline = time.monotonic() + timeout
        return self.context.graph.wait_for(
            lambda: fully_qualified_node_name in self.get_fully_qualified_node_names(),
            max(0.0, deadline - time.monotonic()),
        )


def _names_and_types(tokens: list[Token]) -> list[tuple[str, list[str]]]:
    found: dict[str, set[str]] = {}
    for token in tokens:
        found.setdefault(token.topic, set()).add(token.type_name)
    return sorted((name, sorted(types)) for name, types in found.items())
