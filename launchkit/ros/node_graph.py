"""The graph queries of a node (rclpy's ``Node.count_publishers`` and friends)."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from launchkit.ros.context import Context


class GraphQueries:
    """What a node can ask about the ROS graph; mixed into ``Node``."""

    context: Context

    def resolve_topic_name(self, topic: str, *, only_expand: bool = False) -> str:
        """Expand and remap ``topic`` (``Node`` implements it)."""
        raise NotImplementedError

    def count_publishers(self, topic_name: str) -> int:
        """Publishers on ``topic_name`` anywhere in the graph."""
        return len(self.context.graph.tokens("MP", self.resolve_topic_name(topic_name)))

    def count_subscribers(self, topic_name: str) -> int:
        """Subscriptions on ``topic_name`` anywhere in the graph."""
        return len(self.context.graph.tokens("MS", self.resolve_topic_name(topic_name)))

    def get_node_names(self) -> list[str]:
        """Names of the nodes in the graph."""
        return sorted({t.node_name for t in self.context.graph.tokens("NN")})

    def get_node_names_and_namespaces(self) -> list[tuple[str, str]]:
        """(name, namespace) of the nodes in the graph."""
        return sorted({(t.node_name, t.namespace) for t in self.context.graph.tokens("NN")})

    def get_topic_names_and_types(self) -> list[tuple[str, list[str]]]:
        """Every topic with its types."""
        topics: dict[str, set[str]] = {}
        for kind in ("MP", "MS"):
            for t in self.context.graph.tokens(kind):
                topics.setdefault(t.topic, set()).add(t.type_name)
        return sorted((name, sorted(types)) for name, types in topics.items())
