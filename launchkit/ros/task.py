"""``Future`` and ``Task``: results that arrive later and callbacks run by an executor (rclpy's).

A :class:`Future` completes once (a result, an exception, or a cancel). Its done callbacks run
in its executor when it has one (a client's future runs them in the thread that spins the node)
and at once otherwise. A coroutine awaits it (``await future``); :class:`Task` runs a plain
function or steps a coroutine, as rclpy's executors do with ``async def`` callbacks: a step that
waits on a pending future is resumed when that future completes, not polled.
"""

from __future__ import annotations

import enum
import inspect
import sys
import threading
import warnings
import weakref
from collections.abc import Callable, Generator
from typing import Any, Protocol


class FutureState(enum.Enum):
    """Where a future is in its life."""

    PENDING = "PENDING"
    CANCELLED = "CANCELLED"
    FINISHED = "FINISHED"


class TaskScheduler(Protocol):
    """What a future needs of an executor (or of a node's own queue before it has one)."""

    def create_task(self, callback: Callable[..., Any], *args: Any, **kwargs: Any) -> Task:
        """Run ``callback(*args)`` later in the executor."""

    def resume(self, task: Task) -> None:
        """Run the next step of ``task`` (a coroutine whose awaited future completed)."""

    def retry(self, task: Task) -> None:
        """Run the next step of ``task`` when anything else wakes the executor (a coroutine
        that yielded without a future, as rclpy retries it on every wake-up)."""


# the pending future a coroutine step waited on, read by the Task that ran the step
_awaited = threading.local()


def _no_scheduler() -> None:
    return None


async def await_or_execute(callback: Callable[..., Any], *args: Any) -> Any:
    """Await ``callback(*args)`` if it is a coroutine function, else call it (how executors run
    every callback)."""
    if inspect.iscoroutinefunction(callback):
        return await callback(*args)
    return callback(*args)


class Future:
    """A result that arrives later: ``done()``, ``result()``, ``add_done_callback()``, ``await``."""

    def __init__(self, *, executor: TaskScheduler | None = None) -> None:
        self._state = FutureState.PENDING
        self._result: Any = None
        self._exception: BaseException | None = None
        self._exception_fetched = False
        self._callbacks: list[Callable[[Future], Any]] = []
        self._waiters: list[Callable[[], None]] = []
        self._lock = threading.Lock()
        self._event = threading.Event()
        self._executor: Callable[[], TaskScheduler | None] = _no_scheduler
        self._set_executor(executor)

    def __del__(self) -> None:
        if self._exception is not None and not self._exception_fetched:
            print(
                "The following exception was never retrieved: " + str(self._exception),
                file=sys.stderr,
            )

    def __await__(self) -> Generator[None, None, Any]:
        while self._state == FutureState.PENDING:
            _awaited.future = self
            yield
        return self.result()

    def done(self) -> bool:
        """Whether a result or an exception was set (a cancelled future is not done)."""
        return self._state == FutureState.FINISHED

    def cancelled(self) -> bool:
        """Whether ``cancel()`` ended it."""
        return self._state == FutureState.CANCELLED

    def cancel(self) -> None:
        """Give up waiting (done callbacks still run)."""
        with self._lock:
            if self._state != FutureState.PENDING:
                return
            self._state = FutureState.CANCELLED
        self._complete()

    def result(self) -> Any:
        """The result (None until done); raises the exception if one was set."""
        exception = self.exception()
        if exception is not None:
            raise exception
        return self._result

    def exception(self) -> BaseException | None:
        """The exception the work raised, if any."""
        self._exception_fetched = True
        return self._exception

    def set_result(self, result: Any) -> None:
        """Complete with ``result``."""
        with self._lock:
            self._result = result
            self._state = FutureState.FINISHED
        self._complete()

    def set_exception(self, exception: BaseException) -> None:
        """Complete with an exception."""
        with self._lock:
            self._exception = exception
            self._exception_fetched = False
            self._state = FutureState.FINISHED
        self._complete()

    def wait(self, timeout: float | None = None) -> bool:
        """Block until done or cancelled (a launchkit extension); False after ``timeout``."""
        return self._event.wait(timeout)

    def add_done_callback(self, callback: Callable[[Future], Any]) -> None:
        """Call ``callback(future)`` when done: in the executor if there is one, else at once
        (in the thread that completes it, or here when it is done already)."""
        with self._lock:
            if self._state == FutureState.PENDING:
                self._callbacks.append(callback)
                return
            executor = self._executor()
        if executor is not None:
            executor.create_task(callback, self)
        else:
            callback(self)

    def remove_done_callback(self, callback: Callable[[Future], Any]) -> bool:
        """Forget a done callback; False if it was not there (or already ran)."""
        with self._lock:
            try:
                self._callbacks.remove(callback)
            except ValueError:
                return False
            return True

    def _add_waiter(self, waiter: Callable[[], None]) -> None:
        """Call ``waiter()`` in the completing thread when this leaves PENDING (at once if it
        has): how executors learn that a future they wait for, or a task awaits, is ready."""
        with self._lock:
            if self._state == FutureState.PENDING:
                self._waiters.append(waiter)
                return
        waiter()

    def _set_executor(self, executor: TaskScheduler | None) -> None:
        with self._lock:
            self._executor = _no_scheduler if executor is None else weakref.ref(executor)

    def _complete(self) -> None:
        with self._lock:
            callbacks, self._callbacks = self._callbacks, []
            waiters, self._waiters = self._waiters, []
            executor = self._executor()
        self._event.set()
        for waiter in waiters:
            waiter()
        if executor is not None:
            for callback in callbacks:
                executor.create_task(callback, self)
            return
        for callback in callbacks:
            try:
                callback(self)
            except Exception as exc:  # the others still run, as in rclpy
                warnings.warn(f"Unhandled exception in done callback: {exc}", stacklevel=2)


