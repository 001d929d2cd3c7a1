"""One browser page of the viewer: the ``launchkit.viewer.v1`` WebSocket subprotocol.

Server to page, JSON text frames::

    {"op": "hello", "server": ..., "sessionId": ..., "config": {fixedFrame, frameRate,
     background, displays: [{class, name, enabled, topic, options}]}}
    {"op": "topics", "topics": [{"name": "/scan", "type": "sensor_msgs/msg/LaserScan"}, ...]}
    {"op": "sliders", "topic": "/joint_state_publisher_gui/slider_positions" | null}
    {"op": "msg", "topic": ..., "type": ..., "msg": {...}}      (see convert.py)
    {"op": "rates", "rates": {"/scan": 9.98, ...}}              (each second, wanted topics)
    {"op": "error", "message": ...}

and images as binary frames (convert.py). Page to server::

    {"op": "subscribe", "topics": [...]}   {"op": "unsubscribe", "topics": [...]}
    {"op": "publish", "topic": "/cmd_vel", "type": "geometry_msgs/msg/Twist", "msg": {...}}
"""

from __future__ import annotations

import json
from collections.abc import Awaitable, Callable
from typing import Any

from launchkit.errors import UserError
from launchkit.ros.message_data import build
from launchkit.ros.msgs import normalize_type_name, serialize
from launchkit.stock.rviz2.convert import IMAGE_TYPES
from launchkit.stock.rviz2.hub import Channel, Hub, Message
from launchkit.stock.rviz2.outbox import Frame, Outbox

SUBPROTOCOL = "launchkit.viewer.v1"


class PageSession:
    """The server's side of one page."""

    def __init__(
        self, hub: Hub, send: Callable[[Frame], Awaitable[None]], hello: dict[str, Any]
    ) -> None:
        self.hub = hub
        self.outbox = Outbox(send)
        self._hello = hello
        self._wanted: set[str] = set()

    def start(self) -> None:
        """Send the greeting (with the view's config), the topics and the slider topic."""
        self.outbox.put(json.dumps({"op": "hello", **self._hello}))
        self.hub.join(self)

    def close(self) -> None:
        """The page went away."""
        self.hub.leave(self)

    # -- from the hub ------------------------------------------------------------------------

    def advertise(self, channels: list[Channel]) -> None:
        """The topic list changed."""
        self._send_topics()

    def unadvertise(self, channels: list[Channel]) -> None:
        """The topic list changed (wanted topics stay wanted: they may come back)."""
        self._send_topics()

    def _send_topics(self) -> None:
        topics = [{"name": c.topic, "type": c.type_name} for c in self.hub.channels.values()]
        topics.sort(key=lambda t: t["name"])
        self.outbox.put(json.dumps({"op": "topics", "topics": topics}), key="topics")

    def deliver(self, message: Message) -> None:
        """A message of a wanted topic, converted for the page."""
        frame = message.page_frame()
        if frame is None:
            return
        image = message.channel.type_name in IMAGE_TYPES
        self.outbox.put(frame, key=f"image {message.channel.topic}" if image else None)

    def sliders(self, topic: str | None) -> None:
        """Where joint_state_publisher_gui takes slider positions (None: it does not run)."""
        self.outbox.put(json.dumps({"op": "sliders", "topic": topic}))

    def send_rates(self) -> None:
        """The measured rates of the topics this page wants."""
        if not self._wanted:
            return
        rates = {t: r for t, r in self.hub.rates().items() if t in self._wanted}
        self.outbox.put(json.dumps({"op": "rates", "rates": rates}), key="rates")

    # -- from the page -----------------------------------------------------------------------

    def handle(self, frame: Frame) -> None:
        """One frame from the page; a bad one is answered with an error, never a disconnect."""
        try:
            request = json.loads(frame) if isinstance(frame, str) else None
            if not isinstance(request, dict):
                raise ValueError("a page message is a JSON object with an 'op'")
            op = request.get("op")
            if op == "subscribe":
                for topic in _topics(request):
                    self._wanted.add(topic)
                    self.hub.want(self, topic)
            elif op == "unsubscribe":
                for topic in _topics(request):
                    self._wanted.discard(topic)
                    self.hub.unwant(self, topic)
            elif op == "publish":
                self._publish(request)
            else:
                raise ValueError(f"unknown op {op!r}")
        except (ValueError, UserError) as error:
            self.outbox.put(json.dumps({"op": "error", "message": str(error)}))

    def _publish(self, request: dict[str, Any]) -> None:
        topic = request.get("topic")
        if not isinstance(topic, str) or not topic.startswith("/"):
            raise ValueError("publish: 'topic' must be an absolute topic name")
        type_name = normalize_type_name(str(request.get("type")))
        if self.hub.source.definition(type_name) is None:
            raise ValueError(f"publish: unknown type {type_name}")
        message = build(type_name, request.get("msg", {}), type_name)
        self.hub.publish(self, topic, type_name, serialize(message, type_name))


def _topics(request: dict[str, Any]) -> list[str]:
    topics = request.get("topics")
    if not isinstance(topics, list) or not all(isinstance(t, str) for t in topics):
        raise ValueError(f"{request.get('op')}: 'topics' must be a list of topic names")
    return list(topics)
