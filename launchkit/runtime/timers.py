"""The launch's pending timers (``<timer>``), earliest first, in the scope they captured."""

from __future__ import annotations

import heapq
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from launchkit.description.launch_context import DelayedActions, Snapshot


class TimerQueue:
    """Timers waiting to fire; timers due at the same time fire in the order they were set."""

    def __init__(self) -> None:
        self._heap: list[tuple[float, int, DelayedActions, Snapshot]] = []
        self._sequence = 0

    def __bool__(self) -> bool:
        return bool(self._heap)

    def add(self, due: float, timer: DelayedActions, snapshot: Snapshot) -> None:
        """Fire ``timer`` at ``due`` (the supervisor's clock) in ``snapshot``."""
        self._sequence += 1
        heapq.heappush(self._heap, (due, self._sequence, timer, snapshot))

    def next_due(self) -> float | None:
        """When the earliest timer fires, if there is one."""
        return self._heap[0][0] if self._heap else None

    def pop_due(self, now: float) -> tuple[DelayedActions, Snapshot] | None:
        """The earliest timer if it is due at ``now`` (removed from the queue)."""
        if not self._heap or self._heap[0][0] > now:
            return None
        _, _, timer, snapshot = heapq.heappop(self._heap)
        return timer, snapshot

    def cancel_on_shutdown(self) -> None:
        """Drop the timers that a shutdown cancels (``cancel_on_shutdown``, the default)."""
        self._heap = [t for t in self._heap if not t[2].cancel_on_shutdown]
        heapq.heapify(self._heap)
