"""Router endpoints (``tcp/HOST:PORT``): the default, validation, host and port.

Kept free of Zenoh so that the commands that only look at a router (``launchkit router
status``) and the shared router's start-up do not load it.
"""

from __future__ import annotations

import ipaddress
import os

from launchkit.envvars import ROUTER
from launchkit.errors import UserError

DEFAULT_ROUTER = "tcp/127.0.0.1:7447"
PROTOCOLS = ("tcp", "udp", "tls", "quic")


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
    if not sep or proto not in PROTOCOLS or not colon or not host:
        raise EndpointError(f"invalid router endpoint {endpoint!r}", expected="tcp/HOST:PORT")
    if not port.isdigit() or not 0 < int(port) < 65536:
        raise EndpointError(f"invalid port in router endpoint {endpoint!r}", expected="1..65535")
    return endpoint


def host_port(endpoint: str) -> tuple[str, int]:
    """(host, port) of ``proto/HOST:PORT`` (IPv6 brackets removed)."""
    address = endpoint.partition("/")[2]
    host, _, port = address.rpartition(":")
    return host.strip("[]"), int(port)


def is_loopback(endpoint: str) -> bool:
    """Whether ``endpoint`` is a TCP endpoint on this machine's loopback interface."""
    host, _ = host_port(endpoint)
    if endpoint.partition("/")[0] != "tcp":
        return False
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False
