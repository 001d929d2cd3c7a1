"""Executors: run subscription, service and timer callbacks in the thread that spins.

Zenoh delivers samples on its own threads; they only put work on the node's queue. The spinning
thread takes work from the queue and runs due timers, so user callbacks never run concurrently.
"""

from __future__ import annotations

import threading
import time
from collections import deque
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, Protocol

from launchkit.ros.context import Context, default_context

if TYPE_CHECKING:
    from launchkit.ros.timer import Timer

Work = tuple[Callable[..., Any], tuple[Any, ...]]
_WAKE: Work = (lambda: None, ())
_MAX_WAIT = 1.0  # re-check timers at least this often (a sim clock may have been switched on)


class ExternalShutdownException(Exception):
    """rclpy's exception for "the context was shut down from outside".

    launchkit's ``spin`` returns instead of raising it; it exists so that code written as
    ``except (KeyboardInterrupt, ExternalShutdownException)`` runs unchanged.
    """


class WorkQueue:
    """The queue zenoh threads fill and the spinning thread drains.

    A deque (``append`` and ``popleft`` are atomic) and a lock used as a binary semaphore: a
    producer releases it only when a spinner is waiting, so a message that finds the spinner
    busy costs one append, and one that finds it idle an append and one release. Its cost
    is the thread hop itself, not a Condition's lock juggling (``queue.Queue``). Signal-safe:
    ``put`` and ``wake`` take no lock a spinner could hold, so a signal handler in the spinning
    thread (``Context.interrupt``) can call them; ``Lock.acquire`` keeps its deadline when a
    signal interrupts it (``SimpleQueue.get`` does not on CPython < 3.12: it can then block
    forever, and the node never sees its shutdown).
    """

    def __init__(self) -> None:
        self._items: deque[Work] = deque()
        self._signal = threading.Lock()
        self._signal.acquire()  # held: no wake-up pending; released: a spinner may go on
        self._waiting = 0  # spinners inside get()'s wait (written under _count)
        self._count = threading.Lock()

    def put(self, item: Work) -> None:
        """Queue ``item`` (any thread, or a signal handler) and wake a waiting spinner."""
        self._items.append(item)
        # the spinner announces itself before its last look at the deque, and this reads the
        # flag after appending: one of the two sees the other (the GIL orders them)
        if self._waiting:
            try:
                self._signal.release()
            except RuntimeError:  # released already: a wake-up is pending
                pass

    def get(self, timeout: float | None) -> Work | None:
        """The next work item, or None after ``timeout`` seconds (0 polls)."""
        items = self._items
        if items:
            return items.popleft()
        if timeout is not None and timeout <= 0:
            return None
        deadline = None if timeout is None else time.monotonic() + timeout
        with self._count:
            self._waiting += 1
        try:
            while True:
                if items:
                    return items.popleft()
                if deadline is None:
                    self._signal.acquire()
                    continue
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    return None
                # a stale release (its item taken by the look above) makes this return at
                # once: the loop looks again and waits for the rest of the time
                self._signal.acquire(timeout=remaining)
        finally:
            with self._count:
                self._waiting -= 1

    def wake(self) -> None:
        """Make a blocked ``get`` return."""
        self.put(_WAKE)


class ExecutableNode(Protocol):
    """What an executor uses of a node (:class:`launchkit.ros.Node`)."""

    @property
    def executor(self) -> Executor:
        """The executor that runs the node when none is given."""

    @property
    def timers(self) -> Sequence[Timer]:
        """The node's timers."""

    def route_work(self, queue: WorkQueue | None) -> WorkQueue:
        """Send the node's work to ``queue`` (None: its own); the previous queue."""


