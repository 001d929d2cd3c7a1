"""One browser page of the viewer: the ``launchkit.viewer.v1`` WebSocket subprotocol.

Server to page, JSON text frames::

    {"op": "hello", "server": ..., "sessionId": ..., "config": {fixedFrame, frameRate,
     background, displays: [{class, name, enabled, topic, options}]}}
    {"op": "topics", "topics": [{"name": "/scan", "type": "sensor_msgs/msg/LaserScan"}, ...]}
    {"op": "sliders", "topic": "/joint_state_publisher_gui/slider_positions" | null}
    {"op": "msg", "topic": ..., "type": ..., "msg": {...}}      (see convert.py)
    {"op": "fields", "topic": ..., "type": ..., "t": ..., "msg": {...}}   (the fields form)
    {"op": "rates", "rates": {"/scan": 9.98, ...}}              (each second, wanted topics)
    {"op": "graph", "graph": {nodes, topics, services, actions}}  (see graph_view.py)
    {"op": "interface", "type": ..., "message" | "request" and "response" | "error": ...}
    {"op": "reply", "id": ..., "response": {...}} | {"op": "reply", "id": ..., "error": ...}
    {"op": "error", "message": ...}

and images as binary frames (convert.py). Page to server::

    {"op": "subscribe", "topics": [...], "form": "view" | "fields"}   (form: view by default)
    {"op": "unsubscribe", "topics": [...], "form": ...}
    {"op": "publish", "topic": "/cmd_vel", "type": "geometry_msgs/msg/Twist", "msg": {...}}
    {"op": "graph", "watch": true | false}
    {"op": "interface", "type": "std_srvs/srv/SetBool"}
    {"op": "call", "id": ..., "service": "/talker/set_parameters", "type": ..., "request": {...}}

A topic is wanted from the hub while the page wants it in any form; each message goes to the
page once per form it wants (the view form is what the 3D view, the image panel and the console
read, the fields form every field, for the plot).
"""

from __future__ import annotations

import json
from collections.abc import Awaitable, Callable
from typing import Any

from launchkit.errors import UserError
from launchkit.ros.message_data import build
from launchkit.ros.message_text import to_data
from launchkit.ros.msgs import normalize_type_name, serialize
from launchkit.stock.rviz2.convert import IMAGE_TYPES, to_json
from launchkit.stock.rviz2.hub import Channel, Hub, Message
from launchkit.stock.rviz2.outbox import Frame, Outbox
from launchkit.stock.rviz2.schema import interface_schema

SUBPROTOCOL = "launchkit.viewer.v1"
#: The forms a page can want a topic in: what the views read, and every field.
VIEW, FIELDS = "view", "fields"


