"""The ROS graph as the node graph panel draws it (rqt_graph): nodes, topics, services, actions.

Built from the graph's liveliness tokens, as ``launchkit node info`` reads them. An action is not
an entity of its own on the wire: it is three services (``<name>/_action/send_goal``,
``cancel_goal``, ``get_result``) and two topics (``<name>/_action/feedback``, ``status``). They
are listed under their action, which names its servers (the nodes serving ``send_goal``) and its
clients (the nodes calling it), and each of the five keeps the name of its action, so the page
can show either the action or its parts. Which names count as hidden (a part starting with
``_``) and which are namespaced is the page's choice: it has the names.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from launchkit.ros.keyexpr import Token

ACTION_INFIX = "/_action/"
ACTION_TOPICS = ("feedback", "status")
ACTION_SERVICES = ("send_goal", "cancel_goal", "get_result")
_SEND_GOAL_SUFFIX = "_SendGoal"


@dataclass
class _Entry:
    """A topic or service (or action) and the nodes on each of its two sides."""

    name: str
    types: set[str] = field(default_factory=set)
    sources: set[str] = field(default_factory=set)  # publishers, servers
    sinks: set[str] = field(default_factory=set)  # subscribers, clients

    def as_json(self, source: str, sink: str) -> dict[str, Any]:
        return {
            "name": self.name,
            "types": sorted(self.types),
            source: sorted(self.sources),
            sink: sorted(self.sinks),
            "action": action_of(self.name),
        }


def action_of(name: str) -> str | None:
    """The action a topic or service belongs to (``/fibonacci`` for
    ``/fibonacci/_action/send_goal``), or None."""
    head, infix, part = name.rpartition(ACTION_INFIX)
    if infix and head and part in (*ACTION_TOPICS, *ACTION_SERVICES):
        return head
    return None


def describe_graph(tokens: list[Token]) -> dict[str, Any]:
    """The graph as JSON-ready data: ``nodes``, ``topics``, ``services`` and ``actions``.

    A node is ``{"name": "/ns/talker", "namespace": "/ns"}``; a topic lists its ``publishers``
    and ``subscribers``, a service its ``servers`` and ``clients``, by node name; topics and
    services that make up an action carry its name in ``action``.
    """
    nodes: dict[str, str] = {}
    topics: dict[str, _Entry] = {}
    services: dict[str, _Entry] = {}
    for token in tokens:
        node = token.node_fqn
        if token.kind == "NN":
            nodes[node] = token.namespace
            continue
        table = topics if token.kind in ("MP", "MS") else services
        entry = table.setdefault(token.topic, _Entry(token.topic))
        entry.types.add(token.type_name)
        (entry.sources if token.kind in ("MP", "SS") else entry.sinks).add(node)
    actions: dict[str, _Entry] = {}
    for entry in services.values():
        action = action_of(entry.name)
        if action is None or not entry.name.endswith("/send_goal"):
            continue
        grouped = actions.setdefault(action, _Entry(action))
        grouped.types.update(
            t[: -len(_SEND_GOAL_SUFFIX)] if t.endswith(_SEND_GOAL_SUFFIX) else t
            for t in entry.types
        )
        grouped.sources |= entry.sources
        grouped.sinks |= entry.sinks
    return {
        "nodes": [{"name": n, "namespace": ns} for n, ns in sorted(nodes.items())],
        "topics": [topics[n].as_json("publishers", "subscribers") for n in sorted(topics)],
        "services": [services[n].as_json("servers", "clients") for n in sorted(services)],
        "actions": [
            {**actions[n].as_json("servers", "clients"), "action": None} for n in sorted(actions)
        ],
    }
