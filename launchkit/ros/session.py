"""Zenoh sessions with launchkit's explicit, loopback-only configuration.

Zenoh's defaults listen on every interface and scout by multicast; every session launchkit
opens gets this configuration instead. Peers connect to the router named by ``LAUNCHKIT_ROUTER``
(default ``tcp/127.0.0.1:7447``), listen on loopback only, and learn each other by gossip so
data then flows peer to peer, as in rmw_zenoh.

rmw_zenoh's configuration variables work the same way here (rmw_zenoh 0.2.x,
``src/detail/zenoh_config.cpp:_get_z_config``): ``ZENOH_SESSION_CONFIG_URI`` /
``ZENOH_ROUTER_CONFIG_URI`` name a JSON5 file that replaces launchkit's configuration, and
``ZENOH_CONFIG_OVERRIDE='key=json5;key=json5'`` then changes single keys of whichever
configuration was chosen.
"""

from __future__ import annotations

import json
import os
import threading
import time
from typing import Any, cast

import zenoh

from launchkit.errors import UserError
from launchkit.ros.endpoints import (
    DEFAULT_ROUTER,
    EndpointError,
    host_port,
    router_endpoint,
    validate_endpoint,
)
from launchkit.ros.federation import RouterOptions, RouterOptionsError
from launchkit.ros.logging import get_logger

SESSION_CONFIG_ENV = "ZENOH_SESSION_CONFIG_URI"
ROUTER_CONFIG_ENV = "ZENOH_ROUTER_CONFIG_URI"
CONFIG_OVERRIDE_ENV = "ZENOH_CONFIG_OVERRIDE"
LOOPBACK_LISTEN = "tcp/127.0.0.1:0"


class ZenohConfigError(UserError):
    """A Zenoh configuration file named by ``ZENOH_*_CONFIG_URI`` that cannot be used."""


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
    """A node's configuration: peer, connect to the router, listen on loopback only.

    ``$ZENOH_SESSION_CONFIG_URI`` replaces it with a file, and ``$ZENOH_CONFIG_OVERRIDE``
    changes keys of either, as rmw_zenoh does.
    """
    config = _config_file(SESSION_CONFIG_ENV)
    if config is None:
        config = _base_config("peer")
        config.insert_json5("connect/endpoints", json.dumps([router_endpoint(endpoint)]))
        config.insert_json5("listen/endpoints", json.dumps([LOOPBACK_LISTEN]))
    return apply_overrides(config)


CLIENT_CONNECT_TIMEOUT_MS = 10_000  # a command-line tool's open() fails after this long


def client_config(endpoint: str | None = None) -> zenoh.Config:
    """A command-line tool's configuration: a client of the router, whose ``open()`` returns
    only once connected (or fails).

    A client's queries are answered by the router from everything it knows, so one liveliness
    query lists the whole graph. A peer's first query may leave before its routes are set up
    and come back empty or partial (measured: about 1 in 3 right after ``open()``), which made
    the tools ask again until two answers agreed. ``$ZENOH_SESSION_CONFIG_URI`` and
    ``$ZENOH_CONFIG_OVERRIDE`` apply as for a node, the mode then being client.
    """
    config = _config_file(SESSION_CONFIG_ENV)
    if config is None:
        config = _base_config("client")
        config.insert_json5("connect/endpoints", json.dumps([router_endpoint(endpoint)]))
    else:
        config.insert_json5("mode", '"client"')
    config.insert_json5("connect/exit_on_failure", "true")
    config.insert_json5("connect/timeout_ms", str(CLIENT_CONNECT_TIMEOUT_MS))
    return apply_overrides(config)


