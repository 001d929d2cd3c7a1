"""The hub between the ROS graph and the connected clients (pages and Foxglove apps).

It keeps the channels (one per topic with publishers), which client wants which topic, and the
last messages of latched topics. A topic is subscribed in ROS only while some client wants it,
and unsubscribed when the last one lets go: with nobody watching, the camera renders nothing.

Everything here runs on the server's event loop thread. The ROS side (:class:`Source`) calls
:meth:`Hub.receive` and :meth:`Hub.graph_changed` through ``loop.call_soon_threadsafe``.
"""

from __future__ import annotations

import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Protocol

from launchkit.ros.msgs import deserialize
from launchkit.stock.rviz2.assets import AssetCatalog
from launchkit.stock.rviz2.convert import PageFrame, to_fields, to_page

#: How many messages of a latched topic are kept for clients that subscribe later.
LATCHED_HISTORY = 10
#: The window a topic's rate is measured over, in seconds.
RATE_WINDOW = 2.0


@dataclass(frozen=True)
class Endpoint:
    """A topic as its publishers offer it: the QoS a subscriber must use to match them."""

    topic: str
    type_name: str
    latched: bool = False
    best_effort: bool = False


@dataclass
class Channel:
    """A topic advertised to clients."""

    id: int
    topic: str
    type_name: str
    definition: str
    latched: bool


@dataclass
class Message:
    """One message of a channel, as received from ROS; converted for pages at most once."""

    channel: Channel
    payload: bytes
    stamp_ns: int
    _page: PageFrame | None = None
    _fields: str | None = None
    _failed: bool = False

    def page_frame(self) -> PageFrame | None:
        """The message as a page's views read it; None when its bytes do not decode."""
        if self._page is None and not self._failed:
            try:
                self._page = to_page(self.channel.topic, self.channel.type_name, self.payload)
            except Exception:  # bytes that are not the advertised type: nothing to show
                self._failed = True
        return self._page

    def fields_frame(self) -> str | None:
        """Every field of the message with its arrival time (the plot's form); None when its
        bytes do not decode."""
        if self._fields is None and not self._failed:
            try:
                self._fields = to_fields(
                    self.channel.topic, self.channel.type_name, self.payload, self.stamp_ns
                )
            except Exception:  # bytes that are not the advertised type: nothing to show
                self._failed = True
        return self._fields


class Source(Protocol):
    """The ROS side of the hub."""

    def definition(self, type_name: str) -> str | None:
        """The ``.msg`` text of a type (with its dependencies); None for an unknown type."""

    def subscribe(self, endpoint: Endpoint) -> None:
        """Start receiving ``endpoint``'s topic (replacing a subscription with other QoS)."""

    def unsubscribe(self, topic: str) -> None:
        """Stop receiving ``topic``."""

    def acquire_publisher(self, topic: str, type_name: str) -> None:
        """Make sure a publisher of ``type_name`` on ``topic`` exists."""

    def release_publisher(self, topic: str, type_name: str) -> None:
        """The publisher is no longer needed."""

    def publish(self, topic: str, type_name: str, payload: bytes) -> None:
        """Publish CDR bytes with an acquired publisher."""

    def call_service(
        self, service: str, type_name: str, request: Any, reply: Callable[[Any, str | None], None]
    ) -> None:
        """Call ``service`` with a ``type_name`` request message; ``reply(response, error)``
        runs later on the hub's thread (``error`` None on success)."""


class GraphWatcher(Protocol):
    """A client that shows the node graph."""

    def graph(self, model: dict[str, Any]) -> None:
        """The graph as :func:`.graph_view.describe_graph` describes it, after each change."""


class Session(Protocol):
    """A connected client, as the hub sees it."""

    def advertise(self, channels: list[Channel]) -> None:
        """Channels appeared."""

    def unadvertise(self, channels: list[Channel]) -> None:
        """Channels went away."""

    def deliver(self, message: Message) -> None:
        """A message of a topic this session wants."""

    def sliders(self, topic: str | None) -> None:
        """The joint slider topic of a running joint_state_publisher_gui (None: none runs)."""