class Task(Future):
    """Runs a function, or steps a coroutine until it finishes; the result is its own.

    Executors make them (rclpy: "should only be instantiated by an Executor"); calling a task
    runs it, or resumes its coroutine up to its next ``await`` of a pending future.
    """

    def __init__(
        self,
        handler: Callable[..., Any],
        args: tuple[Any, ...] | list[Any] | None = None,
        kwargs: dict[str, Any] | None = None,
        executor: TaskScheduler | None = None,
    ) -> None:
        super().__init__(executor=executor)
        self._handler: Any = handler
        self._args: tuple[Any, ...] | list[Any] | None = args or ()
        self._kwargs: dict[str, Any] | None = kwargs or {}
        if inspect.iscoroutinefunction(handler):
            self._handler = handler(*self._args, **self._kwargs)
            self._args = self._kwargs = None
        self._executing = False
        self._task_lock = threading.Lock()

    def __call__(self) -> None:
        """Run the task, or its coroutine's next step; a finished one does nothing."""
        if self._state != FutureState.PENDING or self._executing:
            return
        if not self._task_lock.acquire(blocking=False):
            return
        waiting: Future | bool = False
        try:
            if self._state != FutureState.PENDING:
                return
            self._executing = True
            if inspect.iscoroutine(self._handler):
                waiting = self._step()
            else:
                try:
                    self.set_result(self._handler(*(self._args or ()), **(self._kwargs or {})))
                except Exception as exc:
                    self.set_exception(exc)
                self._release()
            self._executing = False
        finally:
            self._task_lock.release()
        # asked for after the lock is free: another thread may resume the task at once
        executor = self._executor()
        if waiting is False or executor is None:
            return
        if isinstance(waiting, Future):
            waiting._add_waiter(lambda: executor.resume(self))
        else:
            executor.retry(self)  # a bare yield: step again on the executor's next wake-up

    def _step(self) -> Future | bool:
        """One step of the coroutine: the pending future it awaits, True for a bare yield,
        False when it finished."""
        _awaited.future = None
        try:
            self._handler.send(None)
        except StopIteration as stop:
            self.set_result(stop.value)
            self._release()
            return False
        except Exception as exc:
            self.set_exception(exc)
            self._release()
            return False
        awaited: Future | None = getattr(_awaited, "future", None)
        _awaited.future = None
        return awaited if awaited is not None and awaited is not self else True

    def _release(self) -> None:
        self._handler = None
        self._args = self._kwargs = None

    def executing(self) -> bool:
        """Whether the task is running right now."""
        return self._executing

    def cancel(self) -> None:
        """Stop a pending coroutine and cancel the task."""
        if self._state == FutureState.PENDING and inspect.iscoroutine(self._handler):
            self._handler.close()
        super().cancel()


class NodeTasks:
    """Schedules tasks on one node's work queue: what a client's future uses as its executor,
    so that its done callbacks run wherever the node is spun (or wait until it is)."""

    def __init__(self, post: Callable[[Any], None]) -> None:
        self._post = post

    def create_task(self, callback: Callable[..., Any], *args: Any, **kwargs: Any) -> Task:
        """Run ``callback(*args, **kwargs)`` when the node is next spun."""
        task = Task(callback, args, kwargs, executor=self)
        self._post(task)
        return task

    def resume(self, task: Task) -> None:
        """Step ``task`` again."""
        self._post(task)

    def retry(self, task: Task) -> None:
        """Step ``task`` again (as soon as the node is spun)."""
        self._post(task)
