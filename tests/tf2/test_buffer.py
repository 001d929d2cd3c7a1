"""tf2_ros' ``Buffer``: lookups that wait for data another thread adds, what a timeout ends
with, the futures and coroutines of the async API, and ``can_transform``'s answers."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

import pytest

from launchkit.ros.clock import Duration, Time
from launchkit.ros.tf2 import Buffer, ExtrapolationException, LookupException
from tests.tf2.transforms import stamped, translation

DEADLINE = 30.0  # generous: the machine may be busy; what is checked is the order of events


def wait_until(condition: Callable[[], bool], what: str) -> None:
    deadline = time.monotonic() + DEADLINE
    while not condition():
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out waiting for {what}")
        time.sleep(0.005)


@contextmanager
def once_waiting(buffer: Buffer, action: Callable[[], None]) -> Iterator[None]:
    """Run ``action`` in another thread as soon as someone waits on ``buffer`` for data."""

    def when_waited() -> None:
        wait_until(lambda: bool(buffer._new_data_callbacks), "a wait on the buffer")
        action()

    thread = threading.Thread(target=when_waited, daemon=True)
    thread.start()
    try:
        yield
    finally:
        thread.join(DEADLINE)


def test_a_lookup_waits_for_the_data_another_thread_adds() -> None:
    buffer = Buffer()
    added = stamped("odom", "base", 5, xyz=(1.0, 0.0, 0.0))
    with once_waiting(buffer, lambda: buffer.set_transform(added, "thread")):
        found = buffer.lookup_transform("odom", "base", Time(seconds=5), Duration(seconds=60))
    assert translation(found) == (1.0, 0.0, 0.0)
    assert not buffer._new_data_callbacks or buffer._callbacks_to_remove


def test_after_the_timeout_the_lookup_raises_what_the_data_gives() -> None:
    buffer = Buffer()
    buffer.set_transform(stamped("odom", "base", 4), "test")
    buffer.set_transform(stamped("odom", "base", 5), "test")
    started = time.monotonic()
    with pytest.raises(ExtrapolationException, match="into the future"):
        buffer.lookup_transform("odom", "base", Time(seconds=6), Duration(seconds=0.3))
    assert time.monotonic() - started >= 0.3
    with pytest.raises(LookupException, match='"map" passed to lookupTransform'):
        buffer.lookup_transform("map", "base", Time(), Duration(seconds=0.05))
    # no timeout: no wait at all
    with pytest.raises(LookupException):
        buffer.lookup_transform("map", "base", Time())


def test_can_transform_answers_as_tf2_py_does() -> None:
    buffer = Buffer()
    buffer.set_transform_static(stamped("base", "laser"), "test")
    assert buffer.can_transform("base", "laser", Time()) == 1
    assert buffer.can_transform("base", "map", Time(), Duration(seconds=0.01)) == 0
    assert buffer.can_transform("base", "map", Time(), return_debug_tuple=True) == (
        0,
        'Invalid frame ID "map" passed to canTransform argument source_frame - '
        "frame does not exist",
    )
    later = stamped("map", "base", 9)
    with once_waiting(buffer, lambda: buffer.set_transform(later, "thread")):
        assert buffer.can_transform("map", "laser", Time(seconds=9), Duration(seconds=60)) == 1


def test_the_advanced_lookup_waits_too() -> None:
    buffer = Buffer()
    buffer.set_transform(stamped("odom", "base", 1), "test")

    def more() -> None:
        buffer.set_transform(stamped("odom", "base", 2, xyz=(1.0, 0.0, 0.0)), "thread")

    with once_waiting(buffer, more):
        found = buffer.lookup_transform_full(
            "base", Time(seconds=2), "base", Time(seconds=1), "odom", Duration(seconds=60)
        )
    assert translation(found) == (-1.0, 0.0, 0.0)


def test_the_future_gets_the_transform_when_it_arrives() -> None:
    buffer = Buffer()
    future = buffer.wait_for_transform_async("odom", "base", Time(seconds=3))
    assert not future.done()
    buffer.set_transform(stamped("odom", "other", 3), "test")
    assert not future.done()
    buffer.set_transform(stamped("odom", "base", 3, xyz=(0.0, 2.0, 0.0)), "test")
    assert future.done() and translation(future.result()) == (0.0, 2.0, 0.0)
    buffer.set_transform(stamped("odom", "base", 4), "test")  # the callback is gone by now
    assert buffer._new_data_callbacks == []
    # already there: done at once
    assert buffer.wait_for_transform_async("odom", "base", Time(seconds=3)).done()


def drive(coroutine: Any, step: Callable[[int], None]) -> Any:
    """Run ``coroutine`` as rclpy's executor does (send until it stops), calling ``step(n)``
    between the sends; its result."""
    for n in range(100):
        try:
            coroutine.send(None)
        except StopIteration as finished:
            return finished.value
        step(n)
    raise AssertionError("the coroutine never finished")


def test_the_coroutine_awaits_the_data() -> None:
    buffer = Buffer()
    added = stamped("map", "odom", 8, xyz=(5.0, 0.0, 0.0))
    result = drive(
        buffer.lookup_transform_async("map", "odom", Time(seconds=8)),
        lambda n: buffer.set_transform(added, "test") if n == 2 else None,
    )
    assert translation(result) == (5.0, 0.0, 0.0)
    full = drive(
        buffer.lookup_transform_full_async("odom", Time(seconds=8), "odom", Time(), "map"),
        lambda n: None,
    )
    assert translation(full) == (0.0, 0.0, 0.0)
