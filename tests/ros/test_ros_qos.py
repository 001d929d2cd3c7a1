"""QoS: transient local reaches late subscribers; best effort does not feed reliable."""

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


def test_best_effort_publisher_does_not_feed_reliable_subscription(
    contexts: Callable[[], Context], capsys: pytest.CaptureFixture[str]
) -> None:
    sub_node = Node("strict", context=contexts())
    got: list[str] = []
    sub = sub_node.create_subscription(
        String, "data", lambda m: got.append(m.data), QoSProfile(depth=10)
    )
    pub_node = Node("loose", context=contexts())
    best_effort = pub_node.create_publisher(
        String, "data", QoSProfile(depth=10, reliability=ReliabilityPolicy.BEST_EFFORT)
    )
    reliable = pub_node.create_publisher(String, "data", QoSProfile(depth=10))
    graph = sub_node.context.graph
    assert graph.wait_for(lambda: bool(sub._blocked_gids), 10), "the subscription never saw it"
    assert pub_node.context.graph.wait_for(lambda: bool(best_effort._warned), 10)

    def publish_both() -> bool:
        best_effort.publish(String(data="best effort"))
        reliable.publish(String(data="reliable"))
        return got.count("reliable") >= 20

    spin_until(sub_node, publish_both, 10, "20 messages from the reliable publisher")
    assert "best effort" not in got
    err = capsys.readouterr().err
    assert "[WARN]" in err and "[strict]" in err and "[loose]" in err
    assert "incompatible QoS" in err and "RELIABILITY" in err


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
