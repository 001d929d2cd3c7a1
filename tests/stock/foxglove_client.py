"""A small Foxglove WebSocket client for tests (protocol ``foxglove.sdk.v1``)."""

from __future__ import annotations

import asyncio
import json
import re
import struct
from dataclasses import dataclass, field
from typing import Any

from websockets.asyncio.client import ClientConnection, connect

SUBPROTOCOL = "foxglove.sdk.v1"
MESSAGE_DATA = 0x01
UNKNOWN_CHANNEL = re.compile(r"Unknown channel ID: (\d+)")


@dataclass
class FoxgloveClient:
    """Connects, records advertised channels, subscribes by topic, collects message payloads."""

    url: str
    channels: dict[str, dict[str, Any]] = field(default_factory=dict)
    subscriptions: dict[int, str] = field(default_factory=dict)
    received: dict[str, list[bytes]] = field(default_factory=dict)
    _ws: ClientConnection | None = None

    async def __aenter__(self) -> FoxgloveClient:
        self._ws = await connect(self.url, subprotocols=[SUBPROTOCOL])  # type: ignore[list-item]
        return self

    async def __aexit__(self, *exc: object) -> None:
        assert self._ws is not None
        await self._ws.close()

    async def _handle_one(self, timeout: float) -> None:
        assert self._ws is not None
        frame = await asyncio.wait_for(self._ws.recv(), timeout)
        if isinstance(frame, str):
            message = json.loads(frame)
            if message["op"] == "advertise":
                for channel in message["channels"]:
                    self.channels[channel["topic"]] = channel
            unknown = UNKNOWN_CHANNEL.fullmatch(message.get("message", ""))
            if message["op"] == "status" and unknown:
                # foxglove-sdk 0.30 can advertise a channel a moment before it accepts
                # subscriptions to it (status "Unknown channel ID"): subscribe again
                channel_id = int(unknown.group(1))
                topics = [t for t, c in self.channels.items() if c["id"] == channel_id]
                await self.subscribe(topics)
            return
        if frame[0] == MESSAGE_DATA:
            (subscription,) = struct.unpack_from("<I", frame, 1)
            topic = self.subscriptions[subscription]
            self.received.setdefault(topic, []).append(bytes(frame[13:]))

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


def receive_topics(url: str, topics: list[str], timeout: float = 20.0) -> FoxgloveClient:
    """Connect to ``url``, wait until ``topics`` are advertised, subscribe to them and wait for a
    message on each; the client, with what it received."""

    async def session() -> FoxgloveClient:
        async with FoxgloveClient(url) as client:
            await client.wait_for(
                f"rviz2 to advertise {topics}",
                lambda: all(t in client.channels for t in topics),
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
