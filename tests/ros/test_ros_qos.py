"""QoS: transient local reaches late subscribers; every publisher feeds every subscription."""

from __future__ import annotations

from collections.abc import Callable

import pytest
from launchkit.ros.msgs.std_msgs.msg import String
from ros_helpers import spin_until

from launchkit.ros import DurabilityPolicy, Node, QoSProfile, ReliabilityPolicy
from launchkit.ros.context import Context

LATCHED = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)


def test_late_subscriber_gets_latched_message(contexts: Callable[[], Context]) -> None:
    publisher_node = Node("robot_state_publisher", context=contexts())
    pub = publisher_node.create_publisher(String, "/robot_description", LATCHED)
    pub.publish(String(data="<robot name='old'/>"))
    pub.publish(String(data="<robot name='r'/>"))

    late = Node("late", context=contexts())
    got: list[str] = []
    late.create_subscription(String, "/robot_description", lambda m: got.append(m.data), LATCHED)
    spin_until(late, lambda: bool(got), 10, "the latched /robot_description")
    assert got == ["<robot name='r'/>"]  # depth 1: only the last one


def test_volatile_late_subscriber_gets_only_new_messages(contexts: Callable[[], Context]) -> None:
    node_a = Node("a", context=contexts())
    pub = node_a.create_publisher(String, "news", 10)
    pub.publish(String(data="before"))
    node_b = Node("b", context=contexts())
    got: list[str] = []
    node_b.create_subscription(String, "news", lambda m: got.append(m.data), 10)
    assert pub.wait_for_subscriptions(1, timeout_sec=10)

    def publish_and_check() -> bool:
        pub.publish(String(data="after"))
        return bool(got)

    spin_until(node_b, publish_and_check, 10, "a message published after subscribing")
    assert "before" not in got


def test_best_effort_publisher_feeds_reliable_subscription_as_rmw_zenoh(
    contexts: Callable[[], Context], capsys: pytest.CaptureFixture[str]
) -> None:
    # rmw_zenoh 0.2.x enforces no DDS compatibility rule (graph_cache.cpp leaves the
    # incompatible-QoS events as a TODO): its reliable subscriptions get best-effort samples
    sub_node = Node("strict", context=contexts())
    got: list[tuple[str, bytes]] = []
    sub_node.create_subscription(
        String,
        "data",
        lambda m, info: got.append((m.data, info["publisher_gid"])),
        QoSProfile(depth=10),
    )
    pub_node = Node("loose", context=contexts())
    best_effort = pub_node.create_publisher(
        String, "data", QoSProfile(depth=10, reliability=ReliabilityPolicy.BEST_EFFORT)
    )
    assert best_effort.wait_for_subscriptions(1, timeout_sec=10)

    def publish() -> bool:
        best_effort.publish(String(data="best effort"))
        return bool(got)

    spin_until(sub_node, publish, 10, "a best-effort message on a reliable subscription")
    assert got[0] == ("best effort", best_effort.gid)  # message info names the publisher
    assert "incompatible" not in capsys.readouterr().err


def test_volatile_publisher_feeds_transient_local_subscription_as_rmw_zenoh(
    contexts: Callable[[], Context],
) -> None:
    sub_node = Node("latched_reader", context=contexts())
    got: list[str] = []
    sub_node.create_subscription(String, "state", lambda m: got.append(m.data), LATCHED)
    pub_node = Node("volatile_writer", context=contexts())
    pub = pub_node.create_publisher(String, "state", 10)
    assert pub.wait_for_subscriptions(1, timeout_sec=10)

    def publish() -> bool:
        pub.publish(String(data="live"))
        return bool(got)

    spin_until(sub_node, publish, 10, "a volatile publisher's message on a latched subscription")


def test_reliable_publisher_feeds_best_effort_subscription(
    contexts: Callable[[], Context],
) -> None:
    sub_node = Node("sensor_user", context=contexts())
    got: list[str] = []
    sub_node.create_subscription(
        String,
        "scan",
        lambda m: got.append(m.data),
        QoSProfile(depth=5, reliability=ReliabilityPolicy.BEST_EFFORT),
    )
    pub_node = Node("sensor", context=contexts())
    pub = pub_node.create_publisher(String, "scan", 10)
    assert pub.wait_for_subscriptions(1, timeout_sec=10)

    def publish() -> bool:
        pub.publish(String(data="x"))
        return bool(got)

    spin_until(sub_node, publish, 10, "a message on /scan")
