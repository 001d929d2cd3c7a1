"""Sim time in launchkit's rclpy outside the lockstep: a node with ``use_sim_time`` runs its
timers, rates and sleeps on the ``/clock`` another node publishes, never on the wall clock."""

from __future__ import annotations

import functools
import threading
from collections.abc import Callable, Iterator

import pytest
from launchkit.ros.msgs.builtin_interfaces.msg import Time
from launchkit.ros.msgs.rosgraph_msgs.msg import Clock

import launchkit.ros as ros
from tests.support import wait_until

NS = 1_000_000_000
DueCheck = Callable[[int], bool]


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


def publish_clock(publisher: ros.Publisher, step_ns: int, last_ns: int, due: DueCheck) -> None:
    """Publish /clock from 0 to ``last_ns`` in ``step_ns`` steps, faster than the wall clock.
    After each step the time stands until ``due(now)`` says what is due by then has happened,
    however late a loaded machine runs the node's threads: otherwise a thread woken at 3.5 s
    may read the time at 4.04 s."""
    now = 0
    while now <= last_ns:
        publisher.publish(Clock(clock=Time(sec=now // NS, nanosec=now % NS)))
        wait_until(
            functools.partial(due, now), 30, f"what is due by {now / NS:g} s of simulated time"
        )
        now += step_ns


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
        # until an instant, not for a while: the thread may read the time after it has moved
        clock.sleep_until(ros.Time(seconds=3, clock_type=clock.clock_type), node.context)
        slept.append(clock.now().nanoseconds)
        for _ in range(3):
            rate.sleep()
            rated.append(clock.now().nanoseconds)

    def happened(now: int) -> bool:
        # the timer each second; at 3 s the sleep, and the rate's first sleep returns at once
        # (the loop is late: the rate began at 0); then one return each half second
        returns = 0 if now < 3 * NS else min(3, 1 + (now - 3 * NS) // (NS // 2))
        return len(fired) >= now // NS and len(slept) >= (now >= 3 * NS) and len(rated) >= returns

    thread = threading.Thread(target=sleeper, daemon=True)
    thread.start()
    publish_clock(publisher, NS // 100, 6 * NS, happened)
    thread.join(10)
    assert fired[:5] == [1 * NS, 2 * NS, 3 * NS, 4 * NS, 5 * NS]
    assert slept == [3 * NS]
    assert rated == [3 * NS, 3 * NS + NS // 2, 4 * NS]