class Executor:
    """Runs the callbacks of the nodes added to it, one at a time, in the spinning thread."""

    def __init__(self, *, context: Context | None = None) -> None:
        self.context = context or default_context
        self._nodes: list[ExecutableNode] = []
        self._work = WorkQueue()

    def add_node(self, node: ExecutableNode) -> bool:
        """Add ``node``; its pending work moves to this executor."""
        if node in self._nodes:
            return False
        self._nodes.append(node)
        old = node.route_work(self._work)
        while (item := old.get(0)) is not None:
            self._work.put(item)
        return True

    def remove_node(self, node: ExecutableNode) -> None:
        """Stop running ``node``'s callbacks here (it gets its own queue back)."""
        if node in self._nodes:
            self._nodes.remove(node)
            node.route_work(None)

    def get_nodes(self) -> list[ExecutableNode]:
        """The nodes this executor runs."""
        return list(self._nodes)

    def _timers(self) -> list[Timer]:
        return [t for node in self._nodes for t in node.timers]

    def spin_once(self, timeout_sec: float | None = None) -> None:
        """Run one ready callback, waiting at most ``timeout_sec`` (None: until one is ready)."""
        deadline = None if timeout_sec is None else time.monotonic() + timeout_sec
        while self.context.ok():
            timer, wait = self._next_timer()
            if timer is not None and wait <= 0:
                timer._fire()
                return
            remaining = None if deadline is None else deadline - time.monotonic()
            if remaining is not None:
                wait = min(wait, remaining) if timer is not None else remaining
            elif timer is None:
                wait = _MAX_WAIT
            item = self._work.get(max(0.0, min(wait, _MAX_WAIT)))
            if item is not None:
                if item is not _WAKE:
                    item[0](*item[1])
                    return
            if remaining is not None and remaining <= 0:
                return

    def _next_timer(self) -> tuple[Timer | None, float]:
        best: Timer | None = None
        best_ns = 0
        for timer in self._timers():
            remaining = timer.time_until_next_call()
            if remaining is None:
                continue
            if timer.clock.ros_time_is_active:
                # sim time advances only with /clock messages, which arrive as work: wait for them
                if remaining > 0:
                    continue
            if best is None or remaining < best_ns:
                best, best_ns = timer, remaining
        return best, best_ns / 1e9

    def spin(self) -> None:
        """Run callbacks until the context shuts down."""
        while self.context.ok():
            self.spin_once(None)

    def spin_until_future_complete(self, future: Any, timeout_sec: float | None = None) -> None:
        """Run callbacks until ``future`` is done (or timeout, or shutdown)."""
        deadline = None if timeout_sec is None else time.monotonic() + timeout_sec
        while self.context.ok() and not future.done():
            remaining = None if deadline is None else deadline - time.monotonic()
            if remaining is not None and remaining <= 0:
                return
            self.spin_once(remaining if remaining is not None else 0.1)

    def wake(self) -> None:
        """Make a blocked ``spin_once`` look again (shutdown, new timer)."""
        self._work.wake()

    def shutdown(self, timeout_sec: float | None = None) -> bool:
        """Forget the nodes."""
        for node in list(self._nodes):
            self.remove_node(node)
        return True


class SingleThreadedExecutor(Executor):
    """rclpy's name for the executor above."""


MultiThreadedExecutor = SingleThreadedExecutor  # callbacks still run one at a time


def spin_once(
    node: ExecutableNode, *, executor: Executor | None = None, timeout_sec: float | None = None
) -> None:
    """Run at most one of ``node``'s ready callbacks, waiting up to ``timeout_sec``."""
    _executor_for(node, executor).spin_once(timeout_sec)


def spin(node: ExecutableNode, executor: Executor | None = None) -> None:
    """Run ``node``'s callbacks until shutdown (SIGINT shuts down and makes this return)."""
    _executor_for(node, executor).spin()


def spin_until_future_complete(
    node: ExecutableNode,
    future: Any,
    executor: Executor | None = None,
    timeout_sec: float | None = None,
) -> None:
    """Run ``node``'s callbacks until ``future`` is done."""
    _executor_for(node, executor).spin_until_future_complete(future, timeout_sec)


def _executor_for(node: ExecutableNode, executor: Executor | None) -> Executor:
    if executor is not None:
        executor.add_node(node)
        return executor
    return node.executor
