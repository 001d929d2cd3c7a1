"""Executors: which thread runs the callbacks of the nodes added to them (rclpy's executors).

Zenoh delivers samples on its own threads; they only queue work on the node (its
:class:`~launchkit.ros.work_queue.WorkQueue`) and ring the executor's doorbell. An executor
waits for the doorbell or the next due timer, asks the entity's callback group, and runs a
handler :class:`~launchkit.ros.task.Task`: in the spinning thread
(:class:`SingleThreadedExecutor`), or in a thread pool (:class:`MultiThreadedExecutor`, where a
mutually exclusive group's callbacks run one at a time and a reentrant group's concurrently).
Coroutine callbacks (``async def``) are stepped by their task and resumed when the future they
await completes. As in rclpy, a context shut down from outside while an executor waits makes it
raise :class:`ExternalShutdownException`.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Sequence
from types import TracebackType
from typing import TYPE_CHECKING, Any, Protocol

from launchkit._lazy import lazy_attributes
from launchkit.ros.context import Context, default_context
from launchkit.ros.task import Future, Task
from launchkit.ros.work_queue import WAKE, Doorbell, WorkQueue

if TYPE_CHECKING:
    from launchkit.ros.callback_groups import CallbackGroup
    from launchkit.ros.timer import Timer

_MAX_WAIT = 1.0  # re-check timers at least this often (a sim clock may have been switched on)


class ExternalShutdownException(Exception):
    """The context was shut down (a signal, or ``shutdown()`` from elsewhere) while waiting."""


class ShutdownException(Exception):
    """The executor itself was shut down."""


class TimeoutException(Exception):
    """Nothing became ready before the timeout."""


class ConditionReachedException(Exception):
    """What the wait was for (a future) is done."""


class ExecutorEntity(Protocol):
    """What an executor uses of a timer, subscription, service, guard condition or waitable."""

    callback_group: CallbackGroup
    _executor_event: bool

    def _take_for_executor(self) -> Callable[[], Any] | None:
        """Take one unit of work: an ``async def`` to run, or None if there is none."""


class ExecutableNode(Protocol):
    """What an executor uses of a node (:class:`launchkit.ros.Node`)."""

    @property
    def context(self) -> Context:
        """The node's context."""

    @property
    def timers(self) -> Sequence[Timer]:
        """The node's timers."""

    @property
    def work(self) -> WorkQueue:
        """The node's queue of ready entities and tasks."""

    @property
    def executor(self) -> Executor | None:
        """The executor the node was added to."""

    @executor.setter
    def executor(self, executor: Executor | None) -> None: ...


class _WorkTracker:
    """Counts the handlers running, so ``shutdown`` can wait for them; knows the threads that
    are stepping one (a callback may shut its own executor down: that one is not waited for)."""

    def __init__(self) -> None:
        self._running = 0
        self._condition = threading.Condition()
        self._stepping: set[int] = set()

    def __enter__(self) -> None:
        with self._condition:
            self._running += 1

    def __exit__(self, *_: object) -> None:
        with self._condition:
            self._running -= 1
            self._condition.notify_all()

    def step(self, handler: Task) -> None:
        """Run one step of ``handler`` in this thread."""
        me = threading.get_ident()
        self._stepping.add(me)
        try:
            handler()
        finally:
            self._stepping.discard(me)

    def idle(self) -> bool:
        """Whether no handler runs (in any thread)."""
        return self._running == 0

    def in_handler(self) -> bool:
        """Whether the calling thread is stepping a handler (so it is inside a callback)."""
        return threading.get_ident() in self._stepping

    def wait(self, timeout_sec: float | None) -> bool:
        if self.in_handler():
            return True
        with self._condition:
            return self._condition.wait_for(lambda: self._running == 0, timeout_sec)


def _never() -> bool:
    return False


