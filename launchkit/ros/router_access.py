"""Whether a router answers at an endpoint, and whether this user may join it.

On a shared machine any user can listen on a free port first; a launchkit process that joined
such a listener would show that user every topic and let it call every service. So before a
process joins a router on this machine it looks up the listening socket's owner
(:mod:`launchkit.ros.port_owner`) and refuses another user's, unless that user is listed in
``$LAUNCHKIT_ROUTER_TRUSTED_USERS``. A router on another machine cannot be checked this way.
"""

from __future__ import annotations

import os
import socket

from launchkit.envvars import ROUTER, ROUTER_TRUSTED_USERS
from launchkit.errors import RuntimeLaunchError
from launchkit.ros.endpoints import host_port, is_loopback
from launchkit.ros.port_owner import Listener, find_listener, proc_available


class ForeignRouterError(RuntimeLaunchError):
    """The router port on this machine belongs to another user."""


def _trusted_uids() -> set[int]:
    uids = {os.getuid()}
    for item in os.environ.get(ROUTER_TRUSTED_USERS, "").split(","):
        item = item.strip()
        if item.isdigit():
            uids.add(int(item))
        elif item:
            import pwd

            try:
                uids.add(pwd.getpwnam(item).pw_uid)
            except KeyError:
                pass  # an unknown name trusts nobody
    return uids


def check_owner(listener: Listener, endpoint: str) -> None:
    """Raise :class:`ForeignRouterError` if ``listener`` belongs to an untrusted user."""
    if listener.uid in _trusted_uids():
        return
    raise ForeignRouterError(
        f"the ROS router port {endpoint} is held by another user "
        f"({listener.user}, uid {listener.uid}): refusing to join it, since whoever runs it "
        "could read every topic and command your robot",
        hint=f"use another port (--router, ${ROUTER}), or, if you trust that user, "
        f"{ROUTER_TRUSTED_USERS}={listener.user}",
    )


def tcp_answers(endpoint: str, timeout: float = 0.2) -> bool:
    """Whether something accepts TCP connections at ``endpoint``."""
    host, port = host_port(endpoint)
    try:
        with socket.create_connection((host, port), timeout=timeout):
            return True
    except OSError:
        return False


def router_answers(endpoint: str) -> bool:
    """Whether a router this user may join listens at ``endpoint``; raises
    :class:`ForeignRouterError` when one listens there that belongs to another user."""
    host, port = host_port(endpoint)
    listener = find_listener(host, port)
    if listener is not None:
        check_owner(listener, endpoint)
        return True
    if is_loopback(endpoint) and proc_available():
        return False  # the kernel's table is the whole truth for this machine's loopback
    return tcp_answers(endpoint)
