"""A subscription's queue honours its KEEP_LAST depth (the oldest message goes, as rmw_zenoh's
does), so a burst to a slow subscriber costs a bounded amount of memory; KEEP_ALL keeps all."""

from __future__ import annotations

import subprocess
import sys
import time
from collections.abc import Callable

from launchkit.ros.msgs.std_msgs.msg import String
from ros_helpers import spin_until

from launchkit.ros import HistoryPolicy, Node, QoSProfile
from launchkit.ros.context import Context
from launchkit.ros.topics import Subscription

BURST = 300
PAYLOAD = "x" * 50_000  # 300 x 50 kB: what an unbounded queue would hold is obvious


def _wait_queued(subscription: Subscription, count: int, timeout: float = 30.0) -> None:
    """Wait (without spinning: nothing is delivered meanwhile) until ``count`` messages have
    reached ``subscription``'s queue, kept or dropped."""
    deadline = time.monotonic() + timeout
    while subscription.dropped + len(subscription._queue) < count:
        if time.monotonic() > deadline:
            raise AssertionError(
                f"only {subscription.dropped + len(subscription._queue)} of {count} messages "
                f"reached the subscription within {timeout} s"
            )
        time.sleep(0.02)


def _burst(contexts: Callable[[], Context], qos: QoSProfile) -> tuple[list[str], Subscription]:
    """Send BURST messages and a last one to a subscriber that does not spin meanwhile; then
    spin it until the last one arrives. What its callback saw, and the subscription."""
    publisher_node = Node("burster", context=contexts())
    subscriber_node = Node("slow", context=contexts())
    received: list[str] = []
    subscription = subscriber_node.create_subscription(
        String, "burst", lambda msg: received.append(msg.data[:7]), qos
    )
    # KEEP_ALL + RELIABLE: the publisher blocks rather than drop (zenoh's congestion control)
    publisher = publisher_node.create_publisher(
        String, "burst", QoSProfile(depth=1000, history=HistoryPolicy.KEEP_ALL)
    )
    assert publisher.wait_for_subscriptions(1, timeout_sec=10)
    for index in range(BURST):
        publisher.publish(String(data=f"{index:07d} {PAYLOAD}"))
    publisher.publish(String(data="last"))
    _wait_queued(subscription, BURST + 1)
    spin_until(subscriber_node, lambda: "last" in received, 30, "the last message")
    return received, subscription


def test_keep_last_delivers_only_the_newest_depth_messages(
    contexts: Callable[[], Context],
) -> None:
    received, subscription = _burst(contexts, QoSProfile(depth=10))
    # the newest ten, in order: the last nine of the burst and the final message
    assert received == [f"{i:07d}" for i in range(BURST - 9, BURST)] + ["last"]
    assert subscription.dropped == BURST + 1 - 10
    assert len(subscription._queue) == 0


def test_keep_all_delivers_everything(contexts: Callable[[], Context]) -> None:
    received, subscription = _burst(contexts, QoSProfile(depth=10, history=HistoryPolicy.KEEP_ALL))
    assert len(received) == BURST + 1 and subscription.dropped == 0


SLOW_SUBSCRIBER = """
import resource, sys, time
from launchkit.ros import Node, spin_once
from launchkit.ros.context import Context
from launchkit.ros.msgs.std_msgs.msg import String

context = Context()
context.init([])
node = Node("slow", context=context)
seen = []
node.create_subscription(String, "burst", lambda m: seen.append(m.data[:4]), 10)
while "warm" not in seen:
    spin_once(node, timeout_sec=0.05)
print("warm", flush=True)
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
sys.stdin.readline()  # the burst was sent meanwhile: nothing was taken from the queue
deadline = time.monotonic() + 60
while "last" not in seen and time.monotonic() < deadline:
    spin_once(node, timeout_sec=0.05)
after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
print("last" in seen, len(seen), (after - before) // 1024, flush=True)
"""


def test_a_burst_to_a_slow_subscriber_costs_bounded_memory(
    contexts: Callable[[], Context],
) -> None:
    subscriber = subprocess.Popen(
        [sys.executable, "-c", SLOW_SUBSCRIBER],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
    )
    assert subscriber.stdin is not None and subscriber.stdout is not None
    try:
        node = Node("burster", context=contexts())
        publisher = node.create_publisher(
            String, "burst", QoSProfile(depth=1000, history=HistoryPolicy.KEEP_ALL)
        )
        assert publisher.wait_for_subscriptions(1, timeout_sec=30)
        publisher.publish(String(data="warm"))
        assert subscriber.stdout.readline().strip() == "warm"
        payload = "x" * 100_000
        for _ in range(2000):  # 200 MB, while the subscriber does not spin
            publisher.publish(String(data=payload))
        publisher.publish(String(data="last"))
        subscriber.stdin.write("go\n")
        subscriber.stdin.flush()
        arrived, delivered, grown_mb = subscriber.stdout.readline().split()
    finally:
        subscriber.kill()
        subscriber.communicate(timeout=30)
    assert arrived == "True"
    # a depth-10 queue of 100 kB messages holds 1 MB; unbounded, it would hold 200 MB
    assert int(grown_mb) < 60, f"peak RSS grew by {grown_mb} MB during a 200 MB burst"
    assert int(delivered) < 2000 // 2, "a slow subscriber sees the newest messages, not all"
