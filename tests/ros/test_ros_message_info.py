"""Raw subscriptions and rclpy's two-argument callbacks: ``(msg, message_info)``."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

from launchkit.ros.msgs.std_msgs.msg import String
from ros_helpers import spin_until

from launchkit.ros import Node, QoSProfile
from launchkit.ros.context import Context
from launchkit.ros.msgs import serialize


def test_a_two_argument_callback_gets_the_message_info(
    contexts: Callable[[], Context],
) -> None:
    talker = Node("talker", context=contexts())
    listener = Node("listener", context=contexts())
    got: list[tuple[Any, dict[str, Any]]] = []
    raw: list[Any] = []
    listener.create_subscription(String, "chatter", lambda m, i: got.append((m, i)), 10)
    listener.create_subscription(String, "chatter", raw.append, 10, raw=True)
    publisher = talker.create_publisher(String, "chatter", QoSProfile(depth=10))
    spin_until(listener, lambda: publisher.get_subscription_count() == 2, 10, "two subscriptions")
    before = time.time_ns()
    sent = [String(data=f"hello {n}") for n in range(3)]
    for message in sent:
        publisher.publish(message)
    spin_until(listener, lambda: len(got) == 3 and len(raw) == 3, 10, "three messages each")

    assert [m.data for m, _ in got] == ["hello 0", "hello 1", "hello 2"]
    assert raw == [serialize(m) for m in sent], "raw=True delivers the CDR bytes, undecoded"
    infos = [i for _, i in got]
    assert [i["publication_sequence_number"] for i in infos] == [1, 2, 3]
    assert [i["reception_sequence_number"] for i in infos] == [1, 2, 3]
    assert all(i["publisher_gid"] == publisher.gid for i in infos)
    for info in infos:
        assert before <= info["source_timestamp"] <= info["received_timestamp"] <= time.time_ns()
