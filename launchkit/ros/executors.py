"""The executors (rclpy's ``SingleThreadedExecutor`` and ``MultiThreadedExecutor``) and the
``spin`` functions that run a node in the context's global executor."""

from __future__ import annotations

import os
import threading
import warnings
import weakref
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor

from launchkit.ros.context import Context, default_context
from launchkit.ros.executor import (
    ConditionReachedException,
    ExecutableNode,
    Executor,
    ExternalShutdownException,
    ShutdownException,
    TimeoutException,
)
from launchkit.ros.task import Future, Task
from launchkit.ros.task import await_or_execute as await_or_execute


class SingleThreadedExecutor(Executor):
    """Runs every callback in the thread that spins."""

    def _spin_once_impl(self, timeout_sec: float | None, condition: Callable[[], bool]) -> None:
        try:
            handler, _, _ = self.wait_for_ready_callbacks(timeout_sec, None, condition)
        except (ShutdownException, TimeoutException, ConditionReachedException):
            return
        self._work_tracker.step(handler)
        exception = handler.exception()
        if exception is not None:
            raise exception


class MultiThreadedExecutor(Executor):
    """Runs callbacks in a pool of ``num_threads`` threads, as their callback groups allow."""

    def __init__(self, num_threads: int | None = None, *, context: Context | None = None) -> None:
        super().__init__(context=context)
        if num_threads is None:
            num_threads = _available_cpus()
        if num_threads == 1:
            warnings.warn(
                "MultiThreadedExecutor is used with a single thread.\n"
                "Use the SingleThreadedExecutor instead.",
                stacklevel=2,
            )
        self._futures: list[Task] = []
        self._executor = ThreadPoolExecutor(num_threads)

    def _spin_once_impl(self, timeout_sec: float | None, condition: Callable[[], bool]) -> None:
        try:
            handler, _, _ = self.wait_for_ready_callbacks(timeout_sec, None, condition)
        except (
            ExternalShutdownException,
            ShutdownException,
            TimeoutException,
            ConditionReachedException,
        ):
            return
        self._executor.submit(self._work_tracker.step, handler)
        self._futures.append(handler)
        for future in self._futures[:]:
            if future.done():
                self._futures.remove(future)
                future.result()  # a callback's exception is raised here, as rclpy does

    def shutdown(self, timeout_sec: float | None = None) -> bool:
        """Stop, wait for the running callbacks, and stop the pool's threads."""
        done = super().shutdown(timeout_sec)
        self._executor.shutdown(wait=done and not self._work_tracker.in_handler())
        return done


def _available_cpus() -> int:
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0)) or 2
    return os.cpu_count() or 2


_global_executors: weakref.WeakKeyDictionary[Context, Executor] = weakref.WeakKeyDictionary()
_global_lock = threading.Lock()


def get_global_executor(context: Context | None = None) -> Executor:
    """The executor ``spin(node)`` uses: one per context (rclpy has one, of the default context),
    shut down and replaced when its context shuts down."""
    context = context or default_context
    with _global_lock:
        executor = _global_executors.get(context)
        if executor is None:
            executor = _global_executors[context] = SingleThreadedExecutor(context=context)

            def reset(made: Executor = executor) -> None:
                made.shutdown()
                with _global_lock:
                    if _global_executors.get(context) is made:
                        del _global_executors[context]

            context.on_shutdown(reset)
    return executor


def spin_once(
    node: ExecutableNode, *, executor: Executor | None = None, timeout_sec: float | None = None
) -> None:
    """Run at most one callback (of ``node``, or of any node ``executor`` runs), waiting up
    to ``timeout_sec`` (None: until one is ready)."""
    executor = executor or get_global_executor(node.context)
    added = executor.add_node(node)
    try:
        executor.spin_once(timeout_sec=timeout_sec)
    finally:
        if added:
            executor.remove_node(node)


def spin(node: ExecutableNode, executor: Executor | None = None) -> None:
    """Run callbacks until the context shuts down. Ctrl-C raises ``KeyboardInterrupt`` and a
    shutdown from outside (SIGTERM) ``ExternalShutdownException``, as in rclpy."""
    executor = executor or get_global_executor(node.context)
    try:
        executor.add_node(node)
        while executor.context.ok():
            executor.spin_once()
    finally:
        executor.remove_node(node)


def spin_until_future_complete(
    node: ExecutableNode,
    future: Future,
    executor: Executor | None = None,
    timeout_sec: float | None = None,
) -> None:
    """Run callbacks until ``future`` is done (or the timeout, or shutdown)."""
    executor = executor or get_global_executor(node.context)
    added = executor.add_node(node)
    try:
        executor.spin_until_future_complete(future, timeout_sec)
    finally:
        if added:
            executor.remove_node(node)
