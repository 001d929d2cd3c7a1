"""tf2_ros' ``Buffer``: the transform buffer with waiting lookups, as ``tf2_ros.Buffer`` in
ROS 2 Jazzy's Python.

A listener fills it from its node's spinning thread; ``lookup_transform`` and ``can_transform``
with a timeout wait, in the calling thread, for data to arrive, so they belong in a thread other
than the one spinning the listener's node (or use ``wait_for_transform_async`` /
``lookup_transform_async`` from a callback). As in tf2_ros, a timeout is wall time (rclpy's
system clock), whatever clock the node uses; after it, the lookup raises the error the data
gives (``LookupException``, ``ExtrapolationException``, ...), not ``TimeoutException``.

Given a node, the buffer serves ``tf2_frames`` (tf2_msgs/FrameGraph: the frames as YAML).
"""

from __future__ import annotations

import threading
import time as _time
from collections.abc import Callable, Generator
from typing import Any

from launchkit.ros.clock import Clock, Duration
from launchkit.ros.msgs import get_service
from launchkit.ros.task import Future
from launchkit.ros.tf2.buffer_core import BufferCore
from launchkit.ros.tf2.buffer_interface import NO_WAIT, BufferInterface
from launchkit.ros.tf2.time_points import NS_PER_SECOND, duration_ns


