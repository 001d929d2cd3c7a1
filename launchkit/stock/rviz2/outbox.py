"""What waits to be sent to one client, with a bound, and images that replace their older self.

A client that reads slower than the robot publishes (a browser tab in the background, a slow
link) must not make the server buffer without end. Frames wait in order; a frame put with a
key (one camera's images) replaces the waiting frame of the same key, so a slow client gets
the newest image rather than a backlog; past :data:`LIMIT` waiting frames the oldest go.
"""

from __future__ import annotations

import asyncio
from collections import deque
from collections.abc import Awaitable, Callable

Frame = str | bytes

#: Frames that may wait for one client.
LIMIT = 1000


class Outbox:
    """The frames waiting for one client, sent by :meth:`run` in order."""

    def __init__(self, send: Callable[[Frame], Awaitable[None]], limit: int = LIMIT) -> None:
        self._send = send
        self._limit = limit
        self._frames: deque[list[object]] = deque()  # [key or None, frame]
        self._keyed: dict[str, list[object]] = {}
        self._ready = asyncio.Event()
        self.dropped = 0

    def put(self, frame: Frame, key: str | None = None) -> None:
        """Queue ``frame``; with ``key``, replace the frame of that key still waiting."""
        if key is not None:
            waiting = self._keyed.get(key)
            if waiting is not None:
                waiting[1] = frame
                self.dropped += 1
                return
        entry: list[object] = [key, frame]
        self._frames.append(entry)
        if key is not None:
            self._keyed[key] = entry
        if len(self._frames) > self._limit:
            oldest = self._frames.popleft()
            if oldest[0] is not None:
                self._keyed.pop(str(oldest[0]), None)
            self.dropped += 1
        self._ready.set()

    def __len__(self) -> int:
        return len(self._frames)

    async def run(self) -> None:
        """Send waiting frames until cancelled (or the connection fails)."""
        while True:
            while not self._frames:
                self._ready.clear()
                await self._ready.wait()
            key, frame = self._frames.popleft()
            if key is not None:
                self._keyed.pop(str(key), None)
            assert isinstance(frame, (str, bytes))
            await self._send(frame)
