"""The actions of the ROS graph, found as rcl_action finds them: by their feedback topics."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit.ros.action.names import action_of_feedback

if TYPE_CHECKING:
    from launchkit.ros.node import Node


def _actions(names_and_types: list[tuple[str, list[str]]]) -> list[tuple[str, list[str]]]:
    found: dict[str, set[str]] = {}
    for topic, types in names_and_types:
        for type_name in types:
            action = action_of_feedback(topic, type_name)
            if action is not None:
                found.setdefault(action[0], set()).add(action[1])
    return sorted((name, sorted(types)) for name, types in found.items())


def get_action_names_and_types(node: Node) -> list[tuple[str, list[str]]]:
    """Every action in the graph with its types: ``[('/fibonacci', ['pkg/action/X'])]``."""
    return _actions(node.get_topic_names_and_types())


def get_action_server_names_and_types_by_node(
    node: Node, remote_node_name: str, remote_node_namespace: str
) -> list[tuple[str, list[str]]]:
    """The actions a node serves (it publishes their feedback)."""
    return _actions(
        node.get_publisher_names_and_types_by_node(remote_node_name, remote_node_namespace)
    )


def get_action_client_names_and_types_by_node(
    node: Node, remote_node_name: str, remote_node_namespace: str
) -> list[tuple[str, list[str]]]:
    """The actions a node is a client of (it subscribes to their feedback)."""
    return _actions(
        node.get_subscriber_names_and_types_by_node(remote_node_name, remote_node_namespace)
    )
