"""The Zenoh router a launch hosts (or joins, when one already listens at the endpoint)."""

from __future__ import annotations

import socket
from dataclasses import dataclass, field
from typing import Any

from launchkit.errors import RuntimeLaunchError
from launchkit.ros.session import (
    close_session,
    host_port,
    open_session,
    router_config,
    router_endpoint,
)


@dataclass
class RouterHandle:
    """A running router: ``endpoint``, whether this process ``hosted`` it, and ``close()``."""

    endpoint: str
    hosted: bool
    _session: Any = field(default=None, repr=False)

    def close(self) -> None:
        """Stop the router if this process hosts it (joined routers are left alone)."""
        if self._session is not None:
            close_session(self._session)
            self._session = None


def is_listening(endpoint: str, timeout: float = 0.2) -> bool:
    """Whether something accepts TCP connections at ``endpoint``."""
    host, port = host_port(endpoint)
    try:
        with socket.create_connection((host, port), timeout=timeout):
            return True
    except OSError:
        return False


def start_router(endpoint: str | None = None) -> RouterHandle:
    """Start a router at ``endpoint`` (default ``$LAUNCHKIT_ROUTER`` or tcp/127.0.0.1:7447).

    If a router already listens there, join it instead (``hosted`` is False).
    """
    endpoint = router_endpoint(endpoint)
    if is_listening(endpoint):
        return RouterHandle(endpoint, hosted=False)
    try:
        session = open_session(router_config(endpoint))
    except Exception as exc:  # zenoh raises a bare ZError
        if is_listening(endpoint):  # lost a race with another launcher: join it
            return RouterHandle(endpoint, hosted=False)
        raise RuntimeLaunchError(f"cannot start the ROS router at {endpoint}: {exc}") from None
    return RouterHandle(endpoint, hosted=True, _session=session)
