"""The simulator's ground truth and joint states of one sim instant, paired by stamp.

The server publishes both topics of an entity back to back with the same stamp; a subscriber
(the diff drive, the camera) gets them as two messages and wants them as one state.
"""

from __future__ import annotations

from typing import Any, Generic, TypeVar

Truth = TypeVar("Truth")


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
