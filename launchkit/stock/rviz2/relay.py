"""A Foxglove WebSocket server that relays ROS topics as they are (ros2msg schema, CDR bytes).

Foxglove's server forgets a message once it is sent, so a client that connects late would
never see a latched topic such as ``/robot_description`` or ``/tf_static``. The relay keeps the
last messages of every latched (transient local) topic and sends them again whenever a client
subscribes to it; clients already subscribed may then see them twice, as a ROS transient-local
subscriber may after a reconnect.
"""

from __future__ import annotations

import threading
import time
from collections import deque
from typing import Any

import foxglove
from foxglove.websocket import ChannelView, Client, ServerListener

from launchkit.errors import UserError

#: How many messages of a latched topic are kept for late clients (one per publisher, usually).
LATCHED_HISTORY = 10


class FoxgloveRelay:
    """Serves topics to Foxglove clients on ``host:port``; ``port=0`` picks a free port."""

    def __init__(
        self, host: str = "127.0.0.1", port: int = 8765, name: str = "launchkit rviz2"
    ) -> None:
        self._context = foxglove.Context()
        self._channels: dict[str, Any] = {}
        self._latched: dict[str, deque[tuple[bytes, int]]] = {}
        self._lock = threading.Lock()
        try:
            self._server = foxglove.start_server(
                name=name,
                host=host,
                port=port,
                server_listener=_Listener(self),
                context=self._context,
            )
        except Exception as exc:  # the SDK reports a busy port as a plain RuntimeError
            raise UserError(
                f"cannot serve Foxglove WebSocket on {host}:{port}: {exc}",
                expected="a free port (choose one with --port N)",
            ) from None
        self.host = host

    @property
    def port(self) -> int:
        """The port the server listens on."""
        return int(self._server.port)

    @property
    def url(self) -> str:
        """The WebSocket URL a client connects to."""
        return f"ws://{self.host}:{self.port}"

    def app_url(self) -> str:
        """A link that opens this server in the Foxglove app."""
        return str(self._server.app_url())

    def topics(self) -> list[str]:
        """The topics advertised so far."""
        with self._lock:
            return sorted(self._channels)

    def add_topic(self, topic: str, type_name: str, definition: str, latched: bool) -> None:
        """Advertise ``topic`` of ROS type ``type_name`` (``definition``: its ``.msg`` text)."""
        with self._lock:
            if topic in self._channels:
                if latched:
                    self._latched.setdefault(topic, deque(maxlen=LATCHED_HISTORY))
                return
            schema = foxglove.Schema(name=type_name, encoding="ros2msg", data=definition.encode())
            self._channels[topic] = foxglove.Channel(
                topic, schema=schema, message_encoding="cdr", context=self._context
            )
            if latched:
                self._latched[topic] = deque(maxlen=LATCHED_HISTORY)

    def publish(self, topic: str, data: bytes, log_time_ns: int | None = None) -> None:
        """Send one CDR-encoded message of an advertised topic to its subscribed clients."""
        stamp = time.time_ns() if log_time_ns is None else log_time_ns
        with self._lock:
            channel = self._channels[topic]
            kept = self._latched.get(topic)
            if kept is not None:
                kept.append((data, stamp))
        channel.log(data, log_time=stamp)

    def resend_latched(self, topic: str) -> None:
        """Send the kept messages of a latched ``topic`` again (a client just subscribed)."""
        with self._lock:
            channel = self._channels.get(topic)
            kept = list(self._latched.get(topic, ()))
        for data, stamp in kept:
            if channel is not None:
                channel.log(data, log_time=stamp)

    def close(self) -> None:
        """Stop the server and close every channel."""
        self._server.stop()
        with self._lock:
            for channel in self._channels.values():
                channel.close()
            self._channels.clear()


class _Listener(ServerListener):
    """Re-sends latched topics on subscribe; the SDK wants on_unsubscribe defined too."""

    def __init__(self, relay: FoxgloveRelay) -> None:
        self._relay = relay

    def on_subscribe(self, client: Client, channel: ChannelView) -> None:
        self._relay.resend_latched(channel.topic)

    def on_unsubscribe(self, client: Client, channel: ChannelView) -> None:
        return None
