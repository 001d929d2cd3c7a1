"""One Foxglove client (the Foxglove app, Lichtblick, foxglove_bridge clients).

The Foxglove WebSocket protocol v1, under either subprotocol name (``foxglove.websocket.v1``,
which Lichtblick and older Foxglove apps ask for, or ``foxglove.sdk.v1``, the current apps'):

- server info with the capabilities ``clientPublish`` and ``assets``, ``cdr`` and ``json``
  client encodings, and ``ROS_DISTRO: jazzy`` (Foxglove then offers ROS 2 message types);
- every topic with publishers advertised as a channel (``cdr`` messages, ``ros2msg`` schemas);
- ``subscribe``/``unsubscribe``: the hub subscribes in ROS while any client wants a topic, and a
  latched topic's kept messages are sent at once to a client that subscribes to it;
- ``advertise``/``unadvertise`` and client message data (``clientPublish``): what Foxglove's
  teleop panel uses to drive; messages in ``cdr`` are checked to decode, ``json`` ones are built
  field by field;
- ``fetchAsset`` for the meshes the robot description names.
"""

from __future__ import annotations

import json
import struct
import time
from collections.abc import Awaitable, Callable
from typing import Any

from launchkit.ros.message_data import build
from launchkit.ros.msgs import MessageTypeError, deserialize, normalize_type_name, serialize
from launchkit.stock.rviz2.hub import Channel, Hub, Message
from launchkit.stock.rviz2.outbox import Frame, Outbox

SUBPROTOCOLS = ("foxglove.sdk.v1", "foxglove.websocket.v1")
MESSAGE_DATA = 0x01
FETCH_ASSET_RESPONSE = 0x04
CLIENT_MESSAGE_DATA = 0x01
INFO, WARNING, ERROR = 0, 1, 2
_CONFLATED = ("sensor_msgs/msg/Image", "sensor_msgs/msg/CompressedImage")


class ProtocolError(Exception):
    """A client message that cannot be served; its text goes back as an error status."""


