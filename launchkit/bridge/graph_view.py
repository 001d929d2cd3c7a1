"""What each side of the bridge sees: topics and services with their types and endpoints.

Both sides are reduced to the same shape, without the bridge's own endpoints, so that deciding
what to bridge is one pure function (:mod:`launchkit.bridge.plan`).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

from launchkit.bridge._rclpy import from_rclpy_qos
from launchkit.ros.keyexpr import Token
from launchkit.ros.qos import QoSProfile

DDS_DEFAULT_DEPTH = 10  # Fast DDS does not announce history depth; assume rclpy's usual 10


@dataclass
class TopicEnds:
    """One topic on one side: its types, its publishers' QoS, how many subscriptions."""

    types: set[str] = field(default_factory=set)
    publishers: list[QoSProfile] = field(default_factory=list)
    subscriptions: int = 0


@dataclass
class ServiceEnds:
    """One service on one side: its types and how many servers."""

    types: set[str] = field(default_factory=set)
    servers: int = 0


@dataclass
class GraphView:
    """Every topic and service of one side that the bridge does not own."""

    topics: dict[str, TopicEnds] = field(default_factory=dict)
    services: dict[str, ServiceEnds] = field(default_factory=dict)

    def topic(self, name: str) -> TopicEnds:
        """The entry of topic ``name`` (created empty)."""
        return self.topics.setdefault(name, TopicEnds())

    def service(self, name: str) -> ServiceEnds:
        """The entry of service ``name`` (created empty)."""
        return self.services.setdefault(name, ServiceEnds())


def zenoh_view(tokens: Iterable[Token], own_zid: str) -> GraphView:
    """launchkit's side, from liveliness tokens (the bridge's own session left out)."""
    view = GraphView()
    for token in tokens:
        if token.zid == own_zid or token.kind == "NN":
            continue
        if token.kind in ("MP", "MS"):
            ends = view.topic(token.topic)
            ends.types.add(token.type_name)
            if token.kind == "MP" and token.qos is not None:
                ends.publishers.append(token.qos)
            elif token.kind == "MS":
                ends.subscriptions += 1
        elif token.kind == "SS":
            service = view.service(token.topic)
            service.types.add(token.type_name)
            service.servers += 1
    return view


def dds_view(node: Any, own_nodes: list[Any]) -> GraphView:
    """The DDS side, asked from the rclpy ``node``; the endpoints of ``own_nodes`` (the
    bridge's rclpy nodes) left out."""
    owners = {(n.get_name(), n.get_namespace()) for n in own_nodes}
    # rclpy counts servers without saying whose: one less for each service the bridge serves
    own_services = [
        name for owner in owners for name, _ in node.get_service_names_and_types_by_node(*owner)
    ]
    view = GraphView()
    for name, types in node.get_topic_names_and_types():
        publishers = [
            info
            for info in node.get_publishers_info_by_topic(name)
            if (info.node_name, info.node_namespace) not in owners
        ]
        subscriptions = [
            info
            for info in node.get_subscriptions_info_by_topic(name)
            if (info.node_name, info.node_namespace) not in owners
        ]
        if not publishers and not subscriptions:
            continue
        ends = view.topic(name)
        ends.types.update(types)
        ends.publishers = [from_rclpy_qos(p.qos_profile, DDS_DEFAULT_DEPTH) for p in publishers]
        ends.subscriptions = len(subscriptions)
    for name, types in node.get_service_names_and_types():
        servers = node.count_services(name) - own_services.count(name)
        if servers > 0:
            service = view.service(name)
            service.types.update(types)
            service.servers = servers
    return view
