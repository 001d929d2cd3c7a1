"""A service whose callback answers when it chooses: what an action server's services need.

A goal request is answered before the accepted-goal callback runs, and a result request only
when the goal ends, without holding the server's callback group meanwhile.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from launchkit.ros.msgs import deserialize, serialize
from launchkit.ros.services import Service


class DeferredService(Service):
    """Calls ``await callback(request, respond)``; ``respond(response)`` sends the answer, now
    or later (once)."""

    async def _answer(
        self, payload: bytes, reply: Callable[[bytes], None], fail: Callable[[str], None]
    ) -> None:
        try:
            request = deserialize(payload, self.type_name + "_Request")
        except Exception as exc:
            fail(f"invalid {self.type_name} request: {exc}")
            return
        response_type = self.type_name + "_Response"

        def respond(response: Any) -> None:
            reply(serialize(response, response_type))

        await self.callback(request, respond)
