"""The executor's hand-off from Zenoh's threads to the spinning thread (``WorkQueue``).

Items arrive once each, in the order each thread put them; a blocked wait returns for an
item or a wake-up and otherwise keeps its deadline; ``put`` and ``wake`` are safe in a signal
handler, which runs in the spinning thread between any two of its bytecodes (Ctrl-C wakes a
spinning node through ``Context.interrupt`` that way). And a node with many subscriptions,
fed by one publisher per topic at once, delivers every message of every topic in order.
"""

from __future__ import annotations

import os
import sys
import threading
import time
from collections.abc import Callable
from types import FrameType
from typing import Any

from launchkit.ros.msgs.std_msgs.msg import String
from ros_helpers import spin_until

from launchkit.ros import HistoryPolicy, Node, QoSProfile
from launchkit.ros.context import Context
from launchkit.ros.executor import WorkQueue
from tests.support import wait_until

SCALE = float(os.environ.get("LAUNCHKIT_TIMEOUT_SCALE", "1"))
PATIENCE = 30.0 * SCALE  # a generous bound on waits that end on a condition


def _item(tag: Any) -> tuple[Callable[..., Any], tuple[Any, ...]]:
    return (print, (tag,))


def test_items_from_many_threads_arrive_once_each_in_each_threads_order() -> None:
    queue = WorkQueue()
    producers, per_producer = 8, 2000
    got: list[Any] = []

    def consume() -> None:
        while len(got) < producers * per_producer:
            item = queue.get(1.0)  # mostly waits: the producers wake it
            if item is not None:
                got.append(item[1][0])

    consumer = threading.Thread(target=consume, daemon=True)
    consumer.start()

    def produce(index: int) -> None:
        for n in range(per_producer):
            queue.put(_item((index, n)))
            if n % 50 == 0:
                time.sleep(0)  # let the consumer catch up and wait again

    threads = [threading.Thread(target=produce, args=(i,)) for i in range(producers)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    consumer.join(PATIENCE)
    assert not consumer.is_alive(), f"the consumer got {len(got)} items and waits for more"
    assert len(got) == producers * per_producer
    for index in range(producers):
        assert [n for i, n in got if i == index] == list(range(per_producer))
    assert queue.get(0) is None


def test_a_blocked_wait_returns_for_an_item_or_a_wake_up() -> None:
    queue = WorkQueue()
    results: list[Any] = []

    def wait(timeout: float | None) -> None:
        results.append(queue.get(timeout))

    for timeout in (None, PATIENCE):
        waiter = threading.Thread(target=wait, args=(timeout,), daemon=True)
        waiter.start()
        wait_until(lambda: queue.bell._waiting == 1, PATIENCE, "the waiter to block", every=0.001)
        queue.put(_item("hello"))
        waiter.join(PATIENCE)
        assert not waiter.is_alive() and results.pop()[1] == ("hello",)

        waiter = threading.Thread(target=wait, args=(timeout,), daemon=True)
        waiter.start()
        wait_until(lambda: queue.bell._waiting == 1, PATIENCE, "the waiter to block", every=0.001)
        queue.wake()
        waiter.join(PATIENCE)
        assert not waiter.is_alive() and results.pop() is not None  # the wake-up item


def test_a_timed_wait_with_nothing_to_take_returns_none() -> None:
    queue = WorkQueue()
    assert queue.get(0) is None
    assert queue.get(0.01) is None
    queue.put(_item(1))
    item = queue.get(0)
    assert item is not None and item[1] == (1,)


def test_a_stale_wake_up_does_not_end_a_wait_early() -> None:
    """A producer that saw the spinner waiting may release after the spinner already took
    its item; the next wait must still wait for an item, not return empty-handed."""
    queue = WorkQueue()
    queue.bell._waiting = 1  # as if a spinner were between announcing itself and taking the item
    queue.put(_item("taken"))
    queue.bell._waiting = 0
    assert queue.get(0) is not None  # the spinner took it; the wake-up stays pending
    results: list[Any] = []
    waiter = threading.Thread(target=lambda: results.append(queue.get(PATIENCE)), daemon=True)
    waiter.start()
    wait_until(
        lambda: queue.bell._waiting == 1 and waiter.is_alive(),
        PATIENCE,
        "the waiter to block",
        every=0.001,
    )
    queue.put(_item("later"))
    waiter.join(PATIENCE)
    assert not waiter.is_alive()
    assert results and results[0] is not None and results[0][1] == ("later",)


def test_put_and_wake_are_safe_at_any_point_of_the_spinning_threads_own_calls() -> None:
    """A signal handler (``Context.interrupt``) runs in the spinning thread between two of its
    bytecodes, possibly inside ``get`` or ``put``: ``put`` and ``wake`` there must neither
    deadlock (a ``queue.Queue`` does: its lock is held) nor lose an item."""
    queue = WorkQueue()
    interrupted = [0]
    inside = [False]
    queue_code = {WorkQueue.get.__code__, WorkQueue.put.__code__}

    def tracer(frame: FrameType, event: str, arg: Any) -> Any:
        if event == "call" and frame.f_code not in queue_code and frame.f_back is not None:
            # also trace what the queue calls (a Queue's Condition and locks are Python code)
            return tracer if _called_from_queue(frame) else None
        if event == "line" and not inside[0]:
            inside[0] = True
            try:
                interrupted[0] += 1
                queue.wake()  # what the handler does, at this line
            finally:
                inside[0] = False
        return tracer

    def _called_from_queue(frame: FrameType) -> bool:
        caller: FrameType | None = frame.f_back
        while caller is not None:
            if caller.f_code in queue_code:
                return True
            caller = caller.f_back
        return False

    taken: list[Any] = []

    def spin() -> None:
        sys.settrace(tracer)
        try:
            for n in range(20):
                queue.put(_item(n))
                taken.append(queue.get(0.001))
                taken.append(queue.get(0))
        finally:
            sys.settrace(None)

    spinner = threading.Thread(target=spin, daemon=True)
    spinner.start()
    spinner.join(PATIENCE)
    assert not spinner.is_alive(), "put/wake inside the queue's own call deadlocked"
    assert interrupted[0] > 0
    while (item := queue.get(0)) is not None:
        taken.append(item)
    numbers = [item[1][0] for item in taken if item is not None and item[0] is print]
    assert numbers == list(range(20))  # every item once, in order, among the wake-ups


def test_many_subscriptions_fed_at_once_get_every_message_in_order(
    contexts: Callable[[], Context],
) -> None:
    topics, count = 12, 40
    subscriber = Node("many_subscriptions", context=contexts())
    received: dict[int, list[int]] = {t: [] for t in range(topics)}
    keep_all = QoSProfile(depth=count, history=HistoryPolicy.KEEP_ALL)
    for topic in range(topics):
        subscriber.create_subscription(
            String,
            f"many_{topic}",
            lambda msg, topic=topic: received[topic].append(int(msg.data)),
            keep_all,
        )
    publishers = []
    for topic in range(topics):
        node = Node(f"feeder_{topic}", context=contexts())
        publishers.append(node.create_publisher(String, f"many_{topic}", keep_all))
    for publisher in publishers:
        assert publisher.wait_for_subscriptions(1, timeout_sec=PATIENCE)

    def feed(index: int) -> None:
        for n in range(count):
            publishers[index].publish(String(data=str(n)))

    feeders = [threading.Thread(target=feed, args=(t,)) for t in range(topics)]
    for feeder in feeders:
        feeder.start()
    spin_until(
        subscriber,
        lambda: all(len(r) == count for r in received.values()),
        PATIENCE,
        "every message of every topic",
    )
    for feeder in feeders:
        feeder.join()
    assert received == {t: list(range(count)) for t in range(topics)}
