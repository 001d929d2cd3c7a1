"""``handle.expect_topic``: the test's own ROS node on a launch's network, collecting messages."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from launchkit.testing._deadline import Deadline

Check = Callable[[], None]  # raises when the launch can no longer deliver (a process died...)


class TopicTimeout(Exception):
    """Not enough matching messages before the deadline; the text says what was seen."""


class TopicProbe:
    """A node of the test process joined to one launch's router and ROS domain (made on first
    use, closed with the launch)."""

    def __init__(self, router: str, domain_id: int) -> None:
        import launchkit.ros as ros  # only tests that look at topics pay for the ROS layer

        self._ros = ros
        self.context = ros.Context(router=router, start_router=False)  # the launch hosts it
        self.context.init([], domain_id)
        self.node = ros.Node("launchkit_test_probe", context=self.context, enable_rosout=False)

    def close(self) -> None:
        """Leave the network (closes the Zenoh session)."""
        self.node.destroy_node()
        self.context.try_shutdown()

    def expect(
        self,
        topic: str,
        min_messages: int,
        deadline: Deadline,
        where: Callable[[Any], bool] | None,
        check: Check,
    ) -> list[Any]:
        """The first ``min_messages`` messages on ``topic`` for which ``where`` holds."""
        from launchkit.ros.msgs import get_message

        ros = self._ros
        graph = self.context.graph
        publisher = None
        while publisher is None:
            check()
            found = graph.tokens("MP", topic)
            if found:
                publisher = found[0]
                break
            if deadline.expired():
                known = sorted({t.topic for t in graph.tokens("MP")})
                raise TopicTimeout(
                    f"no publisher of {topic} appeared; topics with publishers: "
                    + (", ".join(known) or "none")
                )
            graph.wait_for(lambda: bool(graph.tokens("MP", topic)), min(0.1, deadline.remaining()))
        msg_type = get_message(publisher.type_name)
        # Take the publisher's reliability and durability: a latched topic's last message is
        # then delivered too, and a best-effort publisher still reaches us.
        qos = ros.QoSProfile(depth=max(100, min_messages))
        if publisher.qos is not None:
            qos = ros.QoSProfile(
                depth=max(100, min_messages),
                reliability=publisher.qos.reliability,
                durability=publisher.qos.durability,
            )
        matched: list[Any] = []
        seen = [0]

        def collect(message: Any) -> None:
            seen[0] += 1
            if where is None or where(message):
                matched.append(message)

        subscription = self.node.create_subscription(msg_type, topic, collect, qos)
        try:
            while len(matched) < min_messages:
                check()
                if deadline.expired():
                    raise TopicTimeout(
                        f"got {len(matched)} of {min_messages} matching message(s) on {topic} "
                        f"({seen[0]} received in all, type {publisher.type_name})"
                    )
                ros.spin_once(self.node, timeout_sec=min(0.05, deadline.remaining()))
        finally:
            self.node.destroy_subscription(subscription)
        return matched[:min_messages]
