"""Who may use the viewer server: Host and Origin rules (launchkit/stock/rviz2/access.py)."""

from __future__ import annotations

import socket

import pytest

from launchkit.stock.rviz2.access import AccessPolicy, split_host

LOOPBACK = AccessPolicy("127.0.0.1")
ALLOWING = AccessPolicy("127.0.0.1", ["https://app.foxglove.dev/", "http://robot.lan:8765"])
EVERYWHERE = AccessPolicy("0.0.0.0")


@pytest.mark.parametrize(
    ("value", "host"),
    [("127.0.0.1:8765", "127.0.0.1"), ("[::1]:80", "::1"), ("LocalHost", "localhost"), ("", "")],
)
def test_split_host(value: str, host: str) -> None:
    assert split_host(value) == host


@pytest.mark.parametrize(
    ("origin", "accepted"),
    [
        (None, True),  # not a web page
        ("http://127.0.0.1:8765", True),
        ("http://127.0.0.2", True),
        ("https://localhost:3000", True),
        ("http://[::1]:8765", True),
        ("http://viewer.localhost", True),
        ("http://evil.example", False),
        ("http://127.0.0.1.evil.example", False),
        ("https://app.foxglove.dev", False),
        ("null", False),
        ("file://", False),
        ("chrome-extension://abc", False),
    ],
)
def test_loopback_origins_only_by_default(origin: str | None, accepted: bool) -> None:
    assert LOOPBACK.origin_allowed(origin, "127.0.0.1:8765") is accepted


def test_configured_origins_are_accepted_and_star_accepts_any() -> None:
    assert ALLOWING.origin_allowed("https://app.foxglove.dev", "127.0.0.1:8765")
    assert not ALLOWING.origin_allowed("https://app.foxglove.dev.evil.example", "127.0.0.1:8765")
    assert AccessPolicy("127.0.0.1", ["*"]).origin_allowed("http://anything.example", None)


def test_hosts_other_than_this_machines_are_refused() -> None:
    """DNS rebinding: evil.example resolving to 127.0.0.1 must not reach the server."""
    assert LOOPBACK.host_allowed("127.0.0.1:8765") and LOOPBACK.host_allowed("localhost")
    assert not LOOPBACK.host_allowed("evil.example:8765")
    assert not LOOPBACK.host_allowed(None) and not LOOPBACK.host_allowed("")
    assert ALLOWING.host_allowed("robot.lan:8765")  # the host of an allowed origin
    assert LOOPBACK.loopback_only and not EVERYWHERE.loopback_only


def test_a_server_on_every_interface_serves_its_own_pages_by_address() -> None:
    assert EVERYWHERE.host_allowed("192.168.1.20:8765")
    assert EVERYWHERE.host_allowed(f"{socket.gethostname()}:8765")
    assert not EVERYWHERE.host_allowed("evil.example:8765")
    # the page it serves to another machine connects back with its own origin
    assert EVERYWHERE.origin_allowed("http://192.168.1.20:8765", "192.168.1.20:8765")
    assert not EVERYWHERE.origin_allowed("http://192.168.1.20:9999", "192.168.1.20:8765")
    assert not EVERYWHERE.origin_allowed("http://evil.example:8765", "evil.example:8765")