def router_config(endpoint: str, options: RouterOptions | None = None) -> zenoh.Config:
    """The router's configuration: listen on ``endpoint`` only, no multicast scouting; with
    ``options``, also the endpoints, TLS and access control that reach other hosts.

    ``$ZENOH_ROUTER_CONFIG_URI`` replaces it with a file (used as is: ``options`` add their
    endpoints to the file's and set only the keys they name), and ``$ZENOH_CONFIG_OVERRIDE``
    changes keys of either, as rmw_zenoh's router does.
    """
    config = _config_file(ROUTER_CONFIG_ENV)
    from_file = config is not None
    if config is None:
        config = _base_config("router")
        config.insert_json5("listen/endpoints", json.dumps([endpoint]))
        config.insert_json5("connect/endpoints", "[]")
        # a router's open() otherwise spends scouting/delay (500 ms) waiting for scouted peers,
        # even with multicast scouting off: the launch's first node waited for it. Links to
        # other routers (--connect) are made in the background either way.
        config.insert_json5("scouting/delay", "0")
    if options is not None and not options.empty:
        _apply_options(config, endpoint, options, from_file)
    return apply_overrides(config)


def _apply_options(
    config: zenoh.Config, endpoint: str, options: RouterOptions, from_file: bool
) -> None:
    settings = options.settings(endpoint)
    if from_file:  # the file says where the router listens; the options add to its lists
        settings["listen/endpoints"] = list(options.listen)
        for key in ("listen/endpoints", "connect/endpoints"):
            settings[key] = list(dict.fromkeys([*_router_endpoints(config, key), *settings[key]]))
    for key, value in settings.items():
        _insert(config, key, json.dumps(value), "a valid Zenoh setting")
    access = options.access_control()
    if access is not None:
        expected = f"Zenoh's access_control section in {options.access}"
        _insert(config, "access_control", access, expected)


def _router_endpoints(config: zenoh.Config, key: str) -> list[str]:
    """A router's ``listen``/``connect`` endpoints (Zenoh also allows one list per mode)."""
    value = json.loads(config.get_json(key))
    return list(value.get("router", []) if isinstance(value, dict) else value)


def _insert(config: zenoh.Config, key: str, json5: str, expected: str) -> None:
    try:
        config.insert_json5(key, json5)
    except Exception as exc:  # zenoh raises a bare ZError
        message = f"cannot set the router's {key}: {exc}"
        raise RouterOptionsError(message, expected=expected) from None


def _config_file(variable: str) -> zenoh.Config | None:
    """The configuration in the file ``$variable`` names (unset or empty: None)."""
    uri = os.environ.get(variable, "")
    if not uri:
        return None
    try:
        return cast(zenoh.Config, zenoh.Config.from_file(uri))
    except Exception as exc:  # zenoh raises a bare ZError
        raise ZenohConfigError(
            f"{variable}={uri}: not a usable Zenoh configuration file: {exc}",
            expected="a readable JSON5 Zenoh configuration",
        ) from None


def parse_overrides(text: str) -> list[tuple[str, str]]:
    """``key=value;key=value`` as rmw_zenoh splits it: on ``;``, then at the first ``=``.

    A part without ``=`` or with nothing after it is skipped, as rmw_zenoh skips it.
    """
    pairs = []
    for part in text.split(";"):
        key, sep, value = part.partition("=")
        value = value.split("\n", 1)[0]
        if sep and value:
            pairs.append((key, value))
    return pairs


def apply_overrides(config: zenoh.Config) -> zenoh.Config:
    """Insert every ``$ZENOH_CONFIG_OVERRIDE`` pair into ``config``; bad pairs are ignored with a
    warning naming them (rmw_zenoh's behaviour)."""
    for key, value in parse_overrides(os.environ.get(CONFIG_OVERRIDE_ENV, "")):
        try:
            config.insert_json5(key, value)
        except Exception:  # zenoh raises a bare ZError
            get_logger("launchkit.ros").warn(
                f"{CONFIG_OVERRIDE_ENV}: ignored the invalid configuration key-value pair "
                f"({key}, {value})"
            )
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


# re-exported: the endpoint helpers lived here first
__all__ = [
    "DEFAULT_ROUTER",
    "EndpointError",
    "ZenohConfigError",
    "apply_overrides",
    "close_all",
    "close_session",
    "host_port",
    "open_session",
    "parse_overrides",
    "peer_config",
    "router_config",
    "router_endpoint",
    "validate_endpoint",
    "wait_for_router",
]

# zenoh logs transient connection races (two peers dialing each other) at ERROR level; they
# are harmless, so stay quiet unless the user asks with RUST_LOG
zenoh.init_log_from_env_or("off")
