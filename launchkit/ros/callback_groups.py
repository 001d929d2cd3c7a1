"""Callback groups: which of a node's callbacks an executor may run at the same time (rclpy's).

Every timer, subscription, service, client and guard condition belongs to one group (the node's
default group, a :class:`MutuallyExclusiveCallbackGroup`, unless another is given). An executor
asks the group before it runs a callback (``can_execute``), takes permission when it starts it
(``beginning_execution``) and gives it back when the callback, a coroutine included, has
finished (``ending_execution``). A :class:`MultiThreadedExecutor` therefore runs the callbacks of
one mutually exclusive group one at a time and those of a reentrant group concurrently.
"""

from __future__ import annotations

import threading
import weakref
from typing import Any


class CallbackGroup:
    """The base of a callback group; a subclass decides when a callback may run."""

    def __init__(self) -> None:
        self.entities: set[weakref.ref[Any]] = set()

    def add_entity(self, entity: Any) -> None:
        """Make ``entity`` (a timer, subscription, service, client...) a member."""
        self.entities.add(weakref.ref(entity))

    def has_entity(self, entity: Any) -> bool:
        """Whether ``entity`` is a member."""
        return weakref.ref(entity) in self.entities

    def can_execute(self, entity: Any) -> bool:
        """Whether a callback of ``entity`` could start now."""
        raise NotImplementedError()

    def beginning_execution(self, entity: Any) -> bool:
        """Take permission to run a callback of ``entity``; True: ``ending_execution`` follows."""
        raise NotImplementedError()

    def ending_execution(self, entity: Any) -> None:
        """A callback of ``entity`` that had permission has finished."""
        raise NotImplementedError()


class ReentrantCallbackGroup(CallbackGroup):
    """Callbacks run whenever they are ready, concurrently in a multi-threaded executor."""

    def can_execute(self, entity: Any) -> bool:
        """Always."""
        return True

    def beginning_execution(self, entity: Any) -> bool:
        """Always granted."""
        return True

    def ending_execution(self, entity: Any) -> None:
        """Nothing to give back."""


class MutuallyExclusiveCallbackGroup(CallbackGroup):
    """One callback of the group at a time (the default group of a node is one)."""

    def __init__(self) -> None:
        super().__init__()
        self._active: Any = None
        self._lock = threading.Lock()

    def can_execute(self, entity: Any) -> bool:
        """Whether no callback of the group is running."""
        with self._lock:
            return self._active is None

    def beginning_execution(self, entity: Any) -> bool:
        """Granted when no callback of the group is running."""
        with self._lock:
            if self._active is not None:
                return False
            self._active = entity
            return True

    def ending_execution(self, entity: Any) -> None:
        """The running callback is done: the next one may start."""
        with self._lock:
            self._active = None