class Buffer(BufferCore, BufferInterface):
    """Known frames over the last ``cache_time`` (default 10 s), with waiting lookups; given
    ``node``, its clock and a ``tf2_frames`` service."""

    def __init__(self, cache_time: Duration | None = None, node: Any = None) -> None:
        BufferCore.__init__(self, cache_time)
        BufferInterface.__init__(self)
        self._new_data_callbacks: list[Callable[[], None]] = []
        self._callbacks_to_remove: list[Callable[[], None]] = []
        self._callbacks_lock = threading.RLock()
        if node is not None:
            frame_graph = get_service("tf2_msgs/srv/FrameGraph")
            self.srv = node.create_service(frame_graph, "tf2_frames", self._get_frames)
            self.clock = node.get_clock()
        else:
            self.clock = Clock()

    def _get_frames(self, request: Any, response: Any) -> Any:
        response.frame_yaml = self.all_frames_as_yaml()
        return response

    # new data ----------------------------------------------------------------------------------
    def set_transform(self, transform: Any, authority: str) -> None:
        """Add ``transform`` and tell whoever waits for data."""
        super().set_transform(transform, authority)
        self._call_new_data_callbacks()

    def set_transform_static(self, transform: Any, authority: str) -> None:
        """Add static ``transform`` and tell whoever waits for data."""
        super().set_transform_static(transform, authority)
        self._call_new_data_callbacks()

    def _call_new_data_callbacks(self) -> None:
        with self._callbacks_lock:
            for callback in self._new_data_callbacks:
                callback()
            # removed only now: a callback may ask to be removed while the list is walked
            for callback in self._callbacks_to_remove:
                if callback in self._new_data_callbacks:
                    self._new_data_callbacks.remove(callback)
            self._callbacks_to_remove.clear()

    def _add_callback(self, callback: Callable[[], None]) -> None:
        with self._callbacks_lock:
            self._new_data_callbacks.append(callback)

    def _remove_callback(self, callback: Callable[[], None]) -> None:
        with self._callbacks_lock:
            self._callbacks_to_remove.append(callback)

    def _wait_for(self, ready: Callable[[], bool], timeout: Any) -> None:
        """Return when ``ready()`` or after ``timeout`` (wall time), whichever comes first."""
        wait_ns = duration_ns(timeout)
        if wait_ns <= 0 or ready():
            return
        arrived = threading.Event()
        self._add_callback(arrived.set)
        try:
            deadline = _time.monotonic() + wait_ns / NS_PER_SECOND
            while not ready():
                remaining = deadline - _time.monotonic()
                if remaining <= 0:
                    return
                arrived.wait(remaining)
                arrived.clear()  # the next look at the data comes after this
        finally:
            self._remove_callback(arrived.set)

    # the simple API ------------------------------------------------------------------------------
    def lookup_transform(
        self, target_frame: str, source_frame: str, time: Any, timeout: Duration = NO_WAIT
    ) -> Any:
        """The transform from ``source_frame`` into ``target_frame`` at ``time`` (0: the
        latest), waiting up to ``timeout`` for it; raises tf2's exceptions."""
        self.can_transform(target_frame, source_frame, time, timeout)
        return self.lookup_transform_core(target_frame, source_frame, time)

    def can_transform(
        self,
        target_frame: str,
        source_frame: str,
        time: Any,
        timeout: Duration = NO_WAIT,
        return_debug_tuple: bool = False,
    ) -> Any:
        """Whether the lookup can be done (1 or 0, as tf2_py answers), waiting up to
        ``timeout``; with ``return_debug_tuple``, ``(1 or 0, why not)``."""
        self._wait_for(
            lambda: bool(self.can_transform_core(target_frame, source_frame, time)[0]), timeout
        )
        result = self.can_transform_core(target_frame, source_frame, time)
        return result if return_debug_tuple else result[0]

    def wait_for_transform_async(self, target_frame: str, source_frame: str, time: Any) -> Future:
        """A future that gets the transform once it can be looked up (or the lookup's error)."""
        return self._future_lookup(
            lambda: self.can_transform_core(target_frame, source_frame, time)[0],
            lambda: self.lookup_transform(target_frame, source_frame, time),
        )

    async def lookup_transform_async(self, target_frame: str, source_frame: str, time: Any) -> Any:
        """``lookup_transform`` for a coroutine: awaits the data instead of blocking."""
        await _Done(self.wait_for_transform_async(target_frame, source_frame, time))
        return self.lookup_transform_core(target_frame, source_frame, time)

    # the advanced API ----------------------------------------------------------------------------
    def lookup_transform_full(
        self,
        target_frame: str,
        target_time: Any,
        source_frame: str,
        source_time: Any,
        fixed_frame: str,
        timeout: Duration = NO_WAIT,
    ) -> Any:
        """The transform of data in ``source_frame`` at ``source_time`` into ``target_frame`` at
        ``target_time``, ``fixed_frame`` staying put in between; waits up to ``timeout``."""
        self.can_transform_full(
            target_frame, target_time, source_frame, source_time, fixed_frame, timeout
        )
        return self.lookup_transform_full_core(
            target_frame, target_time, source_frame, source_time, fixed_frame
        )

    def can_transform_full(
        self,
        target_frame: str,
        target_time: Any,
        source_frame: str,
        source_time: Any,
        fixed_frame: str,
        timeout: Duration = NO_WAIT,
        return_debug_tuple: bool = False,
    ) -> Any:
        """Whether :meth:`lookup_transform_full` can be done, waiting up to ``timeout``."""
        arguments = (target_frame, target_time, source_frame, source_time, fixed_frame)
        self._wait_for(lambda: bool(self.can_transform_full_core(*arguments)[0]), timeout)
        result = self.can_transform_full_core(*arguments)
        return result if return_debug_tuple else result[0]

    def wait_for_transform_full_async(
        self,
        target_frame: str,
        target_time: Any,
        source_frame: str,
        source_time: Any,
        fixed_frame: str,
    ) -> Future:
        """A future that gets the advanced lookup's transform once it can be done."""
        arguments = (target_frame, target_time, source_frame, source_time, fixed_frame)
        return self._future_lookup(
            lambda: self.can_transform_full_core(*arguments)[0],
            lambda: self.lookup_transform_full_core(*arguments),
        )

    async def lookup_transform_full_async(
        self,
        target_frame: str,
        target_time: Any,
        source_frame: str,
        source_time: Any,
        fixed_frame: str,
    ) -> Any:
        """``lookup_transform_full`` for a coroutine."""
        arguments = (target_frame, target_time, source_frame, source_time, fixed_frame)
        await _Done(self.wait_for_transform_full_async(*arguments))
        return self.lookup_transform_full_core(*arguments)

    def _future_lookup(self, ready: Callable[[], int], lookup: Callable[[], Any]) -> Future:
        """A future completed by ``lookup()`` when ``ready()`` first holds (now or on new
        data), or by the exception it raises."""
        future = Future()

        def on_new_data() -> None:
            if future.done():
                return
            try:
                if ready():
                    future.set_result(lookup())
            except BaseException as error:  # the future carries it to the awaiting code
                future.set_exception(error)

        # registered before the first look, so data arriving in between is not missed
        self._add_callback(on_new_data)
        future.add_done_callback(lambda _: self._remove_callback(on_new_data))
        on_new_data()
        return future


class _Done:
    """Awaits a future the way rclpy's executor runs a coroutine: it yields until the future
    is done, then gives its result."""

    def __init__(self, future: Future) -> None:
        self.future = future

    def __await__(self) -> Generator[None, None, Any]:
        while not self.future.done():
            yield
        return self.future.result()
