"""``Future``: the result of an asynchronous call (rclpy.task.Future's interface), thread-safe."""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any


class Future:
    """A result that arrives later; ``done()``, ``result()``, ``add_done_callback()``."""

    def __init__(self, executor_put: Callable[[Any], None] | None = None) -> None:
        self._event = threading.Event()
        self._result: Any = None
        self._exception: BaseException | None = None
        self._cancelled = False
        self._callbacks: list[Callable[[Future], Any]] = []
        self._lock = threading.Lock()
        # done callbacks run in the spinning thread when the future belongs to a node
        self._schedule = executor_put

    def done(self) -> bool:
        """Whether a result, exception or cancel happened."""
        return self._event.is_set()

    def cancelled(self) -> bool:
        """Whether ``cancel()`` was called before completion."""
        return self._cancelled

    def cancel(self) -> None:
        """Give up waiting."""
        with self._lock:
            if self._event.is_set():
                return
            self._cancelled = True
        self._complete()

    def result(self) -> Any:
        """The result (None until done); raises the exception if one was set."""
        if self._exception is not None:
            raise self._exception
        return self._result

    def exception(self) -> BaseException | None:
        """The exception, if the call failed."""
        return self._exception

    def set_result(self, result: Any) -> None:
        """Complete with ``result``."""
        with self._lock:
            if self._event.is_set():
                return
            self._result = result
        self._complete()

    def set_exception(self, exception: BaseException) -> None:
        """Complete with an exception."""
        with self._lock:
            if self._event.is_set():
                return
            self._exception = exception
        self._complete()

    def wait(self, timeout: float | None = None) -> bool:
        """Block until done (launchkit extension); returns ``done()``."""
        return self._event.wait(timeout)

    def add_done_callback(self, callback: Callable[[Future], Any]) -> None:
        """Call ``callback(future)`` when done (at once if already done)."""
        with self._lock:
            if not self._event.is_set():
                self._callbacks.append(callback)
                return
        self._run(callback)

    def _complete(self) -> None:
        self._event.set()
        with self._lock:
            callbacks, self._callbacks = self._callbacks, []
        for callback in callbacks:
            self._run(callback)
        if not callbacks and self._schedule is not None:
            self._schedule((lambda: None, ()))  # wake a spin_until_future_complete

    def _run(self, callback: Callable[[Future], Any]) -> None:
        if self._schedule is not None:
            self._schedule((callback, (self,)))
        else:
            callback(self)
