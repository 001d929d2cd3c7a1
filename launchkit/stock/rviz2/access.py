"""Who may use the viewer server: the ``Host`` and ``Origin`` checks of every request.

A web page on any site can open a WebSocket to ``127.0.0.1``; the browser then sends the page's
``Origin``, and only the server can refuse it. The rules:

- **Origin** (WebSocket handshakes): accepted when it is a loopback origin (``http://localhost``,
  ``http://127.0.0.1:8000``, ``http://[::1]``, any port, http or https), when it is this
  server's own origin (the page it serves, reached through an allowed ``Host``), when it is
  listed in ``allowed_origins``, or when ``allowed_origins`` holds ``*``. A request without an
  ``Origin`` comes from a program, not a web page (browsers always send one), and is accepted.
  ``Origin: null`` (sandboxed frames, ``file://`` pages) is refused.
- **Host** (every request, pages and WebSockets): against DNS rebinding, where a site's own
  name resolves to 127.0.0.1 and its pages become "same origin" with this server, the ``Host``
  header must name a loopback address, the address the server is bound to, or the host of an
  allowed origin. A server bound to every interface (``0.0.0.0``) also accepts IP addresses
  and this machine's host name.
"""

from __future__ import annotations

import ipaddress
import socket
from collections.abc import Iterable
from urllib.parse import urlsplit

LOOPBACK_NAMES = {"localhost", "localhost.localdomain", "ip6-localhost"}
ANY_ORIGIN = "*"


def _is_loopback(host: str) -> bool:
    host = host.lower().rstrip(".")
    if host in LOOPBACK_NAMES or host.endswith(".localhost"):
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


def _is_ip(host: str) -> bool:
    try:
        ipaddress.ip_address(host)
    except ValueError:
        return False
    return True


def split_host(value: str) -> str:
    """The host of a ``Host`` header value (``127.0.0.1:8765`` -> ``127.0.0.1``, ``[::1]:80``
    -> ``::1``), lower case; "" when it cannot be read."""
    value = value.strip().lower()
    if value.startswith("["):
        end = value.find("]")
        return value[1:end] if end > 0 else ""
    if value.count(":") == 1:
        value = value.split(":", 1)[0]
    return value


def origin_host(origin: str) -> str | None:
    """The host of an origin such as ``http://127.0.0.1:8765``; None when it is not http(s)."""
    try:
        parts = urlsplit(origin)
    except ValueError:
        return None
    if parts.scheme not in ("http", "https") or not parts.hostname:
        return None
    return parts.hostname.lower()


class AccessPolicy:
    """The ``Host`` and ``Origin`` rules for a server bound to ``address``."""

    def __init__(self, address: str, allowed_origins: Iterable[str] = ()) -> None:
        self.address = address
        self.allowed_origins = [o.strip().rstrip("/") for o in allowed_origins if o.strip()]
        self.any_origin = ANY_ORIGIN in self.allowed_origins
        self._wildcard = address in ("", "0.0.0.0", "::")
        self._hosts = {split_host(address)} if address and not self._wildcard else set()
        for origin in self.allowed_origins:
            host = origin_host(origin)
            if host:
                self._hosts.add(host)
        if self._wildcard:
            name = socket.gethostname().lower()
            self._hosts |= {name, f"{name}.local"}

    @property
    def loopback_only(self) -> bool:
        """Whether the server listens on a loopback address only."""
        return not self._wildcard and _is_loopback(split_host(self.address))

    def host_allowed(self, host_header: str | None) -> bool:
        """Whether a request with this ``Host`` header may be served."""
        if not host_header:
            return False
        host = split_host(host_header)
        if not host:
            return False
        if _is_loopback(host) or host in self._hosts:
            return True
        return self._wildcard and _is_ip(host)

    def origin_allowed(self, origin: str | None, host_header: str | None) -> bool:
        """Whether a WebSocket handshake with this ``Origin`` (None: no header) may proceed."""
        if origin is None:
            return True
        origin = origin.strip().rstrip("/")
        if self.any_origin or origin in self.allowed_origins:
            return True
        host = origin_host(origin)
        if host is None:  # "null", file://, chrome-extension://...
            return False
        if _is_loopback(host):
            return True
        # the page this server serves, opened through an allowed Host (a LAN address, say)
        same = urlsplit(origin).netloc.lower() == (host_header or "").strip().lower()
        return same and self.host_allowed(host_header)
