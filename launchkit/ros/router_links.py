"""Whether a router's links to the routers it connects to are up, said when that changes.

Zenoh retries a ``connect`` endpoint silently, whether the other host is down, the link is cut,
or the other router refused this host's certificate; the user would see only a quiet graph.
:class:`LinkWatch` looks at the session's links twice a second and reports, per endpoint,
``linked to ...``, ``lost the link to ...``, and once, if it never came up,
``no link to ... yet``. A link is known by the other router's id and this side's socket, so a
router that restarts between two looks still shows as a lost link and a new one.
"""

from __future__ import annotations

import socket
import threading
from collections.abc import Callable, Sequence
from typing import Any

from launchkit.ros.endpoints import host_port

Report = Callable[[str, str], None]  # (level: "info" | "warn", message)
PERIOD = 0.5
FIRST_WARNING = 5.0  # seconds without a link before saying so


def _key(endpoint: str, host: str) -> tuple[str, str, int]:
    return endpoint.partition("/")[0], host, host_port(endpoint)[1]


def _keys(endpoint: str) -> set[tuple[str, str, int]]:
    """The (protocol, address, port) a link to ``endpoint`` may show (its name resolved)."""
    host, port = host_port(endpoint)
    keys = {_key(endpoint, host)}
    try:
        for *_, address in socket.getaddrinfo(host, port, type=socket.SOCK_STREAM):
            keys.add(_key(endpoint, str(address[0])))
    except OSError:
        pass
    return keys


class LinkWatch:
    """Follows the links of ``session`` to ``endpoints`` on a thread of its own."""

    def __init__(self, session: Any, endpoints: Sequence[str], report: Report) -> None:
        self._session = session
        self._wanted = {endpoint: _keys(endpoint) for endpoint in endpoints}
        self._report = report
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="launchkit-links", daemon=True)
        self._thread.start()

    def linked(self) -> set[str]:
        """The endpoints with a link up now."""
        return set(self._links())

    def _links(self) -> dict[str, frozenset[tuple[str, str]]]:
        """Per endpoint with a link up now, the (other router's id, local socket) of its links."""
        try:
            links = list(self._session.info.links())
        except Exception:  # the session closed under us
            return {}
        present: dict[tuple[str, str, int], set[tuple[str, str]]] = {}
        for link in links:
            try:
                host, _ = host_port(str(link.dst))
            except ValueError:
                continue
            identity = (str(getattr(link, "zid", "")), str(getattr(link, "src", "")))
            present.setdefault(_key(str(link.dst), host), set()).add(identity)
        found = {}
        for endpoint, keys in self._wanted.items():
            identities = frozenset().union(*(present.get(key, set()) for key in keys))
            if identities:
                found[endpoint] = identities
        return found

    def _run(self) -> None:
        up: dict[str, frozenset[tuple[str, str]]] = {}
        warned: set[str] = set()
        waited = 0.0
        while not self._stop.wait(PERIOD):
            waited += PERIOD
            links = self._links()
            now = set(links)
            # a link replaced between two looks (the other router restarted) was lost too
            renewed = {e for e in now & set(up) if not links[e] & up[e]}
            for endpoint in sorted((set(up) - now) | renewed):
                self._report("warn", f"lost the link to the router at {endpoint}; retrying")
            for endpoint in sorted((now - set(up)) | renewed):
                self._report("info", f"linked to the router at {endpoint}")
            if waited >= FIRST_WARNING:
                for endpoint in sorted(set(self._wanted) - now - set(up) - warned):
                    self._report(
                        "warn",
                        f"no link to the router at {endpoint} yet (not running, unreachable, "
                        "or its TLS refused this host's certificate, or this host its); retrying",
                    )
                    warned.add(endpoint)
            warned |= now
            up = links

    def close(self) -> None:
        """Stop watching."""
        self._stop.set()
        self._thread.join(timeout=2)