class FoxgloveSession:
    """The server's side of one Foxglove connection."""

    def __init__(
        self, hub: Hub, send: Callable[[Frame], Awaitable[None]], name: str, session_id: str
    ) -> None:
        self.hub = hub
        self.outbox = Outbox(send)
        self._name = name
        self._session_id = session_id
        self._subscriptions: dict[int, Channel] = {}
        self._by_topic: dict[str, int] = {}
        self._client_channels: dict[int, tuple[str, str, str]] = {}  # topic, type, encoding

    # -- lifecycle ---------------------------------------------------------------------------

    def start(self) -> None:
        """Send server info and the channels."""
        info = {
            "op": "serverInfo",
            "name": self._name,
            "capabilities": ["clientPublish", "assets"],
            "supportedEncodings": ["cdr", "json"],
            "metadata": {"ROS_DISTRO": "jazzy"},
            "sessionId": self._session_id,
        }
        self.outbox.put(json.dumps(info))
        self.hub.join(self)

    def close(self) -> None:
        """The connection ended."""
        self.hub.leave(self)

    # -- from the hub ------------------------------------------------------------------------

    def advertise(self, channels: list[Channel]) -> None:
        """Channels appeared (one message, however many)."""
        self.outbox.put(
            json.dumps(
                {
                    "op": "advertise",
                    "channels": [
                        {
                            "id": c.id,
                            "topic": c.topic,
                            "encoding": "cdr",
                            "schemaName": c.type_name,
                            "schema": c.definition,
                            "schemaEncoding": "ros2msg",
                        }
                        for c in channels
                    ],
                }
            )
        )

    def unadvertise(self, channels: list[Channel]) -> None:
        """Channels went away; subscriptions to them end (the client subscribes again)."""
        ids = {c.id for c in channels}
        for sub_id, channel in list(self._subscriptions.items()):
            if channel.id in ids:
                self._drop(sub_id)
        self.outbox.put(json.dumps({"op": "unadvertise", "channelIds": sorted(ids)}))

    def deliver(self, message: Message) -> None:
        """Message data for this client's subscription to the message's channel."""
        sub_id = self._by_topic.get(message.channel.topic)
        if sub_id is None:
            return
        head = struct.pack("<BIQ", MESSAGE_DATA, sub_id, message.stamp_ns)
        key = f"sub{sub_id}" if message.channel.type_name in _CONFLATED else None
        self.outbox.put(head + message.payload, key)

    def sliders(self, topic: str | None) -> None:
        """Foxglove has its own joint panels."""

    # -- from the client ---------------------------------------------------------------------

    def handle(self, frame: Frame) -> None:
        """One frame from the client; a bad one gets an error status, never a disconnect."""
        try:
            if isinstance(frame, str):
                self._handle_json(frame)
            else:
                self._handle_binary(frame)
        except ProtocolError as error:
            self.status(ERROR, str(error))

    def status(self, level: int, message: str) -> None:
        """Tell the client something (shown in Foxglove's problems panel)."""
        self.outbox.put(json.dumps({"op": "status", "level": level, "message": message}))

    def _handle_json(self, text: str) -> None:
        try:
            request = json.loads(text)
        except ValueError:
            raise ProtocolError("a text message must be JSON") from None
        if not isinstance(request, dict):
            raise ProtocolError("a text message must be a JSON object with an 'op'")
        op = request.get("op")
        handlers: dict[str, Callable[[dict[str, Any]], None]] = {
            "subscribe": self._subscribe,
            "unsubscribe": self._unsubscribe,
            "advertise": self._client_advertise,
            "unadvertise": self._client_unadvertise,
            "fetchAsset": self._fetch_asset,
        }
        handler = handlers.get(str(op))
        if handler is None:
            self.status(WARNING, f"operation {op!r} is not supported by this server")
            return
        handler(request)

    def _subscribe(self, request: dict[str, Any]) -> None:
        by_id = {c.id: c for c in self.hub.channels.values()}
        for entry in _list(request, "subscriptions"):
            sub_id, channel_id = _int(entry, "id"), _int(entry, "channelId")
            channel = by_id.get(channel_id)
            if channel is None:
                self.status(ERROR, f"cannot subscribe: unknown channel {channel_id}")
            elif sub_id in self._subscriptions:
                self.status(ERROR, f"cannot subscribe: subscription id {sub_id} is in use")
            elif channel.topic in self._by_topic:
                self.status(ERROR, f"cannot subscribe: already subscribed to {channel.topic}")
            else:
                self._subscriptions[sub_id] = channel
                self._by_topic[channel.topic] = sub_id
                self.hub.want(self, channel.topic)

    def _unsubscribe(self, request: dict[str, Any]) -> None:
        for sub_id in _list(request, "subscriptionIds"):
            if not isinstance(sub_id, int) or sub_id not in self._subscriptions:
                self.status(WARNING, f"cannot unsubscribe: no subscription {sub_id!r}")
                continue
            self._drop(sub_id)

    def _drop(self, sub_id: int) -> None:
        channel = self._subscriptions.pop(sub_id)
        self._by_topic.pop(channel.topic, None)
        self.hub.unwant(self, channel.topic)

    def _client_advertise(self, request: dict[str, Any]) -> None:
        for entry in _list(request, "channels"):
            channel_id, topic = _int(entry, "id"), entry.get("topic")
            encoding, schema_name = entry.get("encoding"), entry.get("schemaName")
            if not isinstance(topic, str) or not topic.startswith("/"):
                raise ProtocolError(f"client channel {channel_id}: topic must be an absolute name")
            if encoding not in ("cdr", "json"):
                raise ProtocolError(
                    f"client channel {channel_id}: encoding {encoding!r} is not supported "
                    "(expected cdr or json)"
                )
            try:
                type_name = normalize_type_name(str(schema_name))
            except MessageTypeError as error:
                raise ProtocolError(f"client channel {channel_id}: {error}") from None
            if self.hub.source.definition(type_name) is None:
                raise ProtocolError(f"client channel {channel_id}: unknown type {schema_name!r}")
            if channel_id in self._client_channels:
                self._release(channel_id)
            self._client_channels[channel_id] = (topic, type_name, str(encoding))
            self.hub.acquire_publisher(self, topic, type_name)

    def _client_unadvertise(self, request: dict[str, Any]) -> None:
        for channel_id in _list(request, "channelIds"):
            if isinstance(channel_id, int) and channel_id in self._client_channels:
                self._release(channel_id)

    def _release(self, channel_id: int) -> None:
        topic, type_name, _ = self._client_channels.pop(channel_id)
        if (topic, type_name) not in {(t, n) for t, n, _ in self._client_channels.values()}:
            self.hub.release_publisher(self, topic, type_name)

    def _handle_binary(self, data: bytes) -> None:
        if len(data) < 5 or data[0] != CLIENT_MESSAGE_DATA:
            raise ProtocolError("unsupported binary message (expected client message data)")
        (channel_id,) = struct.unpack_from("<I", data, 1)
        advertised = self._client_channels.get(channel_id)
        if advertised is None:
            raise ProtocolError(f"message on client channel {channel_id}, which is not advertised")
        topic, type_name, encoding = advertised
        payload = bytes(data[5:])
        try:
            if encoding == "json":
                payload = serialize(build(type_name, json.loads(payload), type_name), type_name)
            else:
                deserialize(payload, type_name)  # refuse bytes that are not the type
        except Exception as error:
            raise ProtocolError(
                f"dropped a message for {topic}: not a valid {type_name} ({error})"
            ) from None
        self.hub.publish(self, topic, type_name, payload)

    def _fetch_asset(self, request: dict[str, Any]) -> None:
        request_id, uri = _int(request, "requestId"), request.get("uri")
        found = self.hub.catalog.read(uri) if isinstance(uri, str) else None
        if found is None:
            error = f"asset {uri!r} is not a file the robot description names".encode()
            head = struct.pack("<BIBI", FETCH_ASSET_RESPONSE, request_id, 1, len(error))
            self.outbox.put(head + error)
            return
        head = struct.pack("<BIBI", FETCH_ASSET_RESPONSE, request_id, 0, 0)
        self.outbox.put(head + found[0])


def _list(request: dict[str, Any], key: str) -> list[Any]:
    value = request.get(key)
    if not isinstance(value, list):
        raise ProtocolError(f"{request.get('op')}: '{key}' must be a list")
    return value


def _int(entry: Any, key: str) -> int:
    value = entry.get(key) if isinstance(entry, dict) else None
    if not isinstance(value, int) or isinstance(value, bool) or not 0 <= value < 2**32:
        raise ProtocolError(f"'{key}' must be an unsigned 32-bit integer, got {value!r}")
    return value


def session_id() -> str:
    """A new server session id (tells a reconnecting client it met a new server)."""
    return str(time.time_ns())