class Executor:
    """The base of executors: nodes, tasks, and finding the next callback that may run.

    A subclass defines :meth:`spin_once` (and :meth:`spin_once_until_future_complete`) on
    :meth:`wait_for_ready_callbacks`, as rclpy's custom executors do.
    """

    def __init__(self, *, context: Context | None = None) -> None:
        self._context = context or default_context
        self._nodes: list[ExecutableNode] = []
        self._nodes_lock = threading.RLock()
        self._bell = Doorbell()
        self._tasks = WorkQueue(self._bell)  # created and resumed tasks, released entities
        self._blocked: list[ExecutorEntity] = []  # ready, but their group was busy
        self._retry: list[Task] = []  # coroutines that yielded without a future
        self._lock = threading.Lock()
        self._is_shutdown = False
        self._work_tracker = _WorkTracker()
        self._next_node = 0
        self._context.on_shutdown(self.wake)

    @property
    def context(self) -> Context:
        """The context the executor checks (``ok()``)."""
        return self._context

    def create_task(self, callback: Callable[..., Any], *args: Any, **kwargs: Any) -> Task:
        """Run ``callback(*args, **kwargs)`` (a function or coroutine function) while spinning;
        the task is its future."""
        task = Task(callback, args, kwargs, executor=self)
        self._tasks.put(task)
        return task

    def resume(self, task: Task) -> None:
        """Step ``task`` again (the future its coroutine awaited completed)."""
        self._tasks.put(task)

    def retry(self, task: Task) -> None:
        """Step ``task`` again on the next wake-up."""
        with self._lock:
            self._retry.append(task)

    def add_node(self, node: ExecutableNode) -> bool:
        """Run ``node``'s callbacks here; False if it was here already."""
        with self._nodes_lock:
            if node in self._nodes:
                return False
            self._nodes.append(node)
        node.executor = self
        node.work.bell = self._bell
        self._bell.ring()  # work the node already holds
        return True

    def remove_node(self, node: ExecutableNode) -> None:
        """Stop running ``node``'s callbacks (its pending work stays with it)."""
        with self._nodes_lock:
            if node not in self._nodes:
                return
            self._nodes.remove(node)
        if node.work.bell is self._bell:
            node.work.bell = Doorbell()
        self._bell.ring()

    def get_nodes(self) -> list[ExecutableNode]:
        """The nodes added."""
        with self._nodes_lock:
            return list(self._nodes)

    def wake(self) -> None:
        """Make a waiting executor look again (shutdown, new entities)."""
        self._bell.ring()

    def spin(self) -> None:
        """Run callbacks until the context or the executor shuts down."""
        while self._context.ok() and not self._is_shutdown:
            self.spin_once()

    def spin_until_future_complete(self, future: Future, timeout_sec: float | None = None) -> None:
        """Run callbacks until ``future`` is done or cancelled (or the timeout, or shutdown)."""
        future._add_waiter(self.wake)
        deadline = None if timeout_sec is None or timeout_sec < 0 else time.monotonic()
        if deadline is not None and timeout_sec is not None:
            deadline += timeout_sec
        while (
            self._context.ok()
            and not future.done()
            and not future.cancelled()
            and not self._is_shutdown
        ):
            remaining = None if deadline is None else deadline - time.monotonic()
            self.spin_once_until_future_complete(future, remaining)
            if deadline is not None and time.monotonic() >= deadline:
                return

    def spin_once(self, timeout_sec: float | None = None) -> None:
        """Wait (up to ``timeout_sec``; None: forever) for one callback and run it, or start
        it: a subclass's ``_spin_once_impl`` (or its own ``spin_once``) says how."""
        self._spin_once_impl(timeout_sec, _never)

    def spin_once_until_future_complete(
        self, future: Future, timeout_sec: float | None = None
    ) -> None:
        """As :meth:`spin_once`, returning early once ``future`` is done."""
        future._add_waiter(self.wake)
        self._spin_once_impl(timeout_sec, future.done)

    def _spin_once_impl(self, timeout_sec: float | None, condition: Callable[[], bool]) -> None:
        raise NotImplementedError()

    def shutdown(self, timeout_sec: float | None = None) -> bool:
        """Stop running callbacks and wait (up to ``timeout_sec``) for the running ones."""
        self._is_shutdown = True
        self.wake()
        if timeout_sec is not None and timeout_sec < 0:
            timeout_sec = None
        if not self._work_tracker.wait(timeout_sec):
            return False
        for node in self.get_nodes():
            self.remove_node(node)
        return True

    def __enter__(self) -> Executor:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc_val: BaseException | None,
        exc_tb: TracebackType | None,
    ) -> None:
        self.shutdown()

    # finding ready work ---------------------------------------------------------------------
    def can_execute(self, entity: ExecutorEntity) -> bool:
        """Whether ``entity`` has no handler pending and its group lets it run."""
        return not entity._executor_event and entity.callback_group.can_execute(entity)

    def wait_for_ready_callbacks(
        self,
        timeout_sec: float | None = None,
        nodes: list[ExecutableNode] | None = None,
        condition: Callable[[], bool] = _never,
    ) -> tuple[Task, Any, Any]:
        """The next ready callback as ``(handler, entity, node)``; call the handler to run it.

        Raises :class:`TimeoutException`, :class:`ShutdownException` (this executor was shut
        down), :class:`ExternalShutdownException` (the context was) or
        :class:`ConditionReachedException` (``condition()`` became true).
        """
        deadline = None
        if timeout_sec is not None and timeout_sec >= 0:
            deadline = time.monotonic() + timeout_sec
        while True:
            if self._is_shutdown:
                raise ShutdownException()
            if not self._context.ok():
                raise ExternalShutdownException()
            if condition():
                raise ConditionReachedException()
            found, timer_wait = self._next_ready(nodes)
            if found is not None:
                ready: tuple[Task, Any, Any] = found
                return ready
            remaining = None if deadline is None else deadline - time.monotonic()
            if remaining is not None and remaining <= 0:
                raise TimeoutException()
            wait = min(w for w in (timer_wait, remaining, _MAX_WAIT) if w is not None)
            lockstep = self._context.lockstep
            if lockstep is not None and self._work_tracker.idle():
                lockstep.on_idle()
            self._bell.wait(self._has_work, max(0.0, wait))

    def _has_work(self) -> bool:
        return self._tasks.pending() or any(n.work.pending() for n in self.get_nodes())

    def _next_ready(self, only: list[ExecutableNode] | None) -> tuple[Any, float | None]:
        """A ready ``(handler, entity, node)`` or None, and the seconds to the next timer."""
        self._flush_retries()
        while (item := self._tasks.take()) is not None:
            found = self._consider(item, None)
            if found is not None:
                return found, None
        nodes = [n for n in self.get_nodes() if only is None or n in only]
        timer, node, wait = self._next_timer(nodes)
        if timer is not None and wait <= 0:
            return self._make_handler(timer, node), None
        count = len(nodes)
        for offset in range(count):  # round robin: a busy node does not starve the others
            node = nodes[(self._next_node + offset) % count]
            while (item := node.work.take()) is not None:
                found = self._consider(item, node)
                if found is not None:
                    self._next_node = (self._next_node + offset + 1) % count
                    return found, None
        return None, (wait if timer is not None else None)

    def _consider(self, item: Any, node: ExecutableNode | None) -> Any:
        if item is WAKE:
            return None
        if isinstance(item, Task):
            return None if item.done() or item.cancelled() else (item, None, None)
        entity: ExecutorEntity = item
        if not entity.callback_group.can_execute(entity):
            with self._lock:
                if entity not in self._blocked:
                    self._blocked.append(entity)
            return None
        return self._make_handler(entity, node or getattr(entity, "node", None))

    def _flush_retries(self) -> None:
        with self._lock:
            retries, self._retry = self._retry, []
        for task in retries:
            self._tasks.put(task)

    def _release_blocked(self) -> None:
        """A callback ended: the entities that waited for their group get another look."""
        with self._lock:
            blocked, self._blocked = self._blocked, []
        for entity in blocked:
            self._tasks.put(entity)
        self._bell.ring()

    def _next_timer(self, nodes: list[ExecutableNode]) -> tuple[Timer | None, Any, float]:
        best: Timer | None = None
        best_node: Any = None
        best_ns = 0
        for node in nodes:
            for timer in node.timers:
                if not self.can_execute(timer):
                    continue
                remaining = timer.time_until_next_call()
                if remaining is None:
                    continue
                if remaining > 0 and getattr(timer.clock, "ros_time_is_active", False):
                    continue  # sim time moves with /clock messages, which arrive as work
                if best is None or remaining < best_ns:
                    best, best_node, best_ns = timer, node, remaining
        return best, best_node, best_ns / 1e9

    def _make_handler(self, entity: ExecutorEntity, node: Any) -> tuple[Task, Any, Any]:
        """A task that takes permission from ``entity``'s group, takes its work and runs it."""
        entity._executor_event = True

        async def handler() -> None:
            group = entity.callback_group
            if self._is_shutdown or not group.beginning_execution(entity):
                entity._executor_event = False
                with self._lock:
                    self._blocked.append(entity)
                self._bell.ring()
                return
            with self._work_tracker:
                try:
                    work = entity._take_for_executor()
                    entity._executor_event = False
                    if work is not None:
                        await work()
                finally:
                    group.ending_execution(entity)
                    self._release_blocked()

        return Task(handler, executor=self), entity, node


# the concrete executors and the spin functions live in executors.py (they import this module)
__getattr__ = lazy_attributes(
    __name__,
    {
        name: "launchkit.ros.executors"
        for name in (
            "MultiThreadedExecutor",
            "SingleThreadedExecutor",
            "get_global_executor",
            "spin",
            "spin_once",
            "spin_until_future_complete",
        )
    },
    globals(),
)
