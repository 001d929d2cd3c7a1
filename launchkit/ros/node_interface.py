"""What a publisher, subscription, service or client uses of its node.

The entities are built by :class:`launchkit.ros.Node` and hold on to it, but they see it only
through :class:`NodeInterface`: names, the context, its identity on the graph, and the two
hooks into its executor (queue ready work, forget a destroyed entity). This
keeps ``topics.py`` and ``services.py`` from depending on ``node.py`` (which builds them), and
says in one place what the node must keep stable for them.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Protocol

if TYPE_CHECKING:
    from launchkit.ros.callback_groups import CallbackGroup
    from launchkit.ros.context import Context
    from launchkit.ros.logging import RcutilsLogger
    from launchkit.ros.task import NodeTasks


class NodeInterface(Protocol):
    """The part of a node its entities use."""

    @property
    def context(self) -> Context:
        """The ROS context (session, graph, arguments, domain) the node lives in."""

    @property
    def zid(self) -> str:
        """The Zenoh session id the node's liveliness token carries."""

    @property
    def node_id(self) -> int:
        """The node's id within its context (part of every entity's token)."""

    def get_name(self) -> str:
        """The node's name."""

    def get_namespace(self) -> str:
        """The node's namespace."""

    def get_fully_qualified_name(self) -> str:
        """``/namespace/name``."""

    def get_logger(self) -> RcutilsLogger:
        """The node's logger."""

    def resolve_topic_name(self, topic: str, *, only_expand: bool = False) -> str:
        """``topic`` expanded and remapped for this node."""

    def resolve_service_name(self, service: str, *, only_expand: bool = False) -> str:
        """``service`` expanded and remapped for this node."""

    def topic_key(self, fqn: str, type_name: str, type_hash: str) -> str:
        """The Zenoh key expression of a topic or service of this node's domain."""

    @property
    def default_callback_group(self) -> CallbackGroup:
        """The group of the entities made without one."""

    @property
    def scheduler(self) -> NodeTasks:
        """Where the done callbacks of the entities' futures are scheduled."""

    def post(self, work: Any) -> None:
        """Queue a ready entity or a task for the node's executor (any thread)."""

    def forget(self, entity: object) -> None:
        """``entity`` was destroyed: the node no longer closes it at shutdown."""
