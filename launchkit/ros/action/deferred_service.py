"""A service whose callback answers when it chooses: what an action server's services need.

A goal request is answered before the accepted-goal callback runs, and a result request only
when the goal ends, without holding the server's callback group meanwhile.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from launchkit.ros.msgs import serialize
from launchkit.ros.services import Service


class DeferredService(Service):
    """Calls ``await callback(request, respond)``; ``respond(response)`` sends the answer, now
    or later (once)."""

    async def _respond(
        self, request: Any, reply: Callable[[bytes], None], fail: Callable[[str], None]
    ) -> None:
        response_type = self.type_name + "_Response"

        def respond(response: Any) -> None:
            reply(serialize(response, response_type))

        await self.callback(request, respond)
