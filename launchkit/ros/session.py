"""Zenoh sessions with launchkit's explicit, loopback-only configuration.

Zenoh's defaults listen on every interface and scout by multicast; every session launchkit
opens gets this configuration instead. Peers connect to the router named by ``LAUNCHKIT_ROUTER``
(default ``tcp/127.0.0.1:7447``), listen on loopback only, and learn each other by gossip so
data then flows peer to peer, as in rmw_zenoh.
"""

from __future__ import annotations

import json
import os
import threading
import time
from typing import Any, cast

import zenoh

from launchkit.envvars import ROUTER
from launchkit.errors import UserError

DEFAULT_ROUTER = "tcp/127.0.0.1:7447"
LOOPBACK_LISTEN = "tcp/127.0.0.1:0"


class EndpointError(UserError):
    """A malformed router endpoint."""


def router_endpoint(endpoint: str | None = None) -> str:
    """The router endpoint: ``endpoint``, else ``$LAUNCHKIT_ROUTER``, else the default."""
    value = endpoint or os.environ.get(ROUTER) or DEFAULT_ROUTER
    return validate_endpoint(value)


def validate_endpoint(endpoint: str) -> str:
    """``endpoint`` if it looks like ``tcp/HOST:PORT`` (or udp/quic/tls), else an error."""
    proto, sep, address = endpoint.partition("/")
    host, colon, port = address.rpartition(":")
    if not sep or proto not in ("tcp", "udp", "tls", "quic") or not colon or not host:
        raise EndpointError(f"invalid router endpoint {endpoint!r}", expected="tcp/HOST:PORT")
    if not port.isdigit() or not 0 < int(port) < 65536:
        raise EndpointError(f"invalid port in router endpoint {endpoint!r}", expected="1..65535")
    return endpoint


def host_port(endpoint: str) -> tuple[str, int]:
    """(host, port) of ``proto/HOST:PORT`` (IPv6 brackets removed)."""
    address = endpoint.partition("/")[2]
    host, _, port = address.rpartition(":")
    return host.strip("[]"), int(port)


def _base_config(mode: str) -> zenoh.Config:
    config: zenoh.Config = zenoh.Config()
    settings: dict[str, Any] = {
        "mode": mode,
        "scouting/multicast/enabled": False,
        "scouting/gossip/enabled": True,
        "timestamping/enabled": True,
        # nodes must come back after the router restarts: retry quickly, never give up
        "connect/exit_on_failure": False,
        "connect/timeout_ms": -1,
        "connect/retry": {
            "period_init_ms": 50,
            "period_max_ms": 500,
            "period_increase_factor": 2,
        },
    }
    for key, value in settings.items():
        config.insert_json5(key, json.dumps(value))
    return config


def peer_config(endpoint: str | None = None) -> zenoh.Config:
    """A node's configuration: peer, connect to the router, listen on loopback only."""
    uri = os.environ.get("ZENOH_SESSION_CONFIG_URI")
    if uri:
        return cast(zenoh.Config, zenoh.Config.from_file(uri))
    config = _base_config("peer")
    config.insert_json5("connect/endpoints", json.dumps([router_endpoint(endpoint)]))
    config.insert_json5("listen/endpoints", json.dumps([LOOPBACK_LISTEN]))
    return config


def router_config(endpoint: str) -> zenoh.Config:
    """The router's configuration: listen on ``endpoint`` only, no multicast scouting."""
    uri = os.environ.get("ZENOH_ROUTER_CONFIG_URI")
    if uri:
        return cast(zenoh.Config, zenoh.Config.from_file(uri))
    config = _base_config("router")
    config.insert_json5("listen/endpoints", json.dumps([endpoint]))
    config.insert_json5("connect/endpoints", "[]")
    return config


_open_sessions: set[zenoh.Session] = set()
_sessions_lock = threading.Lock()


def open_session(config: zenoh.Config) -> zenoh.Session:
    """Open a session and remember it so :func:`close_all` can close it at exit."""
    session = zenoh.open(config)
    with _sessions_lock:
        _open_sessions.add(session)
    return session


def wait_for_router(session: zenoh.Session, timeout: float) -> bool:
    """Wait until ``session`` is connected to a router (the first queries need it)."""
    deadline = time.monotonic() + timeout
    while not any(True for _ in session.info.routers_zid()):
        if time.monotonic() > deadline:
            return False
        time.sleep(0.001)
    return True


def close_session(session: zenoh.Session) -> None:
    """Close a session opened by :func:`open_session` (idempotent)."""
    with _sessions_lock:
        _open_sessions.discard(session)
    if not session.is_closed():
        session.close()  # type: ignore[no-untyped-call]


def close_all() -> None:
    """Close every session still open (an open advanced subscriber hangs interpreter exit)."""
    with _sessions_lock:
        sessions = list(_open_sessions)
        _open_sessions.clear()
    for session in sessions:
        if not session.is_closed():
            session.close()  # type: ignore[no-untyped-call]


# zenoh logs transient connection races (two peers dialing each other) at ERROR level; they
# are harmless, so stay quiet unless the user asks with RUST_LOG
zenoh.init_log_from_env_or("off")
