"""``wait_for_message``: the next message of a topic, without spinning (rclpy's)."""

from __future__ import annotations

import threading
from typing import Any, Protocol

from launchkit.ros.qos import QoSProfile

_POLL = 0.1  # how often the wait looks whether the context was shut down


class SubscribingNode(Protocol):
    """What the wait uses of a node."""

    @property
    def context(self) -> Any:
        """The node's context."""

    def create_subscription(
        self, msg_type: Any, topic: str, callback: Any, qos_profile: Any, **kwargs: Any
    ) -> Any:
        """A subscription."""

    def destroy_subscription(self, subscription: Any) -> bool:
        """Undeclare a subscription."""


def wait_for_message(
    msg_type: Any,
    node: SubscribingNode,
    topic: str,
    *,
    qos_profile: QoSProfile | int = 1,
    time_to_wait: float = -1,
) -> tuple[bool, Any]:
    """``(True, message)`` for the next message on ``topic``, or ``(False, None)`` after
    ``time_to_wait`` seconds (negative: as long as it takes) or when ROS shuts down."""
    arrived = threading.Event()
    subscription = node.create_subscription(msg_type, topic, lambda _: None, qos_profile)
    subscription.on_arrival = arrived.set  # taken here: no executor needs to spin, as in rclpy
    try:
        remaining = None if time_to_wait is None or time_to_wait < 0 else float(time_to_wait)
        while node.context.ok():
            taken = subscription.take_message()
            if taken is not None:
                return True, taken[0]
            wait = _POLL if remaining is None else min(_POLL, remaining)
            if not arrived.wait(wait) and remaining is not None:
                remaining -= wait
                if remaining <= 0:
                    return False, None
            arrived.clear()
        return False, None
    finally:
        node.destroy_subscription(subscription)
