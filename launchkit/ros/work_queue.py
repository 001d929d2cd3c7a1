"""The hand-off from Zenoh's threads to the thread that spins: work queues and their doorbell.

Each node keeps its ready work (a subscription with messages, a service with requests, a
triggered guard condition, a resumed task) in its own :class:`WorkQueue`; the queues of the
nodes an executor runs share the executor's :class:`Doorbell`, so one wait covers them all and
a node moves between executors (``rclpy.spin_once(node)`` adds and removes it every call)
without its pending work moving.
"""

from __future__ import annotations

import threading
import time
from collections import deque
from collections.abc import Callable
from typing import Any

WAKE: Any = ("wake",)  # the item ``WorkQueue.wake`` puts: it only makes a wait return


class Doorbell:
    """What a waiting spinner blocks on; producers ring it.

    A lock used as a binary semaphore: a producer releases it only when a spinner is waiting,
    so a message that finds the spinner busy costs one flag write, and one that finds it idle
    one release; the cost is the thread hop itself, not a Condition's lock juggling.
    Signal-safe: ``ring`` takes no lock a spinner could hold, so a signal handler in the
    spinning thread (``Context.interrupt``) can call it; ``Lock.acquire`` keeps its deadline
    when a signal interrupts it (``SimpleQueue.get`` does not on CPython < 3.12: it can then
    block forever, and the node never sees its shutdown).
    """

    def __init__(self) -> None:
        self._signal = threading.Lock()
        self._signal.acquire()  # held: no wake-up pending; released: a spinner may go on
        self._waiting = 0  # spinners inside wait() (written under _count)
        self._count = threading.Lock()
        self._rung = False  # a ring no wait has seen yet

    def ring(self) -> None:
        """Make a waiting (or the next) ``wait`` return (any thread, or a signal handler)."""
        self._rung = True
        # the spinner announces itself before its last look, and this reads the count after
        # the producer's append and the flag: one of the two sees the other (the GIL orders)
        if self._waiting:
            try:
                self._signal.release()
            except RuntimeError:  # released already: a wake-up is pending
                pass

    def wait(self, ready: Callable[[], bool], timeout: float | None) -> None:
        """Return when ``ready()`` holds, on a ring, or after ``timeout`` seconds."""
        deadline = None if timeout is None else time.monotonic() + timeout
        with self._count:
            self._waiting += 1
        try:
            while True:
                if self._rung or ready():
                    self._rung = False
                    return
                if deadline is None:
                    self._signal.acquire()
                    continue
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    return
                # a stale release (its ring seen by the look above) makes this return at
                # once: the loop looks again and waits for the rest of the time
                self._signal.acquire(timeout=remaining)
        finally:
            with self._count:
                self._waiting -= 1


class WorkQueue:
    """A queue Zenoh threads fill and a spinning thread drains, ringing a :class:`Doorbell`.

    A deque (``append`` and ``popleft`` are atomic): ``put`` is an append and a ring.
    """

    def __init__(self, bell: Doorbell | None = None) -> None:
        self._items: deque[Any] = deque()
        self.bell = bell or Doorbell()

    def put(self, item: Any) -> None:
        """Queue ``item`` (any thread, or a signal handler) and wake a waiting spinner."""
        self._items.append(item)
        self.bell.ring()

    def take(self) -> Any:
        """The oldest item, or None at once."""
        try:
            return self._items.popleft()
        except IndexError:
            return None

    def pending(self) -> bool:
        """Whether an item waits."""
        return bool(self._items)

    def get(self, timeout: float | None) -> Any:
        """The next item, or None after ``timeout`` seconds (0 polls)."""
        item = self.take()
        if item is not None or (timeout is not None and timeout <= 0):
            return item
        deadline = None if timeout is None else time.monotonic() + timeout
        while True:
            remaining = None if deadline is None else deadline - time.monotonic()
            if remaining is not None and remaining <= 0:
                return None
            self.bell.wait(self.pending, remaining)
            item = self.take()
            if item is not None:
                return item

    def wake(self) -> None:
        """Make a blocked ``get`` return (with the :data:`WAKE` item)."""
        self.put(WAKE)