class PageSession:
    """The server's side of one page."""

    def __init__(
        self, hub: Hub, send: Callable[[Frame], Awaitable[None]], hello: dict[str, Any]
    ) -> None:
        self.hub = hub
        self.outbox = Outbox(send)
        self._hello = hello
        self._wanted: dict[str, set[str]] = {}  # topic -> the forms the page wants it in

    def start(self) -> None:
        """Send the greeting (with the view's config), the topics and the slider topic."""
        self.outbox.put(json.dumps({"op": "hello", **self._hello}))
        self.hub.join(self)

    def close(self) -> None:
        """The page went away."""
        self.hub.watch_graph(self, False)
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
        """A message of a wanted topic, converted for the page, in each form it wants."""
        for form in sorted(self._wanted.get(message.channel.topic, ())):
            self._deliver(message, form)

    def _deliver(self, message: Message, form: str) -> None:
        if form == FIELDS:
            fields = message.fields_frame()
            if fields is not None:
                self.outbox.put(fields)
            return
        frame = message.page_frame()
        if frame is None:
            return
        image = message.channel.type_name in IMAGE_TYPES
        self.outbox.put(frame, key=f"image {message.channel.topic}" if image else None)

    def graph(self, model: dict[str, Any]) -> None:
        """The node graph changed (the page shows it)."""
        self.outbox.put(json.dumps({"op": "graph", "graph": model}), key="graph")

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
                    self._want(topic, _form(request))
            elif op == "unsubscribe":
                for topic in _topics(request):
                    self._unwant(topic, _form(request))
            elif op == "publish":
                self._publish(request)
            elif op == "graph":
                self.hub.watch_graph(self, bool(request.get("watch", True)))
            elif op == "interface":
                self._interface(request)
            elif op == "call":
                self._call(request)
            else:
                raise ValueError(f"unknown op {op!r}")
        except (ValueError, UserError) as error:
            self.outbox.put(json.dumps({"op": "error", "message": str(error)}))

    def _want(self, topic: str, form: str) -> None:
        forms = self._wanted.get(topic)
        if forms is None:
            self._wanted[topic] = {form}
            self.hub.want(self, topic)  # delivers a latched topic's history in this form
        elif form not in forms:
            forms.add(form)
            for message in self.hub.history(topic):
                self._deliver(message, form)

    def _unwant(self, topic: str, form: str) -> None:
        forms = self._wanted.get(topic)
        if forms is None:
            return
        forms.discard(form)
        if not forms:
            del self._wanted[topic]
            self.hub.unwant(self, topic)

    def _interface(self, request: dict[str, Any]) -> None:
        # answered whatever was asked: the page waits for the answer about the type it named
        asked = request.get("type")
        try:
            type_name = _type_name(request, "interface")
            schema = interface_schema(type_name)
        except ValueError as error:
            schema = {"error": str(error)}
        except KeyError:
            schema = {"error": f"unknown type {asked}"}
        self.outbox.put(json.dumps({"op": "interface", "type": asked, **schema}))

    def _call(self, request: dict[str, Any]) -> None:
        call_id = request.get("id")
        service = request.get("service")
        if not isinstance(service, str) or not service.startswith("/"):
            raise ValueError("call: 'service' must be an absolute service name")
        type_name = _type_name(request, "call")
        if "/srv/" not in type_name or self.hub.source.definition(type_name + "_Request") is None:
            raise ValueError(f"call: unknown service type {type_name}")
        try:
            message = build(type_name + "_Request", request.get("request", {}), "request")
        except UserError as error:
            self._reply(call_id, None, str(error))
            return
        self.hub.source.call_service(
            service,
            type_name,
            message,
            lambda response, error: self._reply(call_id, response, error),
        )

    def _reply(self, call_id: Any, response: Any, error: str | None) -> None:
        if error is not None:
            body: dict[str, Any] = {"op": "reply", "id": call_id, "error": error}
        else:
            body = {"op": "reply", "id": call_id, "response": to_data(response, None)}
        self.outbox.put(to_json(body))

    def _publish(self, request: dict[str, Any]) -> None:
        topic = request.get("topic")
        if not isinstance(topic, str) or not topic.startswith("/"):
            raise ValueError("publish: 'topic' must be an absolute topic name")
        type_name = _type_name(request, "publish")
        if self.hub.source.definition(type_name) is None:
            raise ValueError(f"publish: unknown type {type_name}")
        message = build(type_name, request.get("msg", {}), type_name)
        self.hub.publish(self, topic, type_name, serialize(message, type_name))


def _topics(request: dict[str, Any]) -> list[str]:
    topics = request.get("topics")
    if not isinstance(topics, list) or not all(isinstance(t, str) for t in topics):
        raise ValueError(f"{request.get('op')}: 'topics' must be a list of topic names")
    return list(topics)


def _form(request: dict[str, Any]) -> str:
    form = request.get("form", VIEW)
    if form not in (VIEW, FIELDS):
        raise ValueError(f"{request.get('op')}: 'form' must be {VIEW!r} or {FIELDS!r}")
    return str(form)


def _type_name(request: dict[str, Any], op: str) -> str:
    type_name = request.get("type")
    if not isinstance(type_name, str) or type_name.count("/") not in (1, 2):
        raise ValueError(f"{op}: 'type' must be a ROS type name such as std_msgs/msg/String")
    return normalize_type_name(type_name)
