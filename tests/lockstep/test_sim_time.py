"""Sim time in launchkit's rclpy outside the lockstep: a node with ``use_sim_time`` runs its
timers, rates and sleeps on the ``/clock`` another node publishes, never on the wall clock."""

from __future__ import annotations

import itertools
import threading
import time
from collections.abc import Iterator

import pytest
from launchkit.ros.msgs.builtin_interfaces.msg import Time
from launchkit.ros.msgs.rosgraph_msgs.msg import Clock

import launchkit.ros as ros

NS = 1_000_000_000


@pytest.fixture
def sim_node(router: str) -> Iterator[tuple[ros.Node, ros.Publisher]]:
    """A node on sim time spun in a thread, and a /clock publisher in another context."""
    contexts = []
    for _ in range(2):
        context = ros.Context(router=router)
        context.init([])
        contexts.append(context)
    node = ros.Node(
        "sim_timed",
        context=contexts[0],
        parameter_overrides=[ros.Parameter("use_sim_time", value=True)],
    )
    clock_node = ros.Node("clock_source", context=contexts[1])
    publisher = clock_node.create_publisher(Clock, "/clock", 10)
    executor = ros.SingleThreadedExecutor(context=contexts[0])
    executor.add_node(node)
    spinner = threading.Thread(target=executor.spin, daemon=True)
    spinner.start()
    publisher.wait_for_subscriptions(1, timeout_sec=10)
    try:
        yield node, publisher
    finally:
        executor.shutdown()
        for context in contexts:
            context.try_shutdown()
        spinner.join(5)


def publish_until(
    publisher: ros.Publisher, done: threading.Event, step_ns: int, last_ns: int
) -> None:
    """Publish /clock from 0 in ``step_ns`` steps, faster than the wall clock, to ``last_ns``."""
    now = 0
    while now <= last_ns and not done.is_set():
        publisher.publish(Clock(clock=Time(sec=now // NS, nanosec=now % NS)))
        now += step_ns
        time.sleep(0.002)


def test_timers_rates_and_sleeps_follow_a_published_clock(
    sim_node: tuple[ros.Node, ros.Publisher],
) -> None:
    node, publisher = sim_node
    clock = node.get_clock()
    fired: list[int] = []
    node.create_timer(1.0, lambda: fired.append(clock.now().nanoseconds))
    rate = node.create_rate(2.0)
    slept: list[int] = []
    rated: list[int] = []

    def sleeper() -> None:
        clock.sleep_for(ros.Duration(seconds=3.0), node.context)
        slept.append(clock.now().nanoseconds)
        for _ in range(3):
            rate.sleep()
            rated.append(clock.now().nanoseconds)

    thread = threading.Thread(target=sleeper, daemon=True)
    thread.start()
    done = threading.Event()
    # 6 simulated seconds in well under 6 wall seconds (10 ms of sim per ~2 ms of wall)
    started = time.monotonic()
    publish_until(publisher, done, NS // 100, 6 * NS)
    thread.join(10)
    assert time.monotonic() - started < 5.0
    assert [round(t / NS) for t in fired[:5]] == [1, 2, 3, 4, 5]
    assert slept and 3 * NS <= slept[0] < 3 * NS + NS // 10
    assert len(rated) == 3 and all(b - a < NS // 2 + NS // 10 for a, b in itertools.pairwise(rated))
