"""Event callbacks of publishers and subscriptions (rclpy's ``rclpy.event_handler``).

The *matched* event is implemented, from the graph: a publisher's callback hears when
subscriptions of its topic and type appear or go, a subscription's when publishers do (as
rmw_zenoh derives it from its graph cache). The other events (deadline, liveliness,
incompatible QoS or type, message lost) are accepted and never fire: rmw_zenoh reports none of
them either.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from launchkit.ros.keyexpr import Token


class QoSMatchedInfo:
    """rmw's ``matched_status``: how many peers match now, and in all, and the changes since
    the last event."""

    __slots__ = ("current_count", "current_count_change", "total_count", "total_count_change")

    def __init__(self, total: int = 0, total_change: int = 0, current: int = 0, change: int = 0):
        self.total_count = total
        self.total_count_change = total_change
        self.current_count = current
        self.current_count_change = change

    def __repr__(self) -> str:
        return (
            f"QoSMatchedInfo(total_count={self.total_count}, "
            f"total_count_change={self.total_count_change}, "
            f"current_count={self.current_count}, "
            f"current_count_change={self.current_count_change})"
        )


QoSPublisherMatchedInfo = QoSMatchedInfo
QoSSubscriptionMatchedInfo = QoSMatchedInfo

__all__ = [
    "PublisherEventCallbacks",
    "QoSMatchedInfo",
    "QoSPublisherMatchedInfo",
    "QoSSubscriptionMatchedInfo",
    "SubscriptionEventCallbacks",
]


class PublisherEventCallbacks:
    """The event callbacks of a publisher (``create_publisher(event_callbacks=...)``)."""

    def __init__(
        self,
        *,
        deadline: Callable[[Any], None] | None = None,
        incompatible_qos: Callable[[Any], None] | None = None,
        liveliness: Callable[[Any], None] | None = None,
        matched: Callable[[QoSMatchedInfo], None] | None = None,
        incompatible_type: Callable[[Any], None] | None = None,
        use_default_callbacks: bool = True,
    ) -> None:
        self.deadline = deadline
        self.incompatible_qos = incompatible_qos
        self.liveliness = liveliness
        self.matched = matched
        self.incompatible_type = incompatible_type
        self.use_default_callbacks = use_default_callbacks


class SubscriptionEventCallbacks(PublisherEventCallbacks):
    """The event callbacks of a subscription (``create_subscription(event_callbacks=...)``):
    a publisher's, and ``message_lost``."""

    def __init__(
        self, *, message_lost: Callable[[Any], None] | None = None, **callbacks: Any
    ) -> None:
        super().__init__(**callbacks)
        self.message_lost = message_lost


class MatchedEvent:
    """Watches the graph for the peers of one publisher or subscription and has its node's
    executor call ``callback(QoSMatchedInfo)`` when their number changes."""

    def __init__(
        self,
        entity: Any,
        callback: Callable[[QoSMatchedInfo], None],
        peer_kind: str,
        post: Callable[[Any], None],
    ) -> None:
        self.callback = callback
        self.callback_group = entity.callback_group
        self._executor_event = False
        self._topic = entity.topic_name
        self._type = entity.type_name
        self._peer_kind = peer_kind
        self._post = post
        self._lock = threading.Lock()
        self._peers: set[str] = set()
        self._total = 0
        self._total_change = 0
        self._change = 0
        self._pending = False
        self._graph = entity.node.context.graph
        self._graph.add_listener(self._on_graph)

    def _on_graph(self, token: Token, appeared: bool) -> None:
        # Zenoh's thread
        if token.kind != self._peer_kind or token.topic != self._topic:
            return
        if token.type_name != self._type:
            return
        with self._lock:
            if appeared and token.key not in self._peers:
                self._peers.add(token.key)
                self._total += 1
                self._total_change += 1
                self._change += 1
            elif not appeared and token.key in self._peers:
                self._peers.discard(token.key)
                self._change -= 1
            else:
                return
            if self._pending:
                return
            self._pending = True
        self._post(self)

    def _take_for_executor(self) -> Callable[[], Any] | None:
        with self._lock:
            self._pending = False
            info = QoSMatchedInfo(self._total, self._total_change, len(self._peers), self._change)
            self._total_change = self._change = 0
        callback = self.callback

        async def execute() -> None:
            callback(info)

        return execute

    def destroy(self) -> None:
        """Stop watching."""
        self._graph.remove_listener(self._on_graph)
