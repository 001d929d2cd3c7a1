"""A small Foxglove WebSocket client for tests (``foxglove.sdk.v1`` or ``...websocket.v1``)."""

from __future__ import annotations

import asyncio
import json
import struct
from dataclasses import dataclass, field
from typing import Any

from websockets.asyncio.client import ClientConnection, connect

SUBPROTOCOL = "foxglove.sdk.v1"
MESSAGE_DATA = 0x01


@dataclass
class FoxgloveClient:
    """Connects, records advertised channels, subscribes by topic, collects message payloads."""

    url: str
    subprotocol: str = SUBPROTOCOL
    origin: str | None = None
    channels: dict[str, dict[str, Any]] = field(default_factory=dict)
    subscriptions: dict[int, str] = field(default_factory=dict)
    received: dict[str, list[bytes]] = field(default_factory=dict)
    statuses: list[dict[str, Any]] = field(default_factory=list)
    binary: list[bytes] = field(default_factory=list)
    server_info: dict[str, Any] = field(default_factory=dict)
    _ws: ClientConnection | None = None

    async def __aenter__(self) -> FoxgloveClient:
        self._ws = await connect(
            self.url,
            subprotocols=[self.subprotocol],  # type: ignore[list-item]
            origin=self.origin,  # type: ignore[arg-type]
        )
        return self

    @property
    def ws(self) -> ClientConnection:
        """The connection."""
        assert self._ws is not None
        return self._ws

    async def __aexit__(self, *exc: object) -> None:
        assert self._ws is not None
        await self._ws.close()

    async def _handle_one(self, timeout: float) -> None:
        assert self._ws is not None
        frame = await asyncio.wait_for(self._ws.recv(), timeout)
        if isinstance(frame, str):
            message = json.loads(frame)
            if message["op"] == "serverInfo":
                self.server_info = message
            if message["op"] == "status":
                self.statuses.append(message)
            if message["op"] == "advertise":
                for channel in message["channels"]:
                    self.channels[channel["topic"]] = channel
            if message["op"] == "unadvertise":
                gone = set(message["channelIds"])
                self.channels = {t: c for t, c in self.channels.items() if c["id"] not in gone}
            return
        if frame[0] == MESSAGE_DATA:
            (subscription,) = struct.unpack_from("<I", frame, 1)
            topic = self.subscriptions[subscription]
            self.received.setdefault(topic, []).append(bytes(frame[13:]))
        else:
            self.binary.append(bytes(frame))

    async def wait_for(self, what: str, predicate: Any, deadline_s: float = 10.0) -> None:
        """Handle frames until ``predicate()`` holds; fail naming ``what`` after the deadline."""
        loop = asyncio.get_running_loop()
        end = loop.time() + deadline_s
        while not predicate():
            left = end - loop.time()
            if left <= 0:
                raise AssertionError(
                    f"timed out after {deadline_s} s waiting for {what}; advertised "
                    f"{sorted(self.channels)}, received {sorted(self.received)}"
                )
            try:
                await self._handle_one(left)
            except asyncio.TimeoutError:
                continue

    async def subscribe(self, topics: list[str]) -> None:
        """Subscribe to advertised ``topics`` (waits for their advertisements)."""
        assert self._ws is not None
        await self.wait_for(
            f"advertisements of {topics}", lambda: all(t in self.channels for t in topics)
        )
        subs = []
        for topic in topics:
            sub_id = len(self.subscriptions) + 1
            self.subscriptions[sub_id] = topic
            subs.append({"id": sub_id, "channelId": self.channels[topic]["id"]})
        await self._ws.send(json.dumps({"op": "subscribe", "subscriptions": subs}))

    async def unsubscribe(self, topics: list[str]) -> None:
        """End the subscriptions to ``topics``."""
        ids = [i for i, t in self.subscriptions.items() if t in topics]
        for sub_id in ids:
            del self.subscriptions[sub_id]
        await self.ws.send(json.dumps({"op": "unsubscribe", "subscriptionIds": ids}))

    async def send_json(self, message: dict[str, Any]) -> None:
        """Send one JSON operation."""
        await self.ws.send(json.dumps(message))


def receive_topics(
    url: str, topics: list[str], timeout: float = 20.0, advertised: tuple[str, ...] = ()
) -> FoxgloveClient:
    """Connect to ``url``, wait until ``topics`` (and ``advertised``, not subscribed to) are
    advertised, subscribe to ``topics`` and wait for a message on each; the client, with what
    it received."""

    async def session() -> FoxgloveClient:
        async with FoxgloveClient(url) as client:
            await client.wait_for(
                f"rviz2 to advertise {[*topics, *advertised]}",
                lambda: all(t in client.channels for t in [*topics, *advertised]),
                timeout,
            )
            await client.subscribe(topics)
            await client.wait_for(
                f"messages on {topics}",
                lambda: all(t in client.received for t in topics),
                timeout,
            )
            return client

    return asyncio.run(session())
