"""The launch's pending timers (``<timer>``), earliest first, in the scope they captured.

A timer counts its period from when the evaluation that set it is over, as in ROS, whose
timers start when its event loop regains control: after the processes evaluated in the same
pass have been started. So a ``<timer period="0.5">`` beside a node never fires before the
node has run for 0.5 s, however long the pass took (a ``$(command)``, a busy machine).
"""

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
        self._unarmed: list[tuple[float, DelayedActions, Snapshot]] = []

    def __bool__(self) -> bool:
        return bool(self._heap or self._unarmed)

    def add(self, period: float, timer: DelayedActions, snapshot: Snapshot) -> None:
        """Fire ``timer`` in ``snapshot`` ``period`` seconds after the next :meth:`arm`."""
        self._unarmed.append((period, timer, snapshot))

    def arm(self, now: float) -> None:
        """The evaluation is over: the timers it set start counting at ``now``, in the order
        they were set."""
        for period, timer, snapshot in self._unarmed:
            self._sequence += 1
            heapq.heappush(self._heap, (now + period, self._sequence, timer, snapshot))
        self._unarmed.clear()

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
        self._unarmed = [t for t in self._unarmed if not t[1].cancel_on_shutdown]
        heapq.heapify(self._heap)
