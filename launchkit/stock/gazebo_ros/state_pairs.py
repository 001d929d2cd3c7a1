"""The simulator's ground truth and joint states of one sim instant, paired by stamp.

The server publishes both topics of an entity back to back with the same stamp; a subscriber
(the diff drive, the camera) gets them as two messages and wants them as one state.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Generic, TypeVar

import launchkit.ros as ros
from launchkit.ros.topics import Subscription
from launchkit.stock.gazebo_ros import messages

Truth = TypeVar("Truth")


def subscribe_halves(
    node: ros.Node,
    entity: str,
    on_truth: Callable[[Any], None],
    on_joints: Callable[[Any], None],
) -> list[Subscription]:
    """Subscribe ``node`` to both halves of ``entity``'s state: its ground truth
    (``on_truth``) and its joint states (``on_joints``)."""
    return [
        node.create_subscription(
            messages.message_class("nav_msgs", "Odometry"),
            messages.GROUND_TRUTH_TOPIC.format(entity=entity),
            on_truth,
            10,
        ),
        node.create_subscription(
            messages.message_class("sensor_msgs", "JointState"),
            messages.STATE_TOPIC.format(entity=entity),
            on_joints,
            10,
        ),
    ]


def nanoseconds(msg: Any) -> int:
    """The header stamp of ``msg`` in nanoseconds (the pairing key)."""
    return int(msg.header.stamp.sec) * 1_000_000_000 + int(msg.header.stamp.nanosec)


class StatePairs(Generic[Truth]):
    """Holds the unpaired halves; returns a pair when its second half arrives.

    Halves older than a completed pair are dropped: they can never be completed in order.
    """

    def __init__(self) -> None:
        self._truths: dict[int, Truth] = {}
        self._states: dict[int, Any] = {}

    def add_truth(self, key: int, truth: Truth) -> tuple[Any, Truth] | None:
        """Add the ground truth of ``key``; ``(joint states, truth)`` if it completes a pair."""
        self._truths[key] = truth
        return self._pair(key)

    def add_joints(self, key: int, joints: Any) -> tuple[Any, Truth] | None:
        """Add the joint states of ``key``; ``(joint states, truth)`` if it completes a pair."""
        self._states[key] = joints
        return self._pair(key)

    def clear(self) -> None:
        """Forget every unpaired half."""
        self._truths.clear()
        self._states.clear()

    def _pair(self, key: int) -> tuple[Any, Truth] | None:
        if key not in self._states or key not in self._truths:
            return None
        joints, truth = self._states.pop(key), self._truths.pop(key)
        for stale in [k for k in self._states if k < key]:
            del self._states[stale]
        for stale in [k for k in self._truths if k < key]:
            del self._truths[stale]
        return joints, truth