@dataclass
class RateMeter:
    """Messages a second over the last :data:`RATE_WINDOW` seconds."""

    arrivals: deque[float] = field(default_factory=lambda: deque(maxlen=2000))

    def tick(self, now: float) -> None:
        """A message arrived at ``now`` (monotonic seconds)."""
        self.arrivals.append(now)

    def rate(self, now: float) -> float:
        """The rate now (from the intervals between the messages of the window, as ``ros2
        topic hz`` does); 0 when fewer than two messages arrived in the window."""
        while self.arrivals and now - self.arrivals[0] > RATE_WINDOW:
            self.arrivals.popleft()
        if len(self.arrivals) < 2:
            return 0.0
        return (len(self.arrivals) - 1) / max(self.arrivals[-1] - self.arrivals[0], 1e-6)


class Hub:
    """Channels, clients and lazy subscriptions."""

    def __init__(self, source: Source, catalog: AssetCatalog | None = None) -> None:
        self.source = source
        self.catalog = catalog or AssetCatalog()
        self.channels: dict[str, Channel] = {}
        self.sessions: set[Session] = set()
        self.slider_topic: str | None = None
        self._endpoints: dict[str, Endpoint] = {}
        self._ids: dict[tuple[str, str], int] = {}
        self._wanted: dict[str, set[Session]] = {}
        self._subscribed: dict[str, Endpoint] = {}
        self._latched: dict[str, deque[Message]] = {}
        self._meters: dict[str, RateMeter] = {}
        self._publishers: dict[tuple[str, str], set[Session]] = {}
        self._graph: dict[str, Any] | None = None
        self._graph_watchers: set[GraphWatcher] = set()

    # -- clients -----------------------------------------------------------------------------

    def join(self, session: Session) -> None:
        """A client connected: tell it every channel and the slider topic."""
        self.sessions.add(session)
        session.advertise(list(self.channels.values()))
        session.sliders(self.slider_topic)

    def leave(self, session: Session) -> None:
        """A client went away: drop its wishes and its publishers."""
        self.sessions.discard(session)
        for topic in [t for t, who in self._wanted.items() if session in who]:
            self.unwant(session, topic)
        for key in [k for k, who in self._publishers.items() if session in who]:
            self.release_publisher(session, *key)

    def want(self, session: Session, topic: str) -> None:
        """``session`` shows ``topic``: subscribe in ROS if nobody did; latched history now."""
        who = self._wanted.setdefault(topic, set())
        if session in who:
            return
        who.add(session)
        if topic in self._subscribed:
            for message in list(self._latched.get(topic, ())):
                session.deliver(message)
        else:
            self._subscribe(topic)

    def unwant(self, session: Session, topic: str) -> None:
        """``session`` no longer shows ``topic``; the last one to go unsubscribes in ROS."""
        who = self._wanted.get(topic)
        if who is None or session not in who:
            return
        who.discard(session)
        if not who:
            del self._wanted[topic]
            if self._subscribed.pop(topic, None) is not None:
                self.source.unsubscribe(topic)
            self._latched.pop(topic, None)
            self._meters.pop(topic, None)

    def history(self, topic: str) -> list[Message]:
        """The kept messages of a latched topic (for a client that wants them in a new form)."""
        return list(self._latched.get(topic, ()))

    def watch_graph(self, watcher: GraphWatcher, on: bool) -> None:
        """Start (the graph now, then after each change) or stop telling ``watcher`` the graph."""
        if not on:
            self._graph_watchers.discard(watcher)
            return
        self._graph_watchers.add(watcher)
        if self._graph is not None:
            watcher.graph(self._graph)

    def nodes_changed(self, model: dict[str, Any]) -> None:
        """The node graph changed (nodes, topics, services or actions): tell who shows it."""
        if model == self._graph:
            return
        self._graph = model
        for watcher in list(self._graph_watchers):
            watcher.graph(model)

    def wanted(self) -> list[str]:
        """The topics some client wants, sorted."""
        return sorted(self._wanted)

    def subscribed(self) -> list[str]:
        """The topics subscribed in ROS now, sorted."""
        return sorted(self._subscribed)

    # -- publishing for clients --------------------------------------------------------------

    def acquire_publisher(self, session: Session, topic: str, type_name: str) -> None:
        """``session`` will publish ``type_name`` on ``topic``."""
        who = self._publishers.setdefault((topic, type_name), set())
        if not who:
            self.source.acquire_publisher(topic, type_name)
        who.add(session)

    def release_publisher(self, session: Session, topic: str, type_name: str) -> None:
        """``session`` is done publishing on ``topic``."""
        who = self._publishers.get((topic, type_name))
        if who is None or session not in who:
            return
        who.discard(session)
        if not who:
            del self._publishers[(topic, type_name)]
            self.source.release_publisher(topic, type_name)

    def publish(self, session: Session, topic: str, type_name: str, payload: bytes) -> None:
        """Publish CDR bytes for ``session`` (which acquired the publisher)."""
        self.acquire_publisher(session, topic, type_name)
        self.source.publish(topic, type_name, payload)

    # -- from ROS ----------------------------------------------------------------------------

    def graph_changed(self, endpoints: list[Endpoint], slider_topic: str | None) -> None:
        """The topics with publishers now: advertise new ones, unadvertise gone ones, and
        subscribe wanted topics that became available (or changed QoS)."""
        current = {e.topic: e for e in endpoints}
        gone = [c for t, c in self.channels.items() if t not in current]
        gone += [
            c
            for t, c in self.channels.items()
            if t in current and current[t].type_name != c.type_name
        ]
        for channel in gone:
            del self.channels[channel.topic]
        added = []
        for topic, endpoint in current.items():
            if topic in self.channels:
                self.channels[topic].latched = endpoint.latched
                continue
            definition = self.source.definition(endpoint.type_name)
            if definition is None:
                continue
            key = (topic, endpoint.type_name)
            channel_id = self._ids.setdefault(key, len(self._ids) + 1)
            channel = Channel(channel_id, topic, endpoint.type_name, definition, endpoint.latched)
            self.channels[topic] = channel
            added.append(channel)
        self._endpoints = {t: e for t, e in current.items() if t in self.channels}
        for session in list(self.sessions):
            if gone:
                session.unadvertise(gone)
            if added:
                session.advertise(added)
        for topic in list(self._wanted):
            offered = self._endpoints.get(topic)
            if offered is not None and self._subscribed.get(topic) != offered:
                self._subscribe(topic)
        if slider_topic != self.slider_topic:
            self.slider_topic = slider_topic
            for session in list(self.sessions):
                session.sliders(slider_topic)

    def _subscribe(self, topic: str) -> None:
        endpoint = self._endpoints.get(topic)
        if endpoint is None:
            return  # not published (yet): subscribed when it appears
        self._subscribed[topic] = endpoint
        self._latched.pop(topic, None)
        self.source.subscribe(endpoint)

    def receive(self, topic: str, payload: bytes, stamp_ns: int) -> None:
        """A message arrived from ROS: keep it if latched, hand it to who wants it."""
        channel = self.channels.get(topic)
        who = self._wanted.get(topic)
        if channel is None or not who or topic not in self._subscribed:
            return  # a late message of a topic nobody wants any more
        self._meters.setdefault(topic, RateMeter()).tick(time.monotonic())
        message = Message(channel, payload, stamp_ns)
        if channel.latched:
            self._latched.setdefault(topic, deque(maxlen=LATCHED_HISTORY)).append(message)
        if channel.type_name == "std_msgs/msg/String" and b"<robot" in payload:
            self._note_description(payload)
        for session in list(who):
            session.deliver(message)

    def _note_description(self, payload: bytes) -> None:
        """Let clients fetch the meshes a robot description names."""
        try:
            text = str(deserialize(payload, "std_msgs/msg/String").data)
        except Exception:  # not a valid String after all: it names nothing
            return
        self.catalog.note_description(text)

    def rates(self) -> dict[str, float]:
        """Messages a second of every subscribed topic, measured over the last seconds."""
        now = time.monotonic()
        return {t: round(m.rate(now), 2) for t, m in self._meters.items()}
