"""Guard conditions: a callback an executor runs after ``trigger()`` (rclpy's)."""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from launchkit.ros.callback_groups import CallbackGroup
from launchkit.ros.task import await_or_execute

if TYPE_CHECKING:
    from launchkit.ros.context import Context


class GuardCondition:
    """``trigger()`` (from any thread) makes the executor of its node call ``callback`` once."""

    def __init__(
        self,
        callback: Callable[[], Any] | None,
        callback_group: CallbackGroup | None,
        context: Context | None = None,
    ) -> None:
        self.callback = callback
        self.callback_group: Any = callback_group
        self.context = context
        self._executor_event = False  # an executor's handler for it is pending
        self._executor_triggered = False  # triggered and not yet handled
        self._post: Callable[[Any], None] | None = None  # the node's work queue, once added
        self._lock = threading.Lock()

    def _attach(self, post: Callable[[Any], None]) -> None:
        """Deliver triggers to a node's work queue."""
        self._post = post

    def trigger(self) -> None:
        """Make the executor run the callback (once, however often it is triggered before)."""
        with self._lock:
            if self._executor_triggered:
                return
            self._executor_triggered = True
        if self._post is not None:
            self._post(self)

    def _take_for_executor(self) -> Callable[[], Any] | None:
        with self._lock:
            self._executor_triggered = False
        callback = self.callback
        if callback is None:
            return None

        async def execute() -> None:
            await await_or_execute(callback)

        return execute

    def destroy(self) -> None:
        """Stop delivering triggers."""
        self._post = None
