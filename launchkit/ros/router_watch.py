"""The owner of the router port, checked again each time a session links to a router.

A session retries its router for ever, so when this user's router dies and another local user
starts one on the same port, the session links to theirs by itself. The first join was checked
(:mod:`launchkit.ros.router_access`); every later link is checked the same way, from Zenoh's
transport events: the callback runs as the link is made, before the other side has declared
anything to route to, so the context can stop delivering (:attr:`Context.refused
<launchkit.ros.context.Context.refused>`) before a message crosses it. A router on another
machine cannot be checked this way (nor on first join).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import zenoh

from launchkit.ros.endpoints import host_port, is_loopback
from launchkit.ros.port_owner import find_listener, proc_available
from launchkit.ros.router_access import ForeignRouterError, check_owner


def watch_router(
    session: zenoh.Session, endpoint: str, refuse: Callable[[ForeignRouterError], None]
) -> Any:
    """Call ``refuse(error)`` whenever ``session`` links to a router at ``endpoint`` that
    belongs to another (untrusted) user; the listener to undeclare, or None where the owner
    cannot be known."""
    if not is_loopback(endpoint) or not proc_available():
        return None
    host, port = host_port(endpoint)

    def on_event(event: zenoh.TransportEvent) -> None:  # a Zenoh thread, as the link is made
        if event.kind != zenoh.SampleKind.PUT or event.transport.whatami != zenoh.WhatAmI.ROUTER:
            return
        listener = find_listener(host, port)
        if listener is None:
            return
        try:
            check_owner(listener, endpoint)
        except ForeignRouterError as error:
            refuse(error)

    return session.info.declare_transport_events_listener(on_event, history=False)
